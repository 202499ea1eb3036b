"""Properties of the four resampling schemes (seeds/000, section 3.4.1, eqs. 3.8-3.9).

Whatever the weights, a scheme returns ``N`` indices into the particles and
never picks a particle of weight exactly zero, also when the cumulative
weights round to a little below or above one.  Systematic resampling gives
each particle ``floor(N pi)`` or ``ceil(N pi)`` copies, residual resampling at
least ``floor(N pi)``, and on average every scheme gives ``N pi`` copies.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from benchmark.filters.resampling import (
    RESAMPLERS,
    multinomial_resample,
    residual_resample,
    stratified_resample,
    systematic_resample,
)

FLOAT_MAX = float(np.finfo(float).max)
TINIEST = 5e-324
BELOW_ONE = float(np.nextafter(1.0, 0.0))
QUICK = settings(max_examples=30, deadline=None)
BRIEF = settings(max_examples=15, deadline=None)
SCHEMES = sorted(RESAMPLERS)
PERMUTING = ["residual", "stratified", "systematic"]

WEIGHT_VALUES = st.one_of(
    st.just(0.0),
    st.floats(0.0, 1.0),
    st.floats(0.0, FLOAT_MAX),
    st.floats(TINIEST, 1e-300),
)

DECADES = {"unit": (-3.0, 0.0), "wide": (-323.0, 308.0), "tiny": (-323.0, -300.0), "huge": (300.0, 308.0)}


@st.composite
def raw_weights(draw: st.DrawFn, max_size: int = 500) -> np.ndarray:
    """Finite non-negative weights, at least one positive, ``N`` in ``1..max_size``, any scale.

    The bulk comes from a seeded generator spanning a drawn range of decades;
    a few entries are then overwritten with values hypothesis picks.
    """
    n = draw(st.integers(1, max_size))
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    low, high = DECADES[draw(st.sampled_from(sorted(DECADES)))]
    weights = 10.0 ** rng.uniform(low, high, n)
    weights[rng.random(n) < draw(st.sampled_from([0.0, 0.5, 0.95]))] = 0.0
    for index, value in draw(st.lists(st.tuples(st.integers(0, n - 1), WEIGHT_VALUES), max_size=4)):
        weights[index] = value
    if not np.any(weights > 0):
        weights[draw(st.integers(0, n - 1))] = 10.0 ** rng.uniform(low, high)
    return weights


@st.composite
def rounded_weights(draw: st.DrawFn) -> np.ndarray:
    """Nearly normalised weights whose cumulative sum misses one by round-off.

    Either weights normalised in float32 and cast to float64 (sum off by up to
    ~1e-7), or many tiny equal weights that sum to one only approximately;
    trailing zeros are appended so that a wrongly clamped last cumulative
    weight would pick a particle of weight zero.
    """
    n = draw(st.integers(1, 400))
    if draw(st.booleans()):
        rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
        single = rng.random(n).astype(np.float32) + np.float32(1e-3)
        weights = (single / single.sum(dtype=np.float32)).astype(np.float64)
    else:
        weights = np.full(n, 1.0 / n)
    return np.concatenate([weights, np.zeros(draw(st.integers(0, 3)))])


def proportions(weights: np.ndarray) -> np.ndarray:
    """``pi_i / sum(pi)``, with the sum taken exactly, as reference for the copy counts."""
    scaled = weights / weights.max()
    return scaled / math.fsum(scaled)


class PinnedUniforms:
    """Stands in for a generator whose ``random`` returns one fixed value.

    ``numpy.random.Generator.random`` returns multiples of 2**-53 in [0, 1),
    so 0 and ``1 - 2**-53`` are outputs a real generator can produce; this
    stub produces them on demand.
    """

    def __init__(self, value: float) -> None:
        self.value = value

    def random(self, size: int | None = None) -> float | np.ndarray:
        return self.value if size is None else np.full(size, self.value)


def check_indices(indices: np.ndarray, weights: np.ndarray) -> None:
    """``N`` integer indices in ``[0, N)``, none pointing at a particle of weight zero."""
    n = len(weights)
    assert indices.shape == (n,)
    assert np.issubdtype(indices.dtype, np.integer)
    assert np.all((indices >= 0) & (indices < n))
    assert np.all(weights[indices] > 0), f"weight-zero particles chosen: {sorted(set(indices[weights[indices] == 0]))}"


@QUICK
@pytest.mark.parametrize("scheme", SCHEMES)
@given(weights=raw_weights(), seed=st.integers(0, 2**32 - 1))
def test_indices_are_valid_and_avoid_zero_weights(scheme: str, weights: np.ndarray, seed: int) -> None:
    check_indices(RESAMPLERS[scheme](weights, np.random.default_rng(seed)), weights)


@QUICK
@pytest.mark.parametrize("scheme", SCHEMES)
@given(weights=rounded_weights(), seed=st.integers(0, 2**32 - 1))
def test_indices_survive_cumulative_round_off(scheme: str, weights: np.ndarray, seed: int) -> None:
    check_indices(RESAMPLERS[scheme](weights, np.random.default_rng(seed)), weights)


EDGE_WEIGHTS = {
    "tenths summing below one": np.array([0.1] * 10 + [0.0]),
    "halves": np.array([0.5, 0.5, 0.0]),
    "float32 thirds": np.concatenate([np.full(3, np.float32(1) / np.float32(3)).astype(np.float64), [0.0, 0.0]]),
    "sum above one": np.array([0.3, 0.3, 0.4000001, 0.0]),
    "unnormalised": np.array([0.25, 0.0, 0.25, 0.0]),
    "huge": np.array([FLOAT_MAX, 0.0, FLOAT_MAX, 0.0]),
    "tiny": np.array([TINIEST, TINIEST, 0.0, 3 * TINIEST, 0.0]),
}


@pytest.mark.parametrize("scheme", SCHEMES)
@pytest.mark.parametrize("case", sorted(EDGE_WEIGHTS))
def test_extreme_uniforms_never_pick_a_weight_zero_particle(scheme: str, case: str) -> None:
    weights = EDGE_WEIGHTS[case]
    for uniform in (0.0, 0.5, BELOW_ONE):
        check_indices(RESAMPLERS[scheme](weights, PinnedUniforms(uniform)), weights)


@QUICK
@given(weights=raw_weights(), seed=st.integers(0, 2**32 - 1))
def test_systematic_gives_floor_or_ceil_copies(weights: np.ndarray, seed: int) -> None:
    n = len(weights)
    counts = np.bincount(systematic_resample(weights, np.random.default_rng(seed)), minlength=n)
    expected = n * proportions(weights)
    assert np.all(counts >= np.floor(expected - 1e-9))
    assert np.all(counts <= np.ceil(expected + 1e-9))


@QUICK
@given(weights=raw_weights(), seed=st.integers(0, 2**32 - 1))
def test_residual_gives_at_least_floor_copies(weights: np.ndarray, seed: int) -> None:
    n = len(weights)
    counts = np.bincount(residual_resample(weights, np.random.default_rng(seed)), minlength=n)
    assert np.all(counts >= np.floor(n * proportions(weights) - 1e-9))


@QUICK
@pytest.mark.parametrize("scheme", PERMUTING)
@given(n=st.integers(1, 500), value=st.floats(TINIEST, FLOAT_MAX), seed=st.integers(0, 2**32 - 1))
def test_equal_weights_keep_every_particle_once(scheme: str, n: int, value: float, seed: int) -> None:
    for weights in (np.full(n, 1.0 / n), np.full(n, value)):
        indices = RESAMPLERS[scheme](weights, np.random.default_rng(seed))
        assert np.array_equal(np.sort(indices), np.arange(n))


def test_multinomial_equal_weights_leave_about_one_in_e_unchosen() -> None:
    # Each particle is missed with probability (1 - 1/N)^N ~ 1/e; the standard
    # deviation of the missed fraction is ~0.007 here, the tolerance 0.05.
    n = 4000
    indices = multinomial_resample(np.full(n, 1.0 / n), np.random.default_rng(20240611))
    missed = 1.0 - np.unique(indices).size / n
    assert abs(missed - (1.0 - 1.0 / n) ** n) < 0.05


UNBIASED_CASES = {
    "mixed": np.array([0.3, 0.0, 0.05, 0.2, 0.001, 0.149, 0.0, 0.3]),
    "dominant": np.array([0.9, 0.02, 0.02, 0.02, 0.02, 0.02]),
    "unnormalised": np.array([3.0, 1.0, 0.5, 0.0, 2.5, 1.0, 7.0]),
}


@pytest.mark.parametrize("scheme", SCHEMES)
@pytest.mark.parametrize("case", sorted(UNBIASED_CASES))
def test_mean_copy_count_is_n_times_the_weight(scheme: str, case: str) -> None:
    # Over 1000 draws the standard error of a mean count is below 0.045; the
    # tolerance of 0.25 is more than five of those, and the seed is fixed.
    weights = UNBIASED_CASES[case]
    n, draws = len(weights), 1000
    rng = np.random.default_rng(7)
    totals = np.zeros(n)
    for _ in range(draws):
        totals += np.bincount(RESAMPLERS[scheme](weights, rng), minlength=n)
    np.testing.assert_allclose(totals / draws, n * proportions(weights), rtol=0, atol=0.25)


@BRIEF
@pytest.mark.parametrize("scheme", SCHEMES)
@given(weights=raw_weights(max_size=100), seed=st.integers(0, 2**32 - 1))
def test_a_seed_replays_the_draw(scheme: str, weights: np.ndarray, seed: int) -> None:
    first = RESAMPLERS[scheme](weights, np.random.default_rng(seed))
    again = RESAMPLERS[scheme](weights, np.random.default_rng(seed))
    assert np.array_equal(first, again)


@BRIEF
@pytest.mark.parametrize("scheme", SCHEMES)
@given(
    weights=raw_weights(max_size=30),
    bad=st.sampled_from([-1.0, -TINIEST, np.nan, np.inf, -np.inf]),
    data=st.data(),
)
def test_negative_or_non_finite_weights_are_rejected(
    scheme: str, weights: np.ndarray, bad: float, data: st.DataObject
) -> None:
    weights[data.draw(st.integers(0, len(weights) - 1))] = bad
    with pytest.raises(ValueError, match="finite and non-negative"):
        RESAMPLERS[scheme](weights, np.random.default_rng(0))


@pytest.mark.parametrize("scheme", SCHEMES)
def test_empty_weights_are_rejected(scheme: str) -> None:
    with pytest.raises(ValueError, match="non-empty"):
        RESAMPLERS[scheme](np.array([]), np.random.default_rng(0))


def test_every_scheme_is_registered_by_name() -> None:
    assert RESAMPLERS == {
        "multinomial": multinomial_resample,
        "residual": residual_resample,
        "stratified": stratified_resample,
        "systematic": systematic_resample,
    }
