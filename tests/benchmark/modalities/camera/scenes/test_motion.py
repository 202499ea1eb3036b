"""Trajectories and the vehicle speeds of seeds/004 eqs. (7) and (12) (signals themselves: tests/benchmark/scenes)."""

from __future__ import annotations

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from benchmark.modalities.camera.scenes.motion import build_trajectory, psi_matrix, vehicle_speeds
from benchmark.modalities.camera.scenes.projection import camera_axes
from benchmark.modalities.camera.scenes.spec import MotionSpec
from benchmark.scenes.signal import Signal, Wave

TAU = 0.04


def _rng(seed: int = 0) -> np.random.Generator:
    return np.random.default_rng(seed)


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
