"""The compiled target filter against the Kalman core's predict and update, and its invariants (seeds/002, Table 2)."""

from __future__ import annotations

import math

import numba
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from trackbench_stereo_ekf import filter_kernels
from trackbench_stereo_ekf.measurement import observation_jacobian, observe
from trackbench_stereo_ekf.motion import process_noise, propagate, transition_matrix
from trackbench_stereo_ekf.target_filter import NO_MEASUREMENT, TargetFilter, measurement_inputs

from benchmark.filters.kalman import Gaussian, predict, update
from benchmark.modalities.stereo.model import ChaseNavigation


def spd(rng: np.random.Generator, n: int, scale: float) -> np.ndarray:
    A = rng.normal(size=(n, n)) * math.sqrt(scale)
    return A @ A.T + 1e-3 * scale * np.eye(n)


runs = st.fixed_dictionaries(
    {
        "seed": st.integers(0, 2**32 - 1),
        "interval": st.floats(0.01, 2.0),
        "acceleration": st.floats(-0.5, 0.5),
        "sigma_a": st.floats(0.01, 3.0),
        "state_scale": st.integers(-3, 3).map(lambda e: 10.0**e),
        "noise_scale": st.integers(-4, 2).map(lambda e: 10.0**e),
        # per frame: 0 no measurement, 1 measured; and how many intervals it comes after the previous one
        "frames": st.lists(st.tuples(st.integers(0, 1), st.integers(1, 3)), min_size=1, max_size=8),
    }
)


def _frame(rng: np.random.Generator, noise_scale: float) -> tuple[np.ndarray, ChaseNavigation, np.ndarray]:
    navigation = ChaseNavigation((float(rng.normal(0, 50)), float(rng.normal(0, 50))), float(rng.uniform(-7, 7)))
    return rng.normal(0, 20, 2), navigation, spd(rng, 2, noise_scale)


@settings(max_examples=150, deadline=None)
@given(runs)
def test_the_compiled_step_is_the_kalman_core_bit_for_bit(run: dict) -> None:
    rng = np.random.default_rng(run["seed"])
    T, a, sigma_a = run["interval"], run["acceleration"], run["sigma_a"]
    belief = Gaussian(rng.normal(size=4) * math.sqrt(run["state_scale"]), spd(rng, 4, run["state_scale"]))
    compiled = TargetFilter(T, a, sigma_a)
    compiled.start(belief)
    for position, (measured, intervals) in enumerate(run["frames"]):
        if position > 0:  # the first frame corrects the starting belief itself
            interval = intervals * T
            motion = transition_matrix(interval), process_noise(interval, sigma_a)
            belief = predict(belief, lambda x: propagate(x, interval, a), *motion)
            if intervals != 1:
                compiled.predict_over(intervals)
        assert np.array_equal(compiled.ahead_mean, belief.mean)
        if measured:
            z, navigation, noise = _frame(rng, run["noise_scale"])
            prior = belief
            belief = update(belief, z, lambda x: observe(x, navigation), observation_jacobian(navigation), noise)
            compiled.advance(measurement_inputs(z, navigation, noise))
            assert np.array_equal(compiled.prior.mean, prior.mean)
            assert np.array_equal(compiled.prior.covariance, prior.covariance)
        else:
            compiled.advance(NO_MEASUREMENT)
        assert np.array_equal(compiled.belief.mean, belief.mean)
        assert np.array_equal(compiled.belief.covariance, belief.covariance)


@settings(max_examples=100, deadline=None)
@given(runs)
def test_covariances_stay_symmetric_and_positive_semi_definite(run: dict) -> None:
    rng = np.random.default_rng(run["seed"])
    compiled = TargetFilter(run["interval"], run["acceleration"], run["sigma_a"])
    compiled.start(Gaussian(rng.normal(size=4), spd(rng, 4, run["state_scale"])))
    for measured, intervals in run["frames"]:
        if intervals != 1:
            compiled.predict_over(intervals)
        compiled.advance(measurement_inputs(*_frame(rng, run["noise_scale"])) if measured else NO_MEASUREMENT)
        ahead = compiled.state[filter_kernels.AHEAD + 1 : filter_kernels.AHEAD + filter_kernels.BLOCK]
        for covariance in (compiled.belief.covariance, ahead):
            assert np.array_equal(covariance, covariance.T)
            scale = max(float(np.abs(covariance).max()), 1e-300)
            assert np.linalg.eigvalsh(covariance).min() >= -1e-9 * scale
        if measured:
            # a measurement never adds uncertainty: Sigma_bar - Sigma is positive semi-definite
            prior = compiled.prior.covariance
            gain = prior - compiled.belief.covariance
            assert np.linalg.eigvalsh(0.5 * (gain + gain.T)).min() >= -1e-9 * float(np.abs(prior).max())


def test_the_inputs_are_the_layout_the_kernel_reads() -> None:
    noise = np.array([[1.0, 0.2], [0.3, 4.0]])
    inputs = measurement_inputs(np.array([5.0, -1.0]), ChaseNavigation((2.0, 3.0), 0.5), noise)
    k = filter_kernels
    assert inputs.shape == NO_MEASUREMENT.shape == (k.INPUTS,)
    assert inputs[k.HAS_MEASUREMENT] == 1.0 and NO_MEASUREMENT[k.HAS_MEASUREMENT] == 0.0
    assert list(inputs[k.Z : k.Z + 2]) == [5.0, -1.0]
    assert list(inputs[k.CHASE_POSITION : k.CHASE_POSITION + 2]) == [2.0, 3.0]
    assert inputs[k.CHASE_HEADING] == 0.5
    assert list(inputs[k.NOISE_ENTRIES :]) == [1.0, 0.2, 0.3, 4.0]


def test_a_new_filter_has_its_kernels_compiled_for_every_call_its_steps_make(monkeypatch: pytest.MonkeyPatch) -> None:
    calls = []
    monkeypatch.setattr(filter_kernels, "compile_kernels", lambda: calls.append("compiled"))
    TargetFilter(0.2, 0.1, 0.4)
    assert calls == ["compiled"]
    monkeypatch.undo()
    steps = TargetFilter(0.2, 0.1, 0.4)
    steps.start(Gaussian(np.zeros(4), np.eye(4)))
    steps.predict()
    steps.advance(measurement_inputs(*_frame(np.random.default_rng(3), 1.0)))
    steps.advance(NO_MEASUREMENT)
    steps.predict_over(3)
    state, inputs = numba.typeof(steps.state), numba.typeof(NO_MEASUREMENT)
    # one compiled form each, the one compile_kernels made: no step of a filter compiles anything
    assert filter_kernels.predict_ahead.signatures == [(state,)]
    assert filter_kernels.advance.signatures == [(state, inputs)]


def test_a_bad_state_bad_inputs_or_a_singular_innovation_are_refused() -> None:
    compiled = TargetFilter(0.2, 0.0, 0.4)
    compiled.start(Gaussian(np.zeros(4), np.zeros((4, 4))))
    with pytest.raises(ValueError, match="wrong length"):
        compiled.advance(np.zeros(filter_kernels.INPUTS + 1))
    with pytest.raises(ValueError, match="not positive definite"):
        compiled.advance(measurement_inputs(np.zeros(2), ChaseNavigation((0.0, 0.0), 0.0), np.zeros((2, 2))))
    with pytest.raises(ValueError, match="wrong shape"):
        filter_kernels.advance(np.zeros((filter_kernels.ROWS - 1, 4)), NO_MEASUREMENT)
    with pytest.raises(ValueError, match="wrong shape"):
        filter_kernels.predict_ahead(np.zeros((filter_kernels.ROWS, 5)))
