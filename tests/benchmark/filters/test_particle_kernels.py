"""The compiled particle-set loops give NumPy's numbers bit for bit (benchmark.filters.particle_kernels).

Each kernel replaces a chain of NumPy calls in the filters; the filters'
outputs stay the same only if every kernel computes exactly what the chain
did.  The references below are those chains, as the filters wrote them
before the kernels.
"""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp

from benchmark.filters import particle_kernels as kernels

BELOW_ONE = np.nextafter(1.0, 0.0)

weights = hnp.arrays(
    np.float64,
    st.integers(1, 700),
    elements=st.one_of(st.just(0.0), st.floats(0.0, 1e6), st.floats(0.0, 1e-300), st.floats(1e250, 1e300)),
)
"""Non-negative finite weights of many sizes and scales, zeros and extremes included."""


def reference_normalised(raw: np.ndarray) -> np.ndarray:
    peak = raw.max()
    if peak == 0:
        return np.full(raw.size, 1.0 / raw.size)
    scaled = raw / peak
    return scaled / scaled.sum()


def reference_cumulative(raw: np.ndarray) -> np.ndarray:
    cumulative = np.cumsum(reference_normalised(raw))
    return cumulative / cumulative[-1]


@settings(max_examples=200, deadline=None)
@given(weights)
def test_the_pairwise_sum_is_numpys_sum(values):
    assert kernels.pairwise_sum(values) == values.sum()


@settings(max_examples=30, deadline=None)
@given(st.integers(0, 2**32 - 1), st.integers(129, 40_000))
def test_the_pairwise_sum_of_long_arrays_is_numpys_sum(seed, n):
    values = np.random.default_rng(seed).random(n) ** 8
    assert kernels.pairwise_sum(values) == values.sum()


@settings(max_examples=200, deadline=None)
@given(weights)
def test_normalised_and_cumulative_weights_are_numpys(raw):
    np.testing.assert_array_equal(kernels.normalised(raw), reference_normalised(raw))
    np.testing.assert_array_equal(kernels.cumulative(raw), reference_cumulative(raw))


@settings(max_examples=200, deadline=None)
@given(weights, st.data())
def test_the_walk_finds_numpys_indices_for_sorted_and_unsorted_points(raw, data):
    n = raw.size
    sorted_points = (np.arange(n) + data.draw(st.floats(0.0, 1.0, exclude_max=True))) / n
    unsorted_points = data.draw(hnp.arrays(np.float64, n, elements=st.floats(0.0, 1.0)))
    for points in (sorted_points, unsorted_points, np.sort(unsorted_points)):
        expected = np.searchsorted(reference_cumulative(raw), np.minimum(points, BELOW_ONE), side="right")
        np.testing.assert_array_equal(kernels.walk(raw, points, BELOW_ONE), expected)
        assert np.all(kernels.walk(raw, points, BELOW_ONE) < n)


@settings(max_examples=200, deadline=None)
@given(weights, st.data())
def test_weighted_quantiles_are_numpys(raw, data):
    n = raw.size
    values = data.draw(hnp.arrays(np.float64, n, elements=st.floats(-1e3, 1e3)))
    q = np.asarray(data.draw(st.lists(st.floats(0.0, 1.0), min_size=1, max_size=4)))
    w = reference_normalised(raw)
    order = np.argsort(values, kind="stable")
    cumulative = np.cumsum(w[order])
    rows = np.minimum(np.searchsorted(cumulative, q * cumulative[-1], side="left"), n - 1)
    np.testing.assert_array_equal(kernels.weighted_quantiles(values, w, order, q), values[order[rows]])


@given(weights, st.data())
def test_the_first_invalid_weight_is_found(raw, data):
    assert kernels.first_invalid(raw) == -1
    bad = data.draw(st.integers(0, raw.size - 1))
    spoiled = raw.copy()
    spoiled[bad] = data.draw(st.sampled_from([-1.0, -1e-300, np.nan, np.inf, -np.inf]))
    assert kernels.first_invalid(spoiled) == bad


def reference_quantiles(values: np.ndarray, w: np.ndarray, q: np.ndarray) -> np.ndarray:
    """The quantiles as ``ParticleSet.quantiles`` found them before :func:`kernels.distinct_quantiles`."""
    order = np.argsort(values)
    ordered = values[order]
    if not np.all(ordered[1:] > ordered[:-1]):
        order = np.argsort(values, kind="stable")
    return kernels.weighted_quantiles(values, w, order, q)


@settings(max_examples=200, deadline=None)
@given(weights, st.data())
def test_quantiles_of_distinct_values_or_found_after_a_stable_sort_are_the_old_ones(raw, data):
    n = raw.size
    # Few distinct values give ties (-0.0 and 0.0 among them), NaN the unordered case.
    pool = data.draw(st.sampled_from([st.floats(-1e3, 1e3), st.sampled_from([-1.0, -0.0, 0.0, 2.0, np.nan])]))
    values = data.draw(hnp.arrays(np.float64, n, elements=pool))
    q = np.asarray(data.draw(st.lists(st.floats(0.0, 1.0), min_size=1, max_size=4)))
    w = reference_normalised(raw)
    found = kernels.distinct_quantiles(values, w, np.argsort(values), q)
    distinct = bool(np.all(np.sort(values)[1:] > np.sort(values)[:-1]))
    assert (found.size == q.size) == distinct
    if not distinct:
        found = kernels.weighted_quantiles(values, w, np.argsort(values, kind="stable"), q)
    np.testing.assert_array_equal(found, reference_quantiles(values, w, q))
