"""The belief protocols, the invariants of a belief and of an update, and the ``belief_invariants`` check on fakes."""

from __future__ import annotations

import re
import types
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp

from benchmark.model import Frame, SequenceInfo
from benchmark.registry import Registry
from benchmark.testing import CheckResult, check_tracker
from benchmark.filters.resampling import systematic_resample
from benchmark.testing.beliefs import (
    GaussianBelief,
    ParticleBelief,
    gaussian_belief_problems,
    gaussian_update_problems,
    particle_belief_problems,
    particle_update_problems,
)
from benchmark.tracker import Tracker

from .conftest import Steady

FINITE = st.floats(-1e3, 1e3, allow_nan=False, allow_infinity=False, allow_subnormal=False)


@st.composite
def particle_beliefs(draw: st.DrawFn) -> tuple[np.ndarray, np.ndarray]:
    """Finite particles ``(N, D)`` with non-negative weights normalised to sum to one."""
    n = draw(st.integers(1, 40))
    d = draw(st.integers(1, 4))
    particles = draw(hnp.arrays(float, (n, d), elements=FINITE))
    raw = draw(hnp.arrays(float, (n,), elements=st.floats(0.0, 1e6, allow_subnormal=False)))
    weights = np.full(n, 1.0 / n) if raw.sum() == 0 else raw / raw.sum()
    return particles, weights


@st.composite
def gaussian_beliefs(draw: st.DrawFn, min_dims: int = 1) -> tuple[np.ndarray, np.ndarray]:
    """A finite mean ``(D,)`` and a symmetric positive semi-definite covariance ``A A^T``."""
    d = draw(st.integers(min_dims, 5))
    mean = draw(hnp.arrays(float, (d,), elements=FINITE))
    factor = draw(hnp.arrays(float, (d, draw(st.integers(1, 5))), elements=st.floats(-10, 10, allow_subnormal=False)))
    covariance = factor @ factor.T
    return mean, 0.5 * (covariance + covariance.T)


def mentions(problems: list[str], words: str) -> bool:
    return any(words in problem for problem in problems)


# ---------------------------------------------------------------- particle beliefs


@given(particle_beliefs())
def test_a_valid_particle_belief_has_no_problems(belief: tuple[np.ndarray, np.ndarray]) -> None:
    assert particle_belief_problems(*belief) == []


@given(particle_beliefs(), st.data())
def test_a_negative_weight_is_reported(belief: tuple[np.ndarray, np.ndarray], data: st.DataObject) -> None:
    particles, weights = belief
    weights = weights.copy()
    weights[data.draw(st.integers(0, weights.size - 1))] = -data.draw(st.floats(1e-6, 1.0))
    assert mentions(particle_belief_problems(particles, weights), "negative")


@given(particle_beliefs(), st.floats(1.001, 100.0) | st.floats(1e-3, 0.999))
def test_unnormalised_weights_are_reported(belief: tuple[np.ndarray, np.ndarray], factor: float) -> None:
    particles, weights = belief
    assert mentions(particle_belief_problems(particles, weights * factor), "weights sum to")


@given(particle_beliefs(), st.data(), st.sampled_from([np.nan, np.inf, -np.inf]))
def test_a_particle_that_is_not_finite_is_reported(
    belief: tuple[np.ndarray, np.ndarray], data: st.DataObject, bad: float
) -> None:
    particles, weights = belief
    particles = particles.copy()
    particles[data.draw(st.integers(0, particles.shape[0] - 1)), data.draw(st.integers(0, particles.shape[1] - 1))] = (
        bad
    )
    assert mentions(particle_belief_problems(particles, weights), "particle coordinates are not finite")


@given(particle_beliefs(), st.data())
def test_a_nan_weight_is_reported(belief: tuple[np.ndarray, np.ndarray], data: st.DataObject) -> None:
    particles, weights = belief
    weights = weights.copy()
    weights[data.draw(st.integers(0, weights.size - 1))] = np.nan
    assert mentions(particle_belief_problems(particles, weights), "weights are not finite")


def test_mismatched_shapes_are_reported() -> None:
    assert mentions(particle_belief_problems(np.zeros((3, 2)), np.full(4, 0.25)), "do not match")
    assert mentions(particle_belief_problems(np.zeros(3), np.full(3, 1 / 3)), "shape (N, D)")
    assert mentions(particle_belief_problems(np.zeros((0, 2)), np.zeros(0)), "N >= 1")


def test_the_effective_sample_size_bounds_hold_at_the_extremes() -> None:
    assert particle_belief_problems(np.zeros((5, 1)), np.full(5, 0.2)) == []
    assert particle_belief_problems(np.zeros((5, 1)), np.array([1.0, 0, 0, 0, 0])) == []
    # Weights summing to one within the tolerance, but with more than N effective particles, cannot happen;
    # weights far from one are reported for the sum and, when they push it past N, for the size too.
    problems = particle_belief_problems(np.zeros((4, 1)), np.full(4, 0.1))
    assert mentions(problems, "weights sum to") and mentions(problems, "effective sample size")


# ---------------------------------------------------------------- Gaussian beliefs


@given(gaussian_beliefs())
def test_a_valid_gaussian_belief_has_no_problems(belief: tuple[np.ndarray, np.ndarray]) -> None:
    assert gaussian_belief_problems(*belief) == []


@given(gaussian_beliefs(min_dims=2), st.data())
def test_an_asymmetric_covariance_is_reported(belief: tuple[np.ndarray, np.ndarray], data: st.DataObject) -> None:
    mean, covariance = belief
    covariance = covariance.copy()
    i, j = data.draw(st.sampled_from([(i, j) for i in range(mean.size) for j in range(mean.size) if i != j]))
    covariance[i, j] += 1e-3 * max(1.0, float(np.max(np.abs(covariance))))
    assert mentions(gaussian_belief_problems(mean, covariance), "not symmetric")


@given(gaussian_beliefs(), st.data())
def test_a_negative_eigenvalue_is_reported(belief: tuple[np.ndarray, np.ndarray], data: st.DataObject) -> None:
    mean, covariance = belief
    axis = np.zeros(mean.size)
    axis[data.draw(st.integers(0, mean.size - 1))] = 1.0
    # Along this axis the variance becomes at most -1: an eigenvalue of at most -1.
    broken = covariance - (np.trace(covariance) + 1.0) * np.outer(axis, axis)
    assert mentions(gaussian_belief_problems(mean, broken), "not positive semi-definite")


@given(gaussian_beliefs(), st.data(), st.sampled_from([np.nan, np.inf]))
def test_a_gaussian_that_is_not_finite_is_reported(
    belief: tuple[np.ndarray, np.ndarray], data: st.DataObject, bad: float
) -> None:
    mean, covariance = belief
    if data.draw(st.booleans()):
        mean = mean.copy()
        mean[data.draw(st.integers(0, mean.size - 1))] = bad
        assert mentions(gaussian_belief_problems(mean, covariance), "mean entries are not finite")
    else:
        covariance = covariance.copy()
        covariance[data.draw(st.integers(0, mean.size - 1)), data.draw(st.integers(0, mean.size - 1))] = bad
        assert mentions(gaussian_belief_problems(mean, covariance), "covariance entries are not finite")


def test_mismatched_gaussian_shapes_are_reported() -> None:
    assert mentions(gaussian_belief_problems(np.zeros(3), np.eye(2)), "does not match")
    assert mentions(gaussian_belief_problems(np.zeros((3, 1)), np.eye(3)), "shape (D,)")


@settings(max_examples=20)
@given(gaussian_beliefs())
def test_the_tolerance_scales_with_the_covariance(belief: tuple[np.ndarray, np.ndarray]) -> None:
    mean, covariance = belief
    assert gaussian_belief_problems(mean, 1e12 * covariance) == []
    assert gaussian_belief_problems(mean, 1e-12 * covariance) == []


# ---------------------------------------------------------------- the check on fake trackers


class ParticleSteady(Steady):
    """Steady, with a particle belief around its state; the weights shift but stay normalised."""

    name = "particle-steady"

    def reset(self, info: SequenceInfo, rng: np.random.Generator, init: Any = None) -> None:
        super().reset(info, rng, init)
        self.frame_index = -1

    @property
    def particles(self) -> np.ndarray:
        return self.state.d + np.arange(8.0)[:, None]

    @property
    def weights(self) -> np.ndarray:
        raw = np.arange(1.0, 9.0) + max(self.frame_index, 0)
        return raw / raw.sum()

    def step(self, frame: Frame) -> Any:
        self.frame_index = frame.index
        return super().step(frame)


class BrokenWeights(ParticleSteady):
    """Its weights stop summing to one at frame 3."""

    name = "broken-weights"

    @property
    def weights(self) -> np.ndarray:
        weights = super().weights
        return 2.0 * weights if self.frame_index == 3 else weights


class GaussianSteady(Steady):
    """Steady, with a Gaussian belief of ``(d, w)``; None until its first step."""

    name = "gaussian-steady"

    def reset(self, info: SequenceInfo, rng: np.random.Generator, init: Any = None) -> None:
        super().reset(info, rng, init)
        self.stepped = False

    @property
    def mean(self) -> np.ndarray | None:
        return np.array([self.state.d, self.state.w]) if self.stepped else None

    @property
    def covariance(self) -> np.ndarray | None:
        return np.array([[2.0, 0.5], [0.5, 1.0]]) if self.stepped else None

    def step(self, frame: Frame) -> Any:
        self.stepped = True
        return super().step(frame)


class IndefiniteCovariance(GaussianSteady):
    """Its covariance has a negative eigenvalue from the first step."""

    name = "indefinite-covariance"

    @property
    def covariance(self) -> np.ndarray | None:
        return np.array([[1.0, 2.0], [2.0, 1.0]]) if self.stepped else None


class NegativeWhileLost(GaussianSteady):
    """Its variance of ``w`` goes negative while it sees nothing (a blank image), as a faulty coasting step might."""

    name = "negative-while-lost"

    def step(self, frame: Frame) -> Any:
        self.lost = not frame.observation.any()
        return super().step(frame)

    @property
    def covariance(self) -> np.ndarray | None:
        covariance = super().covariance
        return np.diag([2.0, -1e-3]) if covariance is not None and getattr(self, "lost", False) else covariance


@pytest.fixture
def registry(fakes: types.ModuleType) -> Registry:
    return fakes.make_registry()


def run_kit(tracker: type, registry: Registry, fakes: types.ModuleType) -> dict[str, CheckResult]:
    results = check_tracker(tracker, registry=registry, modality_data=fakes.FakeSequence("fake/S1", 10))
    return {result.check: result for result in results}


def failures(results: dict[str, CheckResult]) -> dict[str, str]:
    return {name: result.message for name, result in results.items() if not result.ok}


def started(tracker: type[Tracker]) -> Tracker:
    """An instance after reset: before it, the fakes' belief properties raise AttributeError."""
    instance = tracker()
    instance.reset(None, np.random.default_rng(0))  # type: ignore[arg-type]  # Steady ignores the info
    return instance


def test_the_fakes_satisfy_the_protocols() -> None:
    assert isinstance(started(ParticleSteady), ParticleBelief)
    assert not isinstance(started(ParticleSteady), GaussianBelief)
    assert isinstance(started(GaussianSteady), GaussianBelief)
    assert not isinstance(started(GaussianSteady), ParticleBelief)
    assert not isinstance(started(Steady), ParticleBelief | GaussianBelief)


def test_a_tracker_without_a_belief_skips_the_belief_check_saying_so(registry: Registry, fakes: types.ModuleType) -> None:
    results = run_kit(Steady, registry, fakes)
    assert failures(results) == {}
    assert results["belief_invariants"].outcome == "skipped"
    assert results["belief_invariants"].message.startswith("exposes no belief")


@pytest.mark.parametrize(
    ("tracker", "held"),
    [(ParticleSteady, "particle belief held at 44 of 44"), (GaussianSteady, "Gaussian belief held at 40 of 44")],
)
def test_a_sound_belief_passes_everything(
    tracker: type, held: str, registry: Registry, fakes: types.ModuleType
) -> None:
    results = run_kit(tracker, registry, fakes)
    assert failures(results) == {}
    assert results["belief_invariants"].detail.startswith(held)


@pytest.mark.parametrize(
    ("tracker", "words"),
    [
        (BrokenWeights, "at frame 3: weights sum to"),
        (IndefiniteCovariance, "at frame 0: covariance is not positive"),
        (NegativeWhileLost, "at frame 3, 'blank' observations in frames 3-6: covariance has negative variances: component 1"),
    ],
)
def test_a_broken_belief_fails_exactly_belief_invariants(
    tracker: type, words: str, registry: Registry, fakes: types.ModuleType
) -> None:
    failed = failures(run_kit(tracker, registry, fakes))
    assert list(failed) == ["belief_invariants"]
    assert f"tracker {tracker.name!r}" in failed["belief_invariants"]
    assert words in failed["belief_invariants"]


def test_float32_weights_normalised_in_float32_keep_their_invariants() -> None:
    rng = np.random.default_rng(3)
    for n in (10, 1000, 100_000):
        weights = rng.random(n).astype(np.float32)
        weights /= weights.sum(dtype=np.float32)
        assert particle_belief_problems(np.zeros((n, 2), np.float32), weights) == []


def test_float64_weights_are_held_to_the_float64_tolerance() -> None:
    weights = np.full(1000, 1e-3)
    weights[0] += 1e-7
    [problem] = particle_belief_problems(np.zeros((1000, 2)), weights)
    assert problem.startswith("weights sum to") and "within 1e-09" in problem


def test_a_negative_variance_of_a_small_component_does_not_hide_behind_a_large_one() -> None:
    covariance = np.diag([1e6, -1e-6])
    problems = gaussian_belief_problems(np.zeros(2), covariance)
    assert any("negative variances: component 1" in problem for problem in problems), problems
    assert any("not positive semi-definite" in problem for problem in problems), problems


def test_the_textbook_kalman_update_passes() -> None:
    rng = np.random.default_rng(5)
    for _ in range(50):
        a = rng.normal(size=(4, 4))
        prior = a @ a.T + np.diag([1e4, 1.0, 1e-4, 1e-2])
        h = rng.normal(size=(2, 4))
        gain = prior @ h.T @ np.linalg.inv(h @ prior @ h.T + np.eye(2) * 1e-3)
        posterior = (np.eye(4) - gain @ h) @ prior  # not symmetrised, as textbooks write it
        assert gaussian_belief_problems(np.zeros(4), posterior) == [], posterior


# ---------------------------------------------------------------- Gaussian updates


def unit(elements: float = 1.0) -> st.SearchStrategy[float]:
    return st.floats(-elements, elements, allow_subnormal=False)


@st.composite
def kalman_problems(draw: st.DrawFn) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """A prior ``P``, a measurement matrix ``H`` and noise ``R``, on components of scales ``1e-6`` to ``1e6``.

    ``P = T P0 T`` and ``H = H0 T^-1`` with ``P0 = A A^T + c I`` and ``R =
    B B^T + r I`` of entries at most 1, ``c, r >= 0.1``: the innovation
    covariance ``H0 P0 H0^T + R`` is conditioned well enough for float32
    (below ``1e4``), while the components' scales spread over twelve decades.
    """
    d = draw(st.integers(1, 5))
    m = draw(st.integers(1, d))
    factor = draw(hnp.arrays(float, (d, draw(st.integers(1, 5))), elements=unit()))
    prior0 = factor @ factor.T + draw(st.floats(0.1, 1.0)) * np.eye(d)
    noise = draw(hnp.arrays(float, (m, m), elements=unit()))
    scales = 10.0 ** draw(hnp.arrays(float, (d,), elements=st.floats(-6.0, 6.0)))
    observe0 = draw(hnp.arrays(float, (m, d), elements=unit()))
    prior = scales[:, None] * prior0 * scales[None, :]
    return prior, observe0 / scales[None, :], noise @ noise.T + draw(st.floats(0.1, 1.0)) * np.eye(m)


def gain(prior: np.ndarray, observe: np.ndarray, noise: np.ndarray) -> np.ndarray:
    """``K = P H^T (H P H^T + R)^-1``, in the dtype of its inputs."""
    return np.linalg.solve(observe @ prior @ observe.T + noise, observe @ prior).T


def textbook(prior: np.ndarray, observe: np.ndarray, noise: np.ndarray) -> np.ndarray:
    """``(I - K H) P``, as seeds/002 Table 2 line 6 and seeds/004 eq. (16c) write it: not symmetric to the last bit."""
    return (np.eye(len(prior), dtype=prior.dtype) - gain(prior, observe, noise) @ observe) @ prior


def joseph(prior: np.ndarray, observe: np.ndarray, noise: np.ndarray) -> np.ndarray:
    """``(I - K H) P (I - K H)^T + K R K^T``."""
    k = gain(prior, observe, noise)
    keep = np.eye(len(prior), dtype=prior.dtype) - k @ observe
    return keep @ prior @ keep.T + k @ noise @ k.T


UPDATES = [textbook, joseph]


@given(kalman_problems(), st.sampled_from(UPDATES), st.sampled_from([np.float64, np.float32]))
def test_a_kalman_update_never_widens_its_prior(
    problem: tuple[np.ndarray, np.ndarray, np.ndarray], form: Callable[..., np.ndarray], dtype: type
) -> None:
    prior, observe, noise = (array.astype(dtype) for array in problem)
    posterior = form(prior, observe, noise)
    assert posterior.dtype == dtype
    assert gaussian_update_problems(prior, posterior) == []


@given(kalman_problems())
def test_a_step_without_a_measurement_keeps_its_prior(problem: tuple[np.ndarray, np.ndarray, np.ndarray]) -> None:
    prior = problem[0]
    assert gaussian_update_problems(prior, prior.copy()) == []
    assert gaussian_update_problems(prior.astype(np.float32), prior.astype(np.float32)) == []


def leading_component(problems: list[str]) -> int:
    [problem] = problems
    found = re.search(r"component (\d+) leading", problem)
    assert found is not None, problem
    return int(found.group(1))


@st.composite
def widened(draw: st.DrawFn) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """A prior, a posterior ``P + v v^T`` and ``v`` on the prior's scales (``v_i / sqrt(P_ii)``, at least 0.1 long)."""
    prior = draw(kalman_problems())[0]
    direction = draw(hnp.arrays(float, (len(prior),), elements=unit()))
    assume(np.linalg.norm(direction) > 0.1)
    spread = np.sqrt(np.diag(prior))
    v = spread * direction
    return prior, prior + np.outer(v, v), direction


@given(widened())
def test_a_posterior_wider_than_its_prior_is_named(case: tuple[np.ndarray, np.ndarray, np.ndarray]) -> None:
    prior, posterior, direction = case
    problems = gaussian_update_problems(prior, posterior)
    assert problems and problems[0].startswith("the update widened the belief")
    lead = leading_component(problems)
    assert abs(direction[lead]) >= (1.0 - 1e-9) * np.max(np.abs(direction))
    assert f"variance of component {lead} grew from" in problems[0]


def rescaling(dims: int, data: st.DataObject) -> np.ndarray:
    """``s s^T`` for a scale ``s_i`` of each component from ``1e-6`` to ``1e6``: multiplied in, it rescales."""
    scales = 10.0 ** data.draw(hnp.arrays(float, (dims,), elements=st.floats(-6.0, 6.0)))
    return np.outer(scales, scales)


@given(kalman_problems(), st.data())
def test_a_sound_update_passes_on_any_scale_of_its_components(
    problem: tuple[np.ndarray, np.ndarray, np.ndarray], data: st.DataObject
) -> None:
    prior, observe, noise = problem
    rescale = rescaling(len(prior), data)
    assert gaussian_update_problems(prior * rescale, joseph(prior, observe, noise) * rescale) == []


@given(widened(), st.data())
def test_a_widened_update_fails_on_any_scale_of_its_components(
    case: tuple[np.ndarray, np.ndarray, np.ndarray], data: st.DataObject
) -> None:
    prior, posterior, direction = case
    rescale = rescaling(len(prior), data)
    lead = leading_component(gaussian_update_problems(prior * rescale, posterior * rescale))
    assert abs(direction[lead]) >= (1.0 - 1e-9) * np.max(np.abs(direction))


def test_a_widened_small_component_does_not_hide_behind_a_large_one() -> None:
    prior = np.diag([1e8, 1e-8])
    posterior = np.diag([1e8 - 1.0, 2e-8])
    [problem] = gaussian_update_problems(prior, posterior)
    assert "component 1 leading" in problem and "variance of component 1 grew from 1e-08 to 2e-08" in problem


def test_a_grown_correlation_is_named_by_its_direction() -> None:
    prior = np.eye(2)
    posterior = np.array([[1.0, 0.5], [0.5, 1.0]])  # no variance grew, but along (1, 1) the spread did
    [problem] = gaussian_update_problems(prior, posterior)
    assert "along (0.71, 0.71)" in problem and "by 0.5 of its scale" in problem and "variance" not in problem


def test_bad_update_inputs_are_named() -> None:
    assert mentions(gaussian_update_problems(np.eye(3), np.eye(2)), "posterior covariance of shape (2, 2) does not")
    assert mentions(gaussian_update_problems(np.zeros(3), np.zeros(3)), "prior covariance must have shape (D, D)")
    assert mentions(gaussian_update_problems(np.diag([1.0, np.nan]), np.eye(2)), "prior covariance entries are not")
    assert mentions(gaussian_update_problems(np.eye(2), [[1, 0], [0, "x"]]), "posterior covariance is not an array")


# ---------------------------------------------------------------- particle updates


@st.composite
def predicted_sets(draw: st.DrawFn, dtype: type = float) -> tuple[np.ndarray, np.ndarray]:
    """Predicted particles ``(N, D)`` of ``dtype`` and normalised weights."""
    particles, weights = draw(particle_beliefs())
    return particles.astype(dtype), weights


@given(predicted_sets() | predicted_sets(np.float32), st.booleans(), st.integers(0, 2**32 - 1))
def test_weighing_and_resampling_keep_every_particle_of_the_predicted_set(
    belief: tuple[np.ndarray, np.ndarray], resample: bool, seed: int
) -> None:
    particles, weights = belief
    posterior = particles[systematic_resample(weights, np.random.default_rng(seed))] if resample else particles.copy()
    assert particle_update_problems(particles, posterior) == []


@given(predicted_sets(), st.data())
def test_a_particle_the_update_moved_is_named(belief: tuple[np.ndarray, np.ndarray], data: st.DataObject) -> None:
    particles, _ = belief
    posterior = particles.copy()
    row, column = data.draw(st.integers(0, len(particles) - 1)), data.draw(st.integers(0, particles.shape[1] - 1))
    posterior[row, column] = np.nextafter(posterior[row, column], np.inf)  # by the least a float can move
    assume(not (particles == posterior[row]).all(axis=1).any())
    [problem] = particle_update_problems(particles, posterior)
    assert problem.startswith(f"the update moved particles: 1 of {len(particles)} are not particles of the predicted")
    assert f"(particle {row} is (" in problem


def test_a_signed_zero_is_the_same_particle() -> None:
    assert particle_update_problems(np.array([[0.0, 1.0]]), np.array([[-0.0, 1.0], [0.0, 1.0]])) == []


def test_bad_particle_update_inputs_are_named() -> None:
    assert mentions(particle_update_problems(np.zeros((3, 2)), np.zeros((3, 1))), "do not match prior particles")
    assert mentions(particle_update_problems(np.zeros((0, 2)), np.zeros((3, 2))), "N >= 1")
    assert mentions(particle_update_problems(np.zeros(3), np.zeros((3, 1))), "shape (N, D)")
