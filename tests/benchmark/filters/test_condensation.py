"""Properties of the condensation step (seeds/000, section 3.4 and Fig. 4.10).

The step resamples only when the effective sample size falls below
``ess_fraction * N`` (the text of section 3.4.1), drifts and diffuses with the
movement model and weighs with the observation model; its weights are always
a proper distribution and a seed replays it bit for bit.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp

from benchmark.filters.condensation import Condensation, LinearDriftDiffusion
from benchmark.filters.particles import ParticleSet
from benchmark.filters.resampling import RESAMPLERS, systematic_resample

FLOAT_MAX = float(np.finfo(float).max)
TINIEST = 5e-324
QUICK = settings(max_examples=30, deadline=None)

DECADES = {"unit": (-3.0, 0.0), "wide": (-323.0, 308.0), "tiny": (-323.0, -300.0), "huge": (300.0, 308.0)}


@st.composite
def likelihoods(draw: st.DrawFn, n: int) -> np.ndarray:
    """``n`` finite non-negative likelihoods of any scale: zeros, subnormals, near the float maximum, all equal."""
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    low, high = DECADES[draw(st.sampled_from(sorted(DECADES)))]
    values = 10.0 ** rng.uniform(low, high, n)
    values[rng.random(n) < draw(st.sampled_from([0.0, 0.5, 0.95, 1.0]))] = 0.0
    if draw(st.booleans()):
        values[:] = draw(st.one_of(st.just(0.0), st.floats(TINIEST, FLOAT_MAX)))
    return values


@st.composite
def particle_sets(draw: st.DrawFn, max_size: int = 200, dim: int = 2) -> ParticleSet:
    """Particles with normalised weights ranging from uniform to one-hot."""
    n = draw(st.integers(1, max_size))
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    states = rng.normal(0.0, draw(st.sampled_from([0.0, 1.0, 100.0])), (n, dim))
    raw = rng.random(n) ** draw(st.sampled_from([0.0, 1.0, 10.0, 100.0]))
    if draw(st.booleans()):
        raw[:] = 0.0
        raw[draw(st.integers(0, n - 1))] = 1.0
    if raw.sum() == 0.0:  # a high power of few uniforms can underflow to all zeros
        raw[0] = 1.0
    return ParticleSet(states, raw / raw.sum())


class FixedLikelihood:
    """Observation model returning the given values whatever the states."""

    def __init__(self, values: np.ndarray) -> None:
        self.values = values

    def likelihood(self, states: np.ndarray, observation: Any) -> np.ndarray:
        return self.values.copy()


class GaussianLikelihood:
    """Observation model peaked at the observed state, as a tracker's would be."""

    def likelihood(self, states: np.ndarray, observation: np.ndarray) -> np.ndarray:
        return np.exp(-0.5 * np.sum((states - observation) ** 2, axis=1))


class CountingResampler:
    """Systematic resampling that counts its calls."""

    def __init__(self) -> None:
        self.calls = 0

    def __call__(self, weights: np.ndarray, rng: np.random.Generator) -> np.ndarray:
        self.calls += 1
        return systematic_resample(weights, rng)


def still(dim: int) -> LinearDriftDiffusion:
    """Movement that leaves every particle where it is."""
    return LinearDriftDiffusion(np.eye(dim), np.zeros(dim))


def proportions(raw: np.ndarray) -> np.ndarray:
    """``raw / sum(raw)`` with the sum taken exactly."""
    scaled = raw / raw.max()
    return scaled / math.fsum(scaled)


def assert_distribution(weights: np.ndarray) -> None:
    assert np.all(np.isfinite(weights))
    assert np.all(weights >= 0)
    assert math.isclose(math.fsum(weights), 1.0, abs_tol=1e-12)


@QUICK
@given(
    particles=particle_sets(),
    carry=st.booleans(),
    scheme=st.sampled_from(sorted(RESAMPLERS)),
    seed=st.integers(0, 2**32 - 1),
    data=st.data(),
)
def test_weights_after_a_step_are_a_distribution(
    particles: ParticleSet, carry: bool, scheme: str, seed: int, data: st.DataObject
) -> None:
    values = data.draw(likelihoods(particles.size))
    movement = LinearDriftDiffusion(np.eye(2), np.array([0.1, 0.0]))
    filt = Condensation(movement, FixedLikelihood(values), RESAMPLERS[scheme], carry_weights=carry)
    stepped = filt.step(particles, None, np.random.default_rng(seed))
    assert stepped.states.shape == particles.states.shape
    assert_distribution(stepped.weights)
    if not carry and np.any(values > 0):
        np.testing.assert_allclose(stepped.weights, proportions(values), rtol=1e-12, atol=1e-300)


@QUICK
@given(
    particles=particle_sets(max_size=500),
    epsilon=st.one_of(
        st.sampled_from([0.0, TINIEST, 1e-300]), st.floats(TINIEST, 1e-290), st.floats(1e-290, FLOAT_MAX)
    ),
    seed=st.integers(0, 2**32 - 1),
)
def test_an_all_epsilon_measurement_gives_uniform_weights(particles: ParticleSet, epsilon: float, seed: int) -> None:
    filt = Condensation(still(2), FixedLikelihood(np.full(particles.size, epsilon)), carry_weights=False)
    weights = filt.step(particles, None, np.random.default_rng(seed)).weights
    assert not np.any(np.isnan(weights))
    np.testing.assert_allclose(weights, 1.0 / particles.size, rtol=1e-12)


@QUICK
@given(
    states=st.integers(1, 50).flatmap(
        lambda n: st.integers(1, 4).flatmap(
            lambda d: hnp.arrays(np.float64, (n, d), elements=st.floats(-1e3, 1e3))
        )
    ),
    seeds=st.tuples(st.integers(0, 2**32 - 1), st.integers(0, 2**32 - 1)),
    data=st.data(),
)
def test_zero_diffusion_drifts_deterministically(
    states: np.ndarray, seeds: tuple[int, int], data: st.DataObject
) -> None:
    d = states.shape[1]
    transition = data.draw(hnp.arrays(np.float64, (d, d), elements=st.floats(-10, 10)))
    movement = LinearDriftDiffusion(transition, np.zeros(d))
    first = movement.propagate(states, np.random.default_rng(seeds[0]))
    second = movement.propagate(states, np.random.default_rng(seeds[1]))
    assert np.array_equal(first, states @ transition.T)
    assert np.array_equal(first, second)


@QUICK
@given(n=st.integers(2, 50), seeds=st.tuples(st.integers(0, 2**32 - 1), st.integers(0, 2**32 - 1)))
def test_only_dimensions_with_noise_diffuse(n: int, seeds: tuple[int, int]) -> None:
    assume(seeds[0] != seeds[1])
    movement = LinearDriftDiffusion(np.eye(3), np.array([0.0, 0.5, 0.0]))
    states = np.arange(3.0 * n).reshape(n, 3)
    first = movement.propagate(states, np.random.default_rng(seeds[0]))
    second = movement.propagate(states, np.random.default_rng(seeds[1]))
    assert np.array_equal(first[:, [0, 2]], states[:, [0, 2]])
    assert not np.array_equal(first[:, 1], second[:, 1])


def run(seed: int, steps: int, scheme: str, carry: bool, n: int = 64) -> list[ParticleSet]:
    """A few condensation steps following a target that moves right."""
    rng = np.random.default_rng(seed)
    movement = LinearDriftDiffusion(np.array([[1.0, 1.0], [0.0, 1.0]]), np.array([0.3, 0.1]))
    filt = Condensation(movement, GaussianLikelihood(), RESAMPLERS[scheme], carry_weights=carry)
    particles = ParticleSet.equally_weighted(rng.normal(0.0, 2.0, (n, 2)))
    history = []
    for t in range(steps):
        particles = filt.step(particles, np.array([float(t), 1.0]), rng)
        history.append(particles)
    return history


@settings(max_examples=15, deadline=None)
@given(
    seed=st.integers(0, 2**32 - 1),
    other=st.integers(0, 2**32 - 1),
    steps=st.integers(2, 6),
    scheme=st.sampled_from(sorted(RESAMPLERS)),
    carry=st.booleans(),
)
def test_a_seed_replays_a_run_bit_for_bit(seed: int, other: int, steps: int, scheme: str, carry: bool) -> None:
    assume(seed != other)
    first, again, different = (run(s, steps, scheme, carry) for s in (seed, seed, other))
    for a, b in zip(first, again, strict=True):
        assert np.array_equal(a.states, b.states)
        assert np.array_equal(a.weights, b.weights)
    assert not np.array_equal(first[-1].states, different[-1].states)


@QUICK
@given(particles=particle_sets(), carry=st.booleans(), fraction=st.floats(0.0, 1.0), seed=st.integers(0, 2**32 - 1))
def test_a_step_is_its_prediction_weighed_and_the_weighing_moves_nothing(
    particles: ParticleSet, carry: bool, fraction: float, seed: int
) -> None:
    movement = LinearDriftDiffusion(np.eye(2), np.ones(2))
    filt = Condensation(movement, GaussianLikelihood(), ess_fraction=fraction, carry_weights=carry)
    stepped = filt.step(particles, np.zeros(2), np.random.default_rng(seed))
    predicted = filt.predict(particles, np.random.default_rng(seed))
    weighed = filt.update(predicted, np.zeros(2))
    assert np.array_equal(weighed.states, stepped.states) and np.array_equal(weighed.weights, stepped.weights)
    assert weighed.states is predicted.states


@QUICK
@given(n=st.integers(1, 500), fraction=st.floats(0.0, 0.999), seed=st.integers(0, 2**32 - 1))
def test_a_uniform_set_is_not_resampled(n: int, fraction: float, seed: int) -> None:
    resampler = CountingResampler()
    filt = Condensation(still(2), FixedLikelihood(np.ones(n)), resampler, ess_fraction=fraction)
    filt.step(ParticleSet.equally_weighted(np.zeros((n, 2))), None, np.random.default_rng(seed))
    assert not filt.resampled
    assert resampler.calls == 0


@QUICK
@given(n=st.integers(3, 500), seed=st.integers(0, 2**32 - 1), data=st.data())
def test_a_degenerate_set_is_resampled_onto_its_heavy_particle(n: int, seed: int, data: st.DataObject) -> None:
    heavy = data.draw(st.integers(0, n - 1))
    weights = np.zeros(n)
    weights[heavy] = 1.0
    states = np.random.default_rng(seed).normal(size=(n, 2))
    resampler = CountingResampler()
    filt = Condensation(still(2), FixedLikelihood(np.ones(n)), resampler)
    stepped = filt.step(ParticleSet(states, weights), None, np.random.default_rng(seed))
    assert filt.resampled
    assert resampler.calls == 1
    assert np.array_equal(stepped.states, np.repeat(states[[heavy]], n, axis=0))


@QUICK
@given(particles=particle_sets(), fraction=st.floats(0.0, 1.0), seed=st.integers(0, 2**32 - 1))
def test_resampling_happens_exactly_below_the_threshold(particles: ParticleSet, fraction: float, seed: int) -> None:
    n_eff = 1.0 / float(np.sum(particles.weights**2))
    assume(abs(n_eff - fraction * particles.size) > 1e-9 * particles.size)
    resampler = CountingResampler()
    filt = Condensation(still(2), FixedLikelihood(np.ones(particles.size)), resampler, ess_fraction=fraction)
    stepped = filt.step(particles, None, np.random.default_rng(seed))
    assert filt.resampled == (n_eff < fraction * particles.size)
    assert resampler.calls == int(filt.resampled)
    if not filt.resampled:
        assert np.array_equal(stepped.states, particles.states)


@QUICK
@given(particles=particle_sets(), seed=st.integers(0, 2**32 - 1), data=st.data())
def test_carried_weights_multiply_the_previous_ones(particles: ParticleSet, seed: int, data: st.DataObject) -> None:
    values = data.draw(likelihoods(particles.size).filter(lambda v: bool(np.any(v > 0))))
    product = particles.weights * values
    assume(np.any(product > 0))
    filt = Condensation(still(2), FixedLikelihood(values), ess_fraction=0.0, carry_weights=True)
    stepped = filt.step(particles, None, np.random.default_rng(seed))
    assert_distribution(stepped.weights)
    np.testing.assert_allclose(stepped.weights, proportions(product), rtol=1e-12, atol=1e-300)


@pytest.mark.parametrize(
    ("transition", "noise_std"),
    [
        (np.eye(2), np.zeros(3)),
        (np.eye(3), np.zeros(2)),
        (np.zeros((2, 3)), np.zeros(2)),
        (np.zeros(2), np.zeros(2)),
        (np.zeros((2, 2, 2)), np.zeros(2)),
        (np.eye(2), np.zeros((2, 1))),
        (np.eye(4), np.zeros((2, 2))),
    ],
    ids=["noise-too-long", "noise-too-short", "not-square", "vector", "cube", "noise-column", "noise-matrix"],
)
def test_bad_linear_drift_diffusion_shapes_are_rejected(transition: np.ndarray, noise_std: np.ndarray) -> None:
    with pytest.raises(ValueError, match="does not match"):
        LinearDriftDiffusion(transition, noise_std)


@pytest.mark.parametrize("noise_std", [[0.1, -0.1], [np.nan, 0.0], [np.inf, 0.0]])
def test_negative_or_non_finite_noise_is_rejected(noise_std: list[float]) -> None:
    with pytest.raises(ValueError, match="noise_std"):
        LinearDriftDiffusion(np.eye(2), np.array(noise_std))


@pytest.mark.parametrize(
    "states", [np.zeros((5, 3)), np.zeros(5), np.zeros((5, 2, 1))], ids=["width", "vector", "cube"]
)
def test_states_of_the_wrong_shape_cannot_propagate(states: np.ndarray) -> None:
    with pytest.raises(ValueError, match=r"states must have shape \(N, 2\)"):
        still(2).propagate(states, np.random.default_rng(0))


@pytest.mark.parametrize("bad", [-1.0, np.nan, np.inf])
def test_a_bad_likelihood_is_rejected(bad: float) -> None:
    values = np.ones(4)
    values[2] = bad
    filt = Condensation(still(1), FixedLikelihood(values))
    with pytest.raises(ValueError, match="weight 2 is"):
        filt.step(ParticleSet.equally_weighted(np.zeros((4, 1))), None, np.random.default_rng(0))
