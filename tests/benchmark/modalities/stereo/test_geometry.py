"""Stereo geometry of seeds/002: eq. (15) and its inverse, eq. (17), eqs. (10)-(12); scalars and arrays alike.

Also the simulated camera's depth accuracy (Table 3) and the extent of its image.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from numpy.typing import ArrayLike

from benchmark.modalities.stereo.geometry import (
    in_front,
    in_view,
    project,
    rotation,
    signed_baseline,
    to_camera,
    to_camera_jacobian,
    to_north_east,
    triangulate,
    triangulation_denominator,
    triangulation_jacobian,
)
from benchmark.modalities.stereo.model import StereoCalibration
from benchmark.modalities.stereo.scenes.spec import StereoCameraSpec
from benchmark.modalities.stereo.strategies import calibrations, stereo_measurements

BUMBLEBEE = StereoCameraSpec().calibration()

principal_shift = st.floats(-3.0, 3.0)
coordinate = st.floats(-200.0, 200.0)
heading = st.floats(-math.pi, math.pi)


def pinhole(x: float, y: float, calibration: StereoCalibration) -> tuple[float, float]:
    """``(y_l, y_r)`` of ``(x ahead, y starboard)`` from the pinhole model, for equal principal points."""
    left = calibration.principal_left_px + calibration.focal_px * y / x
    return left, left - calibration.focal_px * calibration.baseline_m / x


# ---------------------------------------------------------------- eq. (15)
def depth_from_disparity(disparity_px: ArrayLike, calibration: StereoCalibration) -> np.ndarray:
    """Range ahead ``Z = f B / d`` for disparities corrected for the principal points.

    Parameters
    ----------
    disparity_px : array_like
        ``d - (C_y - C_y*)``, px.
    calibration : StereoCalibration
        Focal length ``f`` and baseline ``B``.

    Returns
    -------
    numpy.ndarray
        ``Z`` in m.

    References
    ----------
    seeds/002, Table 3 (column "Z") and eq. (15) with ``C_y = C_y*``.
    """
    return calibration.focal_px * calibration.baseline_m / np.asarray(disparity_px, dtype=float)


def depth_accuracy(depth_m: ArrayLike, calibration: StereoCalibration, disparity_error_px: float) -> np.ndarray:
    """Depth error caused by a disparity error, linearised: ``Z^2 / (f B) * delta_d``.

    Parameters
    ----------
    depth_m : array_like
        ``Z``, m.
    calibration : StereoCalibration
        Focal length ``f`` and baseline ``B``.
    disparity_error_px : float
        ``delta_d``; Table 3 uses the correlation accuracy of Table 4, 0.2 px.

    Returns
    -------
    numpy.ndarray
        In m.

    References
    ----------
    seeds/002, Table 3 (column "Z accuracy") and Fig. 5.
    """
    z = np.asarray(depth_m, dtype=float)
    return z**2 / (calibration.focal_px * calibration.baseline_m) * disparity_error_px


def test_signed_baseline_is_the_right_camera_offset_in_opencv_convention() -> None:
    assert signed_baseline(BUMBLEBEE) == -BUMBLEBEE.baseline_m


@settings(max_examples=200, deadline=None)
@given(
    ahead=st.floats(0.3, 300.0),
    lateral=st.floats(-1.2, 1.2),
    focal=st.floats(50.0, 2000.0),
    baseline=st.floats(0.05, 1.0),
    c_left=st.floats(100.0, 400.0),
    c_right=st.floats(100.0, 400.0),
)
def test_triangulation_inverts_projection(ahead, lateral, focal, baseline, c_left, c_right) -> None:
    calibration = StereoCalibration(focal, baseline, c_left, c_right, 640, 16.0, 0.11)
    starboard = lateral * ahead
    y_l, y_r = project(ahead, starboard, calibration)
    x_v, y_v = triangulate(y_l, y_r, calibration)
    assert float(x_v) == pytest.approx(ahead, rel=1e-8)
    assert float(y_v) == pytest.approx(starboard, rel=1e-8, abs=1e-9 * ahead)


@given(x=st.floats(0.5, 40.0), bearing=st.floats(-0.8, 0.8))
def test_triangulation_inverts_the_pinhole_projection(x, bearing) -> None:
    relative = np.array([x, x * np.tan(bearing)])
    left, right = pinhole(*relative, BUMBLEBEE)
    assert in_front(left, right, BUMBLEBEE)
    np.testing.assert_allclose(triangulate(left, right, BUMBLEBEE), relative, rtol=1e-9, atol=1e-9)


@given(x=st.floats(0.5, 40.0), y=st.floats(-10.0, 10.0), shift=principal_shift)
def test_project_inverts_triangulate(x, y, shift) -> None:
    calibration = dataclasses.replace(BUMBLEBEE, principal_right_px=BUMBLEBEE.principal_right_px + shift)
    left, right = project(x, y, calibration)
    assert in_front(left, right, calibration)
    np.testing.assert_allclose(triangulate(left, right, calibration), [x, y], rtol=1e-9, atol=1e-9)


def test_a_target_ahead_to_starboard_has_positive_disparity_and_lies_right_of_centre() -> None:
    y_l, y_r = project(10.0, 2.0, BUMBLEBEE)
    assert y_l > BUMBLEBEE.principal_left_px
    assert y_l - y_r == pytest.approx(BUMBLEBEE.focal_px * BUMBLEBEE.baseline_m / 10.0)
    x_v, y_v = triangulate(y_l, y_r, BUMBLEBEE)
    assert (float(x_v), float(y_v)) == pytest.approx((10.0, 2.0))


def test_eq_15_as_printed_with_the_right_camera_to_starboard() -> None:
    # Eq. (15): x = f T_y / (C_y - C_y* - d), y = T_y (y_l - C_y) / (C_y - C_y* - d), T_y = -B.
    calibration = StereoCalibration(150.0, 0.2, 160.0, 155.0, 320, 16.0, 0.11)
    y_l, y_r = 171.0, 160.5
    d = y_l - y_r
    t_y = -0.2
    expected = (150.0 * t_y / (160.0 - 155.0 - d), t_y * (y_l - 160.0) / (160.0 - 155.0 - d))
    assert tuple(map(float, triangulate(y_l, y_r, calibration))) == pytest.approx(expected)
    assert expected[0] > 0


def test_table_3_depths_follow_from_the_disparity() -> None:
    for disparity, depth in [(1.0, 16.896), (2.0, 8.448), (4.5, 3.75466667), (33.0, 0.512)]:
        x, _ = triangulate(159.5 + disparity, 159.5, BUMBLEBEE)
        assert abs(x - depth) < 1e-3 * depth


def test_disparity_is_one_pixel_at_16_9_m() -> None:
    y_l, y_r = project(16.9, 0.0, BUMBLEBEE)
    assert float(y_l - y_r) == pytest.approx(1.0, abs=1e-3)


def test_linearised_depth_accuracy_matches_triangulation_at_16_9_m() -> None:
    # A small disparity error, scaled to the 0.2 px of Table 4, moves the triangulated depth by ~3.38 m.
    y_l, y_r = project(16.9, 0.0, BUMBLEBEE)
    step = 1e-4
    near, _ = triangulate(y_l + step, y_r, BUMBLEBEE)
    far, _ = triangulate(y_l - step, y_r, BUMBLEBEE)
    assert float(far - near) / (2 * step) * 0.2 == pytest.approx(3.38, abs=0.01)


def test_zero_or_negative_disparity_is_not_in_front() -> None:
    assert not in_front(160.0, 160.0, BUMBLEBEE)
    assert not in_front(160.0, 160.5, BUMBLEBEE)
    assert in_front(160.5, 160.0, BUMBLEBEE)
    assert not in_front(math.nan, 160.0, BUMBLEBEE)
    np.testing.assert_array_equal(
        in_front(np.array([160.0, 160.5, np.nan, np.inf]), 160.0, BUMBLEBEE), [False, True, False, False]
    )


# ---------------------------------------------------------------- eq. (17)
@settings(max_examples=200, deadline=None)
@given(calibration=calibrations(), data=st.data())
def test_jacobian_matches_central_differences(calibration, data) -> None:
    measurement = data.draw(stereo_measurements(calibration))
    left, right = measurement.left_px, measurement.right_px
    assert in_front(left, right, calibration)
    disparity = left - right - (calibration.principal_left_px - calibration.principal_right_px)
    h = 1e-5 * max(1.0, disparity)
    numeric = np.zeros((2, 4))
    for column, (d_left, d_right) in {1: (h, 0.0), 3: (0.0, h)}.items():
        plus = np.array(triangulate(left + d_left, right + d_right, calibration))
        minus = np.array(triangulate(left - d_left, right - d_right, calibration))
        numeric[:, column] = (plus - minus) / (2.0 * h)
    analytic = triangulation_jacobian(left, right, calibration)
    scale = np.abs(analytic).max()
    np.testing.assert_allclose(analytic, numeric, rtol=1e-5, atol=1e-7 * scale)
    assert np.all(analytic[:, [0, 2]] == 0.0)


def test_the_jacobian_denominator_is_eq_17s_d_squared() -> None:
    # D = (C_y - C_y* + y_r - y_l)^2 and dx/dy_l = f T_y / D.
    calibration = dataclasses.replace(BUMBLEBEE, principal_right_px=158.0)
    left, right = 170.0, 166.0
    D = (159.5 - 158.0 + right - left) ** 2
    assert triangulation_denominator(left, right, calibration) ** 2 == D
    assert triangulation_jacobian(left, right, calibration)[0, 1] == pytest.approx(
        calibration.focal_px * -calibration.baseline_m / D
    )


# ------------------------------------------------------------- eqs. (10)-(12)
def test_a_target_ahead_of_a_chaser_heading_east_lies_east() -> None:
    np.testing.assert_allclose(to_north_east(10.0, 0.0, (100.0, 50.0), math.pi / 2), [100.0, 60.0], atol=1e-12)
    # starboard of a boat heading east is south
    np.testing.assert_allclose(to_north_east(0.0, 3.0, (100.0, 50.0), math.pi / 2), [97.0, 50.0], atol=1e-12)


@given(x=coordinate, y=coordinate, X=coordinate, Y=coordinate, psi=heading)
def test_to_camera_inverts_eq_10(x, y, X, Y, psi) -> None:
    north, east = to_north_east(x, y, (X, Y), psi)
    np.testing.assert_allclose(to_camera(north, east, (X, Y), psi), [x, y], atol=1e-9)
    assert math.hypot(north - X, east - Y) == pytest.approx(math.hypot(x, y), abs=1e-9)


@given(X=coordinate, Y=coordinate, psi=heading)
def test_to_camera_jacobian_matches_central_differences_and_is_a_rotation(X, Y, psi) -> None:
    point, h = np.array([X + 7.0, Y - 3.0]), 1e-6
    numeric = np.column_stack(
        [(np.array(to_camera(*(point + h * e), (X, Y), psi)) - to_camera(*(point - h * e), (X, Y), psi)) / (2 * h)
         for e in np.eye(2)]
    )
    jacobian = to_camera_jacobian(psi)
    np.testing.assert_allclose(jacobian, numeric, atol=1e-7)
    np.testing.assert_allclose(jacobian @ rotation(psi), np.eye(2), atol=1e-12)
    assert np.linalg.det(rotation(psi)) == pytest.approx(1.0)


# ------------------------------------------------------ scalars and arrays
def everything(ahead, starboard, chase, psi) -> dict[str, tuple]:
    """Every function of the module, chained from a point in the camera frame and CH's pose."""
    left, right = project(ahead, starboard, BUMBLEBEE)
    north, east = to_north_east(ahead, starboard, chase, psi)
    return {
        "project": (left, right),
        "triangulate": triangulate(left, right, BUMBLEBEE),
        "in_front": (in_front(left, right, BUMBLEBEE),),
        "jacobian": (triangulation_jacobian(left, right, BUMBLEBEE),),
        "to_north_east": (north, east),
        "to_camera": to_camera(north, east, chase, psi),
        "rotation": (rotation(psi),),
        "to_camera_jacobian": (to_camera_jacobian(psi),),
    }


def test_arrays_give_elementwise_the_scalar_results() -> None:
    rng = np.random.default_rng(3)
    n = 7
    ahead, starboard = rng.uniform(1.0, 30.0, n), rng.uniform(-5.0, 5.0, n)
    chase, psi = (rng.uniform(-50.0, 50.0, n), rng.uniform(-50.0, 50.0, n)), rng.uniform(-math.pi, math.pi, n)
    arrays = everything(ahead, starboard, chase, psi)
    assert arrays["jacobian"][0].shape == (n, 2, 4) and arrays["rotation"][0].shape == (n, 2, 2)
    for k in range(n):
        pose = (float(chase[0][k]), float(chase[1][k])), float(psi[k])
        scalars = everything(float(ahead[k]), float(starboard[k]), *pose)
        for name, values in scalars.items():
            for array, scalar in zip(arrays[name], values, strict=True):
                np.testing.assert_allclose(array[k], scalar, rtol=1e-15, atol=0.0, err_msg=name)
    assert all(isinstance(v, float) for v in (*project(1.0, 2.0, BUMBLEBEE), *to_camera(1.0, 2.0, (0.0, 0.0), 0.3)))
    assert isinstance(in_front(170.0, 160.0, BUMBLEBEE), bool)


# ---------------------------------------------------------------- Table 3: the simulated camera
TABLE_3 = [  # disparity px, Z m, Z accuracy m (seeds/002, Table 3)
    (1.0, 16.896, 3.3792),
    (1.5, 11.264, 1.5019),
    (2.0, 8.448, 0.8448),
    (2.5, 6.7584, 0.5407),
    (3.5, 4.82742857, 0.2759),
    (4.5, 3.75466667, 0.1669),
    (7.0, 2.41371429, 0.0690),
    (33.0, 0.512, 0.0031),
]


@pytest.mark.parametrize(("disparity", "depth", "accuracy"), TABLE_3)
def test_table_3_is_reproduced(disparity, depth, accuracy) -> None:
    assert float(depth_from_disparity(disparity, BUMBLEBEE)) == pytest.approx(depth, rel=1e-6)
    assert float(depth_accuracy(depth, BUMBLEBEE, 0.2)) == pytest.approx(accuracy, abs=6e-5)


def test_image_spans_half_a_pixel_beyond_the_outer_pixel_centres() -> None:
    inside = in_view(np.array([-0.5, 0.0, 319.0, 319.5]), BUMBLEBEE)
    outside = in_view(np.array([-0.51, 319.51, np.nan]), BUMBLEBEE)
    assert inside.all() and not outside.any()
