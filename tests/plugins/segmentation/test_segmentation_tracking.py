"""Tests of the Kalman filter on (d, alpha, w) and the region of interest it predicts (seeds/000, section 2.3)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from trackbench_segmentation.tracking import CableKalman, lateral_std, region_of_interest

from benchmark.filters.kalman import Gaussian
from benchmark.modalities.camera.geometry import cable_borders, chord_midpoint, model_to_pixel
from benchmark.modalities.camera.model import CableState
from benchmark.testing.beliefs import gaussian_update_problems

SIZE = (320, 240)
PROCESS = (25.0, 0.003, 4.0)
MEASUREMENT = (4.0, 0.0003, 4.0)

states = st.builds(
    CableState,
    st.floats(-150, 150),
    st.floats(-1.5, 1.5),
    st.floats(5, 100),
    st.floats(0, 0.17),
)


def assert_symmetric_psd(covariance: np.ndarray) -> None:
    assert np.array_equal(covariance, covariance.T)
    assert np.linalg.eigvalsh(covariance).min() >= -1e-12


@settings(max_examples=40, deadline=None)
@given(steps=st.lists(st.one_of(st.none(), states), min_size=1, max_size=25))
def test_the_belief_stays_symmetric_positive_semidefinite(steps):
    kalman = CableKalman(PROCESS, MEASUREMENT)
    for measured in steps:
        kalman.predict()
        if measured is not None:
            kalman.update(measured)
        if kalman.belief is not None:
            assert_symmetric_psd(kalman.belief.covariance)
            assert np.all(np.isfinite(kalman.belief.mean))
            assert -math.pi / 2 < kalman.belief.mean[1] <= math.pi / 2


@settings(max_examples=40, deadline=None)
@given(steps=st.lists(st.one_of(st.none(), states), min_size=1, max_size=25))
def test_each_update_exposes_its_prior_and_narrows_it(steps):
    kalman = CableKalman(PROCESS, MEASUREMENT)
    for measured in steps:
        kalman.predict()
        assert kalman.prior is None
        had_belief = kalman.belief is not None
        if measured is not None:
            kalman.update(measured)
        if measured is None or not had_belief:
            assert kalman.prior is None
        else:
            assert gaussian_update_problems(kalman.prior.covariance, kalman.belief.covariance) == []
            assert abs(kalman.prior.mean[1] - kalman.belief.mean[1]) < math.pi / 2  # the same form of the centreline


def test_a_prior_is_turned_with_the_corrected_angle():
    kalman = CableKalman(PROCESS, MEASUREMENT)
    kalman.start(CableState(20.0, math.radians(89.0), 30.0, 0.0))
    kalman.predict()
    predicted = kalman.belief
    kalman.update(CableState(-20.0, math.radians(-85.0), 30.0, 0.0))  # the same centreline as (20, 95 deg)
    assert kalman.belief.mean[1] < 0  # corrected beyond 90 deg, brought back as (-d, alpha - pi)
    flip = np.diag([-1.0, 1.0, 1.0])
    assert np.allclose(kalman.prior.mean, [-20.0, math.radians(89.0) - math.pi, 30.0])
    assert np.array_equal(kalman.prior.covariance, flip @ predicted.covariance @ flip)


def test_prediction_grows_the_covariance_and_keeps_the_mean():
    kalman = CableKalman(PROCESS, MEASUREMENT)
    kalman.start(CableState(10.0, 0.1, 30.0, 0.0))
    before = kalman.belief
    kalman.predict()
    assert np.array_equal(kalman.belief.mean, before.mean)
    assert np.allclose(np.diag(kalman.belief.covariance), np.diag(before.covariance) + PROCESS)


def test_an_update_pulls_the_mean_towards_the_measurement_and_shrinks_the_covariance():
    kalman = CableKalman(PROCESS, MEASUREMENT)
    kalman.start(CableState(0.0, 0.0, 30.0, 0.0))
    kalman.predict()
    spread = np.diag(kalman.belief.covariance).copy()
    kalman.update(CableState(10.0, 0.05, 34.0, 0.0))
    assert 0.0 < kalman.belief.mean[0] < 10.0 and 30.0 < kalman.belief.mean[2] < 34.0
    assert np.all(np.diag(kalman.belief.covariance) < spread)


def test_a_measurement_across_the_half_turn_is_the_same_centreline():
    kalman = CableKalman(PROCESS, MEASUREMENT)
    kalman.start(CableState(20.0, math.radians(88.0), 30.0, 0.0))
    kalman.predict()
    kalman.update(CableState(-20.0, math.radians(-88.0), 30.0, 0.0))
    d, alpha, _ = kalman.belief.mean
    # The corrected centreline lies between the two, near the horizontal, in either of its two forms.
    if alpha > 0:
        assert d == pytest.approx(20.0) and math.radians(88.0) < alpha <= math.pi / 2
    else:
        assert d == pytest.approx(-20.0) and -math.pi / 2 < alpha < math.radians(-88.0)
    assert_symmetric_psd(kalman.belief.covariance)


def test_update_without_a_belief_starts_from_the_measurement():
    kalman = CableKalman(PROCESS, MEASUREMENT)
    kalman.update(CableState(5.0, 0.1, 25.0, 0.0))
    assert kalman.belief.mean.tolist() == [5.0, 0.1, 25.0]
    assert np.array_equal(kalman.belief.covariance, np.diag(MEASUREMENT))
    kalman.forget()
    assert kalman.belief is None


@settings(max_examples=30, deadline=None)
@given(
    d=st.floats(-80, 80),
    alpha=st.floats(-0.6, 0.6),
    w=st.floats(10, 60),
    variance=st.floats(0.0, 50.0),
)
def test_the_roi_holds_both_predicted_borders_and_grows_with_uncertainty(d, alpha, w, variance):
    state = CableState(d, alpha, w, 0.0)
    tight = Gaussian(np.array([d, alpha, w]), np.diag([variance, variance * 1e-4, variance]))
    loose = Gaussian(tight.mean, tight.covariance + np.diag([100.0, 0.01, 100.0]))
    roi, half = region_of_interest(tight, SIZE, 5.0, 2.0)
    wider, wider_half = region_of_interest(loose, SIZE, 5.0, 2.0)
    assert roi.shape == (SIZE[1], SIZE[0]) and roi.dtype == bool
    assert wider_half > half >= w / 2 + 5.0
    assert np.all(wider[roi])
    for border in cable_borders(state):
        u, v = (int(round(c)) for c in model_to_pixel(*chord_midpoint(border, SIZE), SIZE))
        if 0 <= u < SIZE[0] and 0 <= v < SIZE[1]:
            assert roi[v, u]


def test_lateral_std_combines_position_width_and_angle():
    covariance = np.diag([4.0, 1e-4, 16.0])
    assert lateral_std(covariance, 100.0) == np.float64(math.sqrt(4.0 + 4.0 + 1.0))


@settings(max_examples=40, deadline=None)
@given(start=states, measured=states, frames=st.integers(0, 5))
def test_the_gate_distance_is_the_same_for_both_forms_of_a_centreline(start, measured, frames):
    kalman = CableKalman(PROCESS, MEASUREMENT)
    kalman.start(start)
    for _ in range(frames):
        kalman.predict()
    other_form = CableState(-measured.d, measured.alpha - math.copysign(math.pi, measured.alpha), measured.w, 0.0)
    distance = kalman.distance(measured)
    assert distance >= 0.0
    assert kalman.distance(other_form) == pytest.approx(distance, rel=1e-9, abs=1e-9)
    assert kalman.distance(start) == pytest.approx(0.0, abs=1e-12)


def test_the_gate_distance_counts_standard_deviations_of_the_innovation():
    kalman = CableKalman(PROCESS, MEASUREMENT)
    assert kalman.distance(CableState(50.0, 0.0, 30.0, 0.0)) == 0.0, "no belief: nothing to gate against"
    kalman.start(CableState(0.0, 0.0, 30.0, 0.0))
    kalman.predict()
    d_spread = MEASUREMENT[0] + PROCESS[0] + MEASUREMENT[0]
    # Three standard deviations of the innovation in d alone: a squared distance of 9.
    assert kalman.distance(CableState(3.0 * math.sqrt(d_spread), 0.0, 30.0, 0.0)) == pytest.approx(9.0)
