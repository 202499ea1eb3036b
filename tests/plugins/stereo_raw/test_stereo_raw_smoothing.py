"""The moving average behind the raw baseline's speed and heading (seeds/002, sections 3.3-4)."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from trackbench_stereo_raw.smoothing import VelocitySmoother


def test_no_velocity_before_the_second_position():
    smoother = VelocitySmoother(15)
    assert smoother.add(0.0, [1.0, 2.0]) is None
    assert smoother.add(0.2, [1.2, 2.0]) is not None


@given(seed=st.integers(0, 2**32 - 1), window=st.integers(1, 20))
def test_once_full_it_is_the_change_of_the_moving_average_of_positions(seed, window):
    rng = np.random.default_rng(seed)
    T = 0.2
    positions = rng.normal(0.0, 3.0, (60, 2)) + np.arange(60)[:, None] * [0.5, -0.2]
    smoother = VelocitySmoother(window)
    velocities = [smoother.add(k * T, p) for k, p in enumerate(positions)]
    kernel = np.ones(window) / window
    averages = np.column_stack([np.convolve(positions[:, i], kernel, mode="valid") for i in range(2)])
    # averages[j] covers positions j .. j + window - 1
    for k in range(window, 60):
        expected = (averages[k - window + 1] - averages[k - window]) / T
        np.testing.assert_allclose(velocities[k], expected, atol=1e-9)


def test_before_the_window_fills_it_averages_what_it_has():
    smoother = VelocitySmoother(15)
    smoother.add(0.0, [0.0, 0.0])
    smoother.add(1.0, [1.0, 0.0])
    np.testing.assert_allclose(smoother.add(2.0, [1.0, 4.0]), [0.5, 2.0])


def test_a_gap_is_bridged_by_the_actual_time_between_measurements():
    smoother = VelocitySmoother(15)
    times = [0.0, 0.2, 0.4, 1.6, 1.8, 2.0]
    velocity = np.array([3.0, -1.5])
    results = [smoother.add(t, velocity * t + [10.0, 5.0]) for t in times]
    for result in results[1:]:
        np.testing.assert_allclose(result, velocity, atol=1e-12)


def test_time_must_increase_and_window_must_be_positive():
    smoother = VelocitySmoother(3)
    smoother.add(1.0, [0.0, 0.0])
    with pytest.raises(ValueError, match="does not follow"):
        smoother.add(1.0, [1.0, 0.0])
    with pytest.raises(ValueError, match="window"):
        VelocitySmoother(0)
