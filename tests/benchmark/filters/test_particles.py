"""Properties of weighted particle sets (seeds/000, section 3.3, eqs. 3.10-3.11).

Weights are drawn over the whole positive float range, with zeros, subnormals
and values near the float maximum, because likelihoods of image measurements
span hundreds of orders of magnitude.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp

from benchmark.filters.particles import ParticleSet, effective_sample_size, normalise_weights

FLOAT_MAX = float(np.finfo(float).max)
TINIEST = 5e-324
QUICK = settings(max_examples=30, deadline=None)

WEIGHT_VALUES = st.one_of(
    st.just(0.0),
    st.floats(0.0, 1.0),
    st.floats(0.0, FLOAT_MAX),
    st.floats(TINIEST, 1e-300),
)

DECADES = {"unit": (-3.0, 0.0), "wide": (-323.0, 308.0), "tiny": (-323.0, -300.0), "huge": (300.0, 308.0)}


@st.composite
def raw_weights(
    draw: st.DrawFn,
    max_size: int = 500,
    values: st.SearchStrategy[float] = WEIGHT_VALUES,
    decades: tuple[str, ...] = tuple(DECADES),
) -> np.ndarray:
    """Finite non-negative weights, at least one positive, ``N`` in ``1..max_size``.

    The bulk comes from a seeded generator spanning a drawn range of decades
    (cheap for ``N`` in the hundreds); a few entries are then overwritten with
    values hypothesis picks and shrinks.
    """
    n = draw(st.integers(1, max_size))
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    low, high = DECADES[draw(st.sampled_from(decades))]
    weights = 10.0 ** rng.uniform(low, high, n)
    weights[rng.random(n) < draw(st.sampled_from([0.0, 0.5, 0.95]))] = 0.0
    for index, value in draw(st.lists(st.tuples(st.integers(0, n - 1), values), max_size=4)):
        weights[index] = value
    if draw(st.booleans()):
        weights[:] = draw(values)
    if not np.any(weights > 0):
        weights[draw(st.integers(0, n - 1))] = 10.0 ** rng.uniform(low, high)
    return weights


@st.composite
def states_for(draw: st.DrawFn, n: int, max_dim: int = 4) -> np.ndarray:
    """``(n, D)`` finite states of a drawn magnitude, some dimensions possibly constant."""
    d = draw(st.integers(1, max_dim))
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    states = rng.normal(draw(st.floats(-1e3, 1e3)), draw(st.sampled_from([0.0, 1e-6, 1.0, 1e3])), (n, d))
    cells = st.tuples(st.integers(0, n - 1), st.integers(0, d - 1), st.floats(-1e6, 1e6))
    for row, column, value in draw(st.lists(cells, max_size=3)):
        states[row, column] = value
    return states


@QUICK
@given(raw_weights())
def test_normalised_weights_are_finite_non_negative_and_sum_to_one(raw: np.ndarray) -> None:
    weights = normalise_weights(raw)
    assert weights.shape == raw.shape
    assert np.all(np.isfinite(weights))
    assert np.all(weights >= 0)
    assert math.isclose(math.fsum(weights), 1.0, abs_tol=1e-12)


@QUICK
@given(raw_weights())
def test_normalising_keeps_zeros_and_order(raw: np.ndarray) -> None:
    weights = normalise_weights(raw)
    assert np.all(weights[raw == 0] == 0)
    order = np.argsort(raw, kind="stable")
    assert np.all(np.diff(weights[order]) >= 0)
    assert weights[int(np.argmax(raw))] == weights.max() > 0


@QUICK
@given(raw_weights(values=st.one_of(st.just(0.0), st.floats(1e-100, 1e100)), decades=("unit",)), st.integers(-200, 200))
def test_normalising_ignores_the_scale(raw: np.ndarray, exponent: int) -> None:
    # Powers of two scale exactly, so the result must not change at all.
    scaled = raw * 2.0**exponent
    assert np.array_equal(normalise_weights(scaled), normalise_weights(raw))


@QUICK
@given(raw_weights(max_size=50, values=st.one_of(st.just(0.0), st.floats(1e-6, 1e6)), decades=("unit",)))
def test_normalised_weights_are_proportional_to_raw(raw: np.ndarray) -> None:
    weights = normalise_weights(raw)
    np.testing.assert_allclose(weights * math.fsum(raw), raw, rtol=1e-12, atol=0)


@QUICK
@given(st.integers(1, 500), st.one_of(st.just(0.0), st.floats(TINIEST, FLOAT_MAX)))
def test_all_equal_weights_become_uniform(n: int, value: float) -> None:
    weights = normalise_weights(np.full(n, value))
    assert not np.any(np.isnan(weights))
    np.testing.assert_allclose(weights, 1.0 / n, rtol=1e-14)


def test_huge_weights_do_not_overflow_into_uniform() -> None:
    weights = normalise_weights(np.array([FLOAT_MAX, FLOAT_MAX, 0.0, FLOAT_MAX / 2]))
    np.testing.assert_allclose(weights, [0.4, 0.4, 0.0, 0.2], rtol=1e-14)


@QUICK
@given(raw_weights(max_size=30), st.data())
def test_negative_or_non_finite_weights_are_rejected_by_index(raw: np.ndarray, data: st.DataObject) -> None:
    index = data.draw(st.integers(0, raw.size - 1))
    raw[index] = data.draw(st.sampled_from([-1.0, -TINIEST, -FLOAT_MAX, np.nan, np.inf, -np.inf]))
    with pytest.raises(ValueError, match=rf"weight {index} is"):
        normalise_weights(raw)


@pytest.mark.parametrize("raw", [np.array([]), np.ones((2, 3)), np.float64(1.0)])
def test_weights_must_be_a_non_empty_vector(raw: np.ndarray) -> None:
    with pytest.raises(ValueError, match="non-empty 1-D"):
        normalise_weights(raw)


@QUICK
@given(raw_weights())
def test_effective_sample_size_lies_between_one_and_n(raw: np.ndarray) -> None:
    n_eff = effective_sample_size(normalise_weights(raw))
    assert 1.0 - 1e-9 <= n_eff <= raw.size * (1.0 + 1e-9)


@QUICK
@given(st.integers(1, 500))
def test_effective_sample_size_of_uniform_weights_is_n(n: int) -> None:
    assert math.isclose(effective_sample_size(np.full(n, 1.0 / n)), n, rel_tol=1e-12)
    assert math.isclose(ParticleSet.equally_weighted(np.zeros((n, 2))).effective_size, n, rel_tol=1e-12)


@QUICK
@given(st.integers(1, 500), st.data())
def test_effective_sample_size_of_a_one_hot_is_one(n: int, data: st.DataObject) -> None:
    raw = np.zeros(n)
    raw[data.draw(st.integers(0, n - 1))] = data.draw(st.floats(TINIEST, FLOAT_MAX))
    assert effective_sample_size(normalise_weights(raw)) == 1.0


@QUICK
@given(raw_weights(max_size=200).flatmap(lambda raw: st.tuples(st.just(raw), states_for(raw.size))))
def test_mmse_lies_within_the_particle_range_per_dimension(case: tuple[np.ndarray, np.ndarray]) -> None:
    raw, states = case
    particles = ParticleSet(states, normalise_weights(raw))
    estimate = particles.mmse()
    assert estimate.shape == (states.shape[1],)
    tolerance = 1e-9 * max(1.0, float(np.abs(states).max()))
    assert np.all(estimate >= states.min(axis=0) - tolerance)
    assert np.all(estimate <= states.max(axis=0) + tolerance)


@QUICK
@given(raw_weights(max_size=100).flatmap(lambda raw: st.tuples(st.just(raw), states_for(raw.size))))
def test_best_is_a_particle_of_highest_weight(case: tuple[np.ndarray, np.ndarray]) -> None:
    raw, states = case
    particles = ParticleSet(states, normalise_weights(raw))
    holders = np.flatnonzero(np.all(states == particles.best(), axis=1))
    assert particles.weights[holders].max() == particles.weights.max()


@QUICK
@given(states_for(20), st.data())
def test_take_copies_the_chosen_states_with_equal_weights(states: np.ndarray, data: st.DataObject) -> None:
    indices = np.array(data.draw(st.lists(st.integers(-20, 19), min_size=1, max_size=40)))
    taken = ParticleSet.equally_weighted(states).take(indices)
    # Bit for bit the rows that indexing picks (negative indices count from the end).
    assert taken.states.tobytes() == states[indices].tobytes()
    np.testing.assert_allclose(taken.weights, 1.0 / indices.size, rtol=1e-15)


@QUICK
@given(st.integers(1, 20), st.integers(1, 4), st.integers(0, 20))
def test_mismatched_states_and_weights_are_rejected(n: int, d: int, m: int) -> None:
    if m != n:
        with pytest.raises(ValueError, match="do not match"):
            ParticleSet(np.zeros((n, d)), np.full(m, 1.0 / max(m, 1)))
    with pytest.raises(ValueError, match="do not match"):
        ParticleSet(np.zeros(n), np.full(n, 1.0 / n))
    with pytest.raises(ValueError, match="do not match"):
        ParticleSet(np.zeros((n, d, 1)), np.full(n, 1.0 / n))
    with pytest.raises(ValueError, match="do not match"):
        ParticleSet(np.zeros((n, d)), np.full((n, 1), 1.0 / n))


def test_an_empty_particle_set_is_rejected() -> None:
    with pytest.raises(ValueError, match="do not match"):
        ParticleSet(np.zeros((0, 2)), np.zeros(0))


@QUICK
@given(st.integers(1, 20), st.data())
def test_negative_or_nan_particle_weights_are_rejected(n: int, data: st.DataObject) -> None:
    weights = np.full(n, 1.0 / n)
    weights[data.draw(st.integers(0, n - 1))] = data.draw(st.sampled_from([-0.5, -TINIEST, np.nan, np.inf]))
    with pytest.raises(ValueError, match="finite and non-negative"):
        ParticleSet(np.zeros((n, 2)), weights)


@QUICK
@given(
    raw_weights(max_size=200).flatmap(lambda raw: st.tuples(st.just(raw), states_for(raw.size))),
    st.lists(st.floats(0.0, 1.0), min_size=1, max_size=5),
    st.data(),
)
def test_quantiles_are_particle_values_ordered_in_q(
    case: tuple[np.ndarray, np.ndarray], qs: list[float], data: st.DataObject
) -> None:
    raw, states = case
    dimension = data.draw(st.integers(0, states.shape[1] - 1))
    particles = ParticleSet(states, normalise_weights(raw))
    values = particles.quantiles(sorted(qs), dimension)
    assert values.shape == (len(qs),)
    assert np.all(np.diff(values) >= 0)
    assert np.all(np.isin(values, states[:, dimension]))
    assert values[0] >= particles.quantiles(0.0, dimension) and values[-1] <= particles.quantiles(1.0, dimension)


@QUICK
@given(states_for(25), st.integers(0, 24))
def test_quantiles_of_equal_weights_invert_the_empirical_distribution(states: np.ndarray, k: int) -> None:
    # Between two steps of the empirical distribution, clear of rounding in the cumulative sum.
    q = (k + 0.5) / 25
    particles = ParticleSet.equally_weighted(states)
    for dimension in range(states.shape[1]):
        expected = np.quantile(states[:, dimension], q, method="inverted_cdf")
        assert particles.quantiles(q, dimension) == expected


def test_quantiles_ignore_a_few_light_particles_far_off() -> None:
    states = np.r_[np.linspace(0.0, 1.0, 95), np.full(5, 1e6)][:, None]
    low, high, top = ParticleSet.equally_weighted(states).quantiles([0.16, 0.84, 1.0], 0)
    assert 0.0 <= low <= high <= 1.0 and top == 1e6


@pytest.mark.parametrize("q", [-0.1, 1.5, math.nan])
def test_a_quantile_outside_zero_to_one_is_rejected(q: float) -> None:
    with pytest.raises(ValueError, match="quantiles must be in"):
        ParticleSet.equally_weighted(np.zeros((3, 2))).quantiles([0.5, q], 1)


@settings(max_examples=150, deadline=None)
@given(st.data())
def test_quantiles_sum_the_weights_in_the_stable_order_whether_values_tie_or_not(data):
    n = data.draw(st.integers(1, 300))
    # Few distinct values force ties; continuous ones make them unlikely.
    column = st.one_of(st.integers(-3, 3).map(float), st.floats(-1e3, 1e3))
    values = data.draw(hnp.arrays(np.float64, n, elements=column))
    weights = normalise_weights(data.draw(hnp.arrays(np.float64, n, elements=st.floats(0.0, 10.0))))
    q = np.asarray(data.draw(st.lists(st.floats(0.0, 1.0), min_size=1, max_size=3)))
    order = np.argsort(values, kind="stable")
    cumulative = np.cumsum(weights[order])
    rows = np.minimum(np.searchsorted(cumulative, q * cumulative[-1], side="left"), n - 1)
    particles = ParticleSet(np.column_stack([values, -values]), weights)
    np.testing.assert_array_equal(particles.quantiles(q, 0), values[order[rows]])


@QUICK
@given(st.integers(1, 60), st.data())
def test_quantiles_with_and_without_ties_are_those_of_the_stable_order(n: int, data: st.DataObject) -> None:
    values = data.draw(hnp.arrays(np.float64, n, elements=st.sampled_from([-3.0, -0.0, 0.0, 1.5, 7.0])))
    raw = data.draw(hnp.arrays(np.float64, n, elements=st.floats(0.0, 10.0)))
    particles = ParticleSet(np.column_stack([values, values]), normalise_weights(raw + 1.0))
    q = np.array([0.0, 0.16, 0.5, 0.84, 1.0])
    order = np.argsort(values, kind="stable")
    cumulative = np.cumsum(particles.weights[order])
    rows = np.minimum(np.searchsorted(cumulative, q * cumulative[-1], side="left"), n - 1)
    np.testing.assert_array_equal(particles.quantiles(q, 0), values[order[rows]])
