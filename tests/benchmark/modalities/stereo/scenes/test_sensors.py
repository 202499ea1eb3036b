"""The stereo front end, GPS and dropout models: noise statistics and loss rules."""

from __future__ import annotations

import math

import numpy as np
import pytest

from benchmark.modalities.stereo.geometry import project
from benchmark.modalities.stereo.scenes.sensors import Loss, burst_dropouts, correlated_noise, stereo_measurements
from benchmark.modalities.stereo.scenes.spec import StereoCameraSpec

CAMERA = StereoCameraSpec()
BUMBLEBEE = CAMERA.calibration()


def _lag_one(x: np.ndarray) -> float:
    return float(np.corrcoef(x[1:], x[:-1])[0, 1])


def test_white_gps_noise_has_the_given_sigma_and_no_memory() -> None:
    noise = correlated_noise(np.random.default_rng(1), (20000, 2), 0.3, 0.0)
    assert noise.std(axis=0) == pytest.approx([0.3, 0.3], rel=0.03)
    assert abs(_lag_one(noise[:, 0])) < 0.03


def test_correlated_gps_noise_keeps_its_sigma_and_decays_with_the_correlation_time() -> None:
    noise = correlated_noise(np.random.default_rng(2), (40000, 2), 0.5, 10.0)
    assert noise.std(axis=0) == pytest.approx([0.5, 0.5], rel=0.08)
    assert _lag_one(noise[:, 1]) == pytest.approx(math.exp(-0.1), abs=0.02)


def test_dropouts_come_at_the_given_rate_in_bursts_of_the_given_mean_length() -> None:
    missed = burst_dropouts(np.random.default_rng(3), 200000, 0.05, 4.0)
    assert missed.mean() == pytest.approx(0.05, rel=0.1)
    starts = np.flatnonzero(np.diff(missed.astype(int)) == 1)
    assert missed.sum() / starts.size == pytest.approx(4.0, rel=0.1)


def test_no_dropouts_at_rate_zero_and_bad_arguments_are_refused() -> None:
    assert not burst_dropouts(np.random.default_rng(0), 100, 0.0, 3.0).any()
    with pytest.raises(ValueError, match="rate"):
        burst_dropouts(np.random.default_rng(0), 100, 1.0, 3.0)
    with pytest.raises(ValueError, match="mean_burst"):
        burst_dropouts(np.random.default_rng(0), 100, 0.1, 0.5)


def test_without_noise_the_front_end_reports_the_true_relative_position() -> None:
    ahead, starboard = np.array([3.0, 10.0, 25.0]), np.array([-1.0, 2.0, 0.5])
    m = stereo_measurements(ahead, starboard, BUMBLEBEE, np.zeros((3, 2)), 0.3, np.zeros(3, dtype=bool))
    assert m.kept.all()
    np.testing.assert_allclose(m.ahead_m, ahead)
    np.testing.assert_allclose(m.starboard_m, starboard, atol=1e-12)
    true_l, true_r = project(ahead, starboard, BUMBLEBEE)
    np.testing.assert_allclose(m.left_px, true_l)
    np.testing.assert_allclose(m.right_px, true_r)


def test_the_front_end_loses_targets_out_of_view_too_far_or_dropped() -> None:
    ahead = np.array([10.0, -5.0, 5.0, 80.0, 10.0, 80.0])
    starboard = np.array([0.0, 0.0, 8.0, 0.0, 0.0, 200.0])
    dropped = np.array([False, False, False, False, True, True])
    m = stereo_measurements(ahead, starboard, BUMBLEBEE, np.zeros((6, 2)), 0.3, dropped)
    assert list(m.loss) == [
        Loss.KEPT,
        Loss.OUT_OF_VIEW,  # behind the camera
        Loss.OUT_OF_VIEW,  # 58 deg to starboard, beyond the half field of view of 48.6 deg
        Loss.LOW_DISPARITY,  # 0.21 px
        Loss.DROPOUT,
        Loss.OUT_OF_VIEW,  # geometry first
    ]


def test_pixel_noise_has_variance_q_f_and_the_disparity_variance_m_squared() -> None:
    n = 20000
    rng = np.random.default_rng(4)
    ahead, starboard = rng.uniform(3.0, 30.0, n), rng.uniform(-2.0, 2.0, n)
    noise = CAMERA.pixel_noise_px * rng.standard_normal((n, 2))
    m = stereo_measurements(ahead, starboard, BUMBLEBEE, noise, 0.0, np.zeros(n, dtype=bool))
    true_l, true_r = project(ahead, starboard, BUMBLEBEE)
    assert np.std(m.left_px - true_l) == pytest.approx(0.11 / math.sqrt(2.0), rel=0.03)
    assert np.std(m.right_px - true_r) == pytest.approx(0.0778, rel=0.03)
    assert np.std((m.left_px - m.right_px) - (true_l - true_r)) == pytest.approx(0.11, rel=0.03)
    # The error in range grows as Z^2 / (f B) * m (seeds/002, Fig. 5).
    far = (ahead > 20) & m.kept
    near = (ahead < 6) & m.kept
    assert np.std(m.ahead_m[far] - ahead[far]) > 10 * np.std(m.ahead_m[near] - ahead[near])
