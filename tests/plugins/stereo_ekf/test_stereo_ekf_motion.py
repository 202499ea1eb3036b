"""Motion model of seeds/002, eqs. (5)-(9)."""

from __future__ import annotations

import numpy as np
from hypothesis import given
from hypothesis import strategies as st
from trackbench_stereo_ekf.motion import control_vector, process_noise, propagate, transition_matrix


def test_propagation_moves_by_velocity_plus_the_control_acceleration_on_every_component():
    state = np.array([10.0, -4.0, 2.0, -1.0])
    T, a = 0.2, 0.003
    expected = np.array([10.0 + 2.0 * T, -4.0 - 1.0 * T, 2.0, -1.0]) + a * np.array([T**2 / 2, T**2 / 2, T, T])
    np.testing.assert_allclose(propagate(state, T, a), expected)
    np.testing.assert_allclose(transition_matrix(T) @ state + control_vector(T) * a, expected)


@given(T=st.floats(0.01, 2.0), sigma=st.floats(0.01, 3.0))
def test_process_noise_is_the_covariance_of_per_axis_acceleration_noise(T, sigma):
    # one independent acceleration per axis acting as [T^2/2, T] on (position, velocity)
    north = np.array([T**2 / 2, 0.0, T, 0.0])
    east = np.array([0.0, T**2 / 2, 0.0, T])
    expected = sigma**2 * (np.outer(north, north) + np.outer(east, east))
    R = process_noise(T, sigma)
    np.testing.assert_allclose(R, expected, rtol=1e-12, atol=1e-15)
    assert np.allclose(R[0, 2], sigma**2 * T**3 / 2)
    np.testing.assert_array_equal(R, R.T)
    assert np.linalg.eigvalsh(R).min() >= -1e-12 * np.abs(R).max()


def test_process_noise_matches_sampled_accelerations():
    rng = np.random.default_rng(3)
    T, sigma = 0.2, 0.4
    accelerations = rng.normal(0.0, sigma, (200_000, 2))
    B = np.array([[T**2 / 2, 0.0], [0.0, T**2 / 2], [T, 0.0], [0.0, T]])
    samples = accelerations @ B.T
    np.testing.assert_allclose(np.cov(samples.T), process_noise(T, sigma), rtol=0.02, atol=0.01 * (T * sigma) ** 2)


def test_printed_t_to_the_three_halves_would_not_be_a_covariance():
    T = 0.2
    printed = np.array([[T**4 / 4, T**1.5], [T**1.5, T**2]])
    assert np.linalg.eigvalsh(printed).min() < 0.0
