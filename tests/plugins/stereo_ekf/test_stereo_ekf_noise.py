"""Measurement noise of seeds/002, eqs. (18) and (20)."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from trackbench_stereo_ekf.measurement import observe
from trackbench_stereo_ekf.noise import full_covariance, measurement_noise, modified_covariance, navigation_noise

from benchmark.modalities.stereo.geometry import triangulate
from benchmark.modalities.stereo.model import ChaseNavigation

left_px = st.floats(0.0, 319.0)
disparity_px = st.floats(0.3, 80.0)


@given(left=left_px, disparity=disparity_px)
def test_full_covariance_is_symmetric_positive_semidefinite(scene, left, disparity):
    CALIBRATION, PIXEL_VARIANCE = scene.CALIBRATION, scene.PIXEL_VARIANCE
    Q = full_covariance(left, left - disparity, CALIBRATION, PIXEL_VARIANCE)
    np.testing.assert_allclose(Q, Q.T, rtol=1e-12)
    assert np.linalg.eigvalsh(Q).min() >= -1e-9 * np.abs(Q).max()
    assert Q[0, 0] > 0.0


def test_full_covariance_matches_sampled_pixel_noise(scene):
    CALIBRATION, PIXEL_VARIANCE = scene.CALIBRATION, scene.PIXEL_VARIANCE
    CALIBRATION, PIXEL_VARIANCE = scene.CALIBRATION, scene.PIXEL_VARIANCE
    rng = np.random.default_rng(7)
    left, right = 200.0, 190.0
    noise = rng.normal(0.0, np.sqrt(PIXEL_VARIANCE), (50_000, 2))
    points = triangulate(left + noise[:, 0], right + noise[:, 1], CALIBRATION)
    np.testing.assert_allclose(
        np.cov(points), full_covariance(left, right, CALIBRATION, PIXEL_VARIANCE), rtol=0.05
    )


@given(left=left_px, disparity=disparity_px)
def test_modified_covariance_is_diagonal_with_eq_18_depth_and_constant_lateral_variance(scene, left, disparity):
    CALIBRATION, PIXEL_VARIANCE = scene.CALIBRATION, scene.PIXEL_VARIANCE
    right = left - disparity
    Q = modified_covariance(left, right, CALIBRATION, PIXEL_VARIANCE, lateral_k=2.0)
    assert Q[0, 1] == Q[1, 0] == 0.0
    assert Q[0, 0] == pytest.approx(full_covariance(left, right, CALIBRATION, PIXEL_VARIANCE)[0, 0], rel=1e-12)
    assert Q[1, 1] == pytest.approx(2.0 * PIXEL_VARIANCE)
    assert Q[1, 1] == pytest.approx(CALIBRATION.correlation_accuracy_px**2)


@pytest.mark.parametrize(("disparity", "accuracy"), [(1.0, 3.3792), (2.0, 0.8448), (3.5, 0.2759), (7.0, 0.0690)])
def test_depth_standard_deviation_reproduces_table_3(scene, disparity, accuracy):
    # Table 3 is for a correlation accuracy of 0.2 px, so Q_f = 0.2^2 / 2 (eq. 19)
    Q = modified_covariance(159.5 + disparity, 159.5, scene.CALIBRATION, 0.2**2 / 2, lateral_k=2.0)
    assert np.sqrt(Q[0, 0]) == pytest.approx(accuracy, rel=2e-3)


def test_depth_variance_grows_with_range(scene):
    CALIBRATION, PIXEL_VARIANCE = scene.CALIBRATION, scene.PIXEL_VARIANCE
    CALIBRATION, PIXEL_VARIANCE = scene.CALIBRATION, scene.PIXEL_VARIANCE
    near = measurement_noise(170.0, 160.0, CALIBRATION, PIXEL_VARIANCE)
    far = measurement_noise(161.0, 160.0, CALIBRATION, PIXEL_VARIANCE)
    assert far[0, 0] == pytest.approx(near[0, 0] * 10.0**4)


def test_measurement_noise_selects_the_form(scene):
    CALIBRATION, PIXEL_VARIANCE = scene.CALIBRATION, scene.PIXEL_VARIANCE
    CALIBRATION, PIXEL_VARIANCE = scene.CALIBRATION, scene.PIXEL_VARIANCE
    eq18 = measurement_noise(200.0, 190.0, CALIBRATION, PIXEL_VARIANCE, form="eq18")
    eq20 = measurement_noise(200.0, 190.0, CALIBRATION, PIXEL_VARIANCE, form="eq20", lateral_k=3.0)
    assert eq18[0, 1] != 0.0
    assert eq20[0, 1] == 0.0 and eq20[1, 1] == pytest.approx(3.0 * PIXEL_VARIANCE)
    with pytest.raises(ValueError, match="eq19"):
        measurement_noise(200.0, 190.0, CALIBRATION, PIXEL_VARIANCE, form="eq19")


def test_navigation_noise_matches_sampled_gps_and_compass_errors():
    rng = np.random.default_rng(11)
    position, heading = np.array([40.0, -25.0]), 0.7
    navigation = ChaseNavigation(tuple(position), heading)
    state = np.array([52.0, -14.0, 0.0, 0.0])
    z = observe(state, navigation)
    gps_std, compass_std = 0.3, np.radians(2.0)
    n = 20_000
    gps = rng.normal(0.0, gps_std, (n, 2))
    turns = rng.normal(0.0, compass_std, n)
    samples = np.array(
        [observe(state, ChaseNavigation(tuple(position + g), heading + t)) for g, t in zip(gps, turns, strict=True)]
    )
    np.testing.assert_allclose(np.cov(samples.T), navigation_noise(z, gps_std, compass_std), rtol=0.05, atol=2e-3)


def test_navigation_noise_vanishes_without_navigation_errors():
    assert np.all(navigation_noise([12.0, 3.0], 0.0, 0.0) == 0.0)
