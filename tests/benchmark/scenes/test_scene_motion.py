"""Trajectories and the vehicle speeds of seeds/004 eqs. (7) and (12)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from benchmark.scenes.motion import (
    build_trajectory,
    evaluate_signal,
    psi_matrix,
    smoothed_noise,
    vehicle_speeds,
)
from benchmark.scenes.projection import camera_axes
from benchmark.scenes.spec import Event, MotionSpec, Signal, Wave

TAU = 0.04


def _rng(seed: int = 0) -> np.random.Generator:
    return np.random.default_rng(seed)


def test_step_event_moves_the_signal_and_stays() -> None:
    signal = Signal(mean=1.0, events=(Event(frame=20.0, amplitude=3.0, duration_frames=6.0),))
    values = evaluate_signal(signal, 40, _rng())
    assert np.all(values[:17] == 1.0)
    assert np.all(values[24:] == pytest.approx(4.0))
    assert np.all(np.diff(values) >= 0)


def test_pulse_event_goes_out_and_comes_back() -> None:
    signal = Signal(events=(Event(frame=10.0, amplitude=-2.0, duration_frames=8.0, shape="pulse"),))
    values = evaluate_signal(signal, 30, _rng())
    assert values.min() == pytest.approx(-2.0)
    assert int(np.argmin(values)) == 10
    assert np.all(values[15:] == pytest.approx(0.0))


def test_wave_is_silent_outside_its_window() -> None:
    signal = Signal(waves=(Wave(amplitude=5.0, period_frames=7.0, start_frame=10.0, stop_frame=30.0),))
    values = evaluate_signal(signal, 50, _rng())
    assert np.all(values[:10] == 0.0) and np.all(values[31:] == 0.0)
    assert np.max(np.abs(values[10:31])) > 4.0


def test_smoothed_noise_has_unit_variance_and_the_kernel_correlation() -> None:
    smooth = 2.0
    noise = smoothed_noise(_rng(1), 40000, smooth)
    assert noise.std() == pytest.approx(1.0, abs=0.05)
    lag_one = np.corrcoef(noise[:-1], noise[1:])[0, 1]
    # A Gaussian kernel of std s gives correlation exp(-1 / (4 s^2)) at lag one.
    assert lag_one == pytest.approx(math.exp(-1.0 / (4 * smooth**2)), abs=0.02)


@settings(max_examples=40, deadline=None)
@given(theta=st.floats(-1, 1), sigma=st.floats(-1, 1), xi=st.floats(-1, 1))
def test_psi_columns_are_the_versors_with_sigma_for_phi(theta: float, sigma: float, xi: float) -> None:
    # Eq. (12): the columns of Psi are h, v and a of section II with phi -> sigma.
    np.testing.assert_allclose(psi_matrix(theta, sigma, xi), camera_axes(theta, sigma, xi).T, atol=1e-12)


def test_level_flight_along_the_pipe_is_pure_frontal_speed() -> None:
    motion = MotionSpec(
        cy_m=Signal(mean=2.0), phi_deg=Signal(mean=55.0), speed_mps=Signal(mean=0.5), speed_noise_mps=0.0
    )
    trajectory = build_trajectory(motion, 20, TAU, _rng())
    speeds = vehicle_speeds(trajectory, TAU, math.radians(55.0))
    np.testing.assert_allclose(speeds, np.tile((0.0, 0.0, 0.5), (20, 1)), atol=1e-12)
    np.testing.assert_allclose(np.diff(trajectory.cz), 0.5 * TAU)


wavy_motion = st.builds(
    MotionSpec,
    cx_m=st.builds(Signal, noise_std=st.floats(0, 0.1), waves=st.just((Wave(0.2, 17.0),))),
    cy_m=st.builds(Signal, mean=st.just(2.0), noise_std=st.floats(0, 0.1)),
    theta_deg=st.builds(Signal, noise_std=st.floats(0, 3), waves=st.just((Wave(5.0, 23.0),))),
    phi_deg=st.builds(Signal, mean=st.floats(30, 90), noise_std=st.floats(0, 3)),
    xi_deg=st.builds(Signal, noise_std=st.floats(0, 3)),
    speed_mps=st.builds(Signal, mean=st.floats(0.1, 1.5), noise_std=st.floats(0, 0.2)),
)


@settings(max_examples=15, deadline=None)
@given(motion=wavy_motion, nominal=st.floats(30, 90), seed=st.integers(0, 2**32 - 1))
def test_speeds_satisfy_equation_seven(motion: MotionSpec, nominal: float, seed: int) -> None:
    trajectory = build_trajectory(motion, 30, TAU, _rng(seed))
    phi0 = math.radians(nominal)
    speeds = vehicle_speeds(trajectory, TAU, phi0)
    centres = trajectory.centres()
    for k in range(30):
        psi = psi_matrix(trajectory.theta[k], trajectory.phi[k] - phi0, trajectory.xi[k])
        np.testing.assert_allclose(centres[k] + psi @ speeds[k] * TAU, centres[k + 1], atol=1e-10)


def test_trajectories_repeat_for_a_seed_and_channels_are_independent() -> None:
    base = MotionSpec(cx_m=Signal(noise_std=0.1), theta_deg=Signal(noise_std=2.0))
    noisier = MotionSpec(cx_m=Signal(noise_std=0.1), theta_deg=Signal(noise_std=2.0, noise_smooth_frames=1.0))
    a = build_trajectory(base, 25, TAU, _rng(7))
    b = build_trajectory(base, 25, TAU, _rng(7))
    c = build_trajectory(noisier, 25, TAU, _rng(7))
    d = build_trajectory(base, 25, TAU, _rng(8))
    np.testing.assert_array_equal(a.cx, b.cx)
    np.testing.assert_array_equal(a.theta, b.theta)
    np.testing.assert_array_equal(a.cx, c.cx)
    assert not np.array_equal(a.theta, c.theta)
    assert not np.array_equal(a.cx, d.cx)
    assert len(a) == 26
