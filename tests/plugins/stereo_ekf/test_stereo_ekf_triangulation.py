"""Triangulation of seeds/002 eq. (15) and its Jacobian, eq. (17)."""

from __future__ import annotations

import dataclasses

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from trackbench_stereo_ekf.triangulation import (
    in_front,
    project,
    signed_baseline,
    triangulate,
    triangulation_jacobian,
)

left_px = st.floats(0.0, 319.0)
disparity_px = st.floats(0.3, 80.0)
principal_shift = st.floats(-3.0, 3.0)


def test_signed_baseline_is_the_right_camera_offset_in_opencv_convention(scene):
    assert signed_baseline(scene.CALIBRATION) == -scene.CALIBRATION.baseline_m


@given(x=st.floats(0.5, 40.0), bearing=st.floats(-0.8, 0.8))
def test_triangulation_inverts_the_pinhole_projection(scene, x, bearing):
    CALIBRATION = scene.CALIBRATION
    relative = np.array([x, x * np.tan(bearing)])
    left, right = scene.project(relative)
    assert in_front(left, right, CALIBRATION)
    np.testing.assert_allclose(triangulate(left, right, CALIBRATION), relative, rtol=1e-9, atol=1e-9)


def test_table_3_depths_follow_from_the_disparity(scene):
    CALIBRATION = scene.CALIBRATION
    for disparity, depth in [(1.0, 16.896), (2.0, 8.448), (4.5, 3.75466667), (33.0, 0.512)]:
        x, _ = triangulate(159.5 + disparity, 159.5, CALIBRATION)
        assert abs(x - depth) < 1e-3 * depth


def test_zero_or_negative_disparity_is_not_in_front(scene):
    CALIBRATION = scene.CALIBRATION
    assert not in_front(160.0, 160.0, CALIBRATION)
    assert not in_front(160.0, 160.5, CALIBRATION)
    assert in_front(160.5, 160.0, CALIBRATION)


@settings(max_examples=200)
@given(left=left_px, disparity=disparity_px, shift_left=principal_shift, shift_right=principal_shift)
def test_jacobian_matches_central_differences(scene, left, disparity, shift_left, shift_right):
    CALIBRATION = scene.CALIBRATION
    calibration = dataclasses.replace(
        CALIBRATION,
        principal_left_px=CALIBRATION.principal_left_px + shift_left,
        principal_right_px=CALIBRATION.principal_right_px + shift_right,
    )
    # the disparity is counted from the principal-point offset, so that the target is in front
    right = left - disparity - (calibration.principal_left_px - calibration.principal_right_px)
    assert in_front(left, right, calibration)
    h = 1e-5 * max(1.0, disparity)
    numeric = np.zeros((2, 4))
    for column, (d_left, d_right) in {1: (h, 0.0), 3: (0.0, h)}.items():
        plus = triangulate(left + d_left, right + d_right, calibration)
        minus = triangulate(left - d_left, right - d_right, calibration)
        numeric[:, column] = (plus - minus) / (2.0 * h)
    analytic = triangulation_jacobian(left, right, calibration)
    scale = np.abs(analytic).max()
    np.testing.assert_allclose(analytic, numeric, rtol=1e-5, atol=1e-7 * scale)
    assert np.all(analytic[:, [0, 2]] == 0.0)


@given(x=st.floats(0.5, 40.0), y=st.floats(-10.0, 10.0), shift=principal_shift)
def test_project_inverts_triangulate(scene, x, y, shift):
    calibration = dataclasses.replace(
        scene.CALIBRATION, principal_right_px=scene.CALIBRATION.principal_right_px + shift
    )
    left, right = project([x, y], calibration)
    assert in_front(left, right, calibration)
    np.testing.assert_allclose(triangulate(left, right, calibration), [x, y], rtol=1e-9, atol=1e-9)
