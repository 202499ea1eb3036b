"""The stereo pair: projection, triangulation by eq. (15) and Table 3 of seeds/002."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from benchmark.model import StereoCalibration
from benchmark.scenes.stereo_projection import depth_accuracy, depth_from_disparity, in_view, project, triangulate
from benchmark.scenes.stereo_spec import StereoCameraSpec

BUMBLEBEE = StereoCameraSpec().calibration()

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


@pytest.mark.parametrize(("disparity", "depth", "accuracy"), TABLE_3)
def test_table_3_is_reproduced(disparity, depth, accuracy) -> None:
    assert float(depth_from_disparity(disparity, BUMBLEBEE)) == pytest.approx(depth, rel=1e-6)
    assert float(depth_accuracy(depth, BUMBLEBEE, 0.2)) == pytest.approx(accuracy, abs=6e-5)


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


def test_image_spans_half_a_pixel_beyond_the_outer_pixel_centres() -> None:
    inside = in_view(np.array([-0.5, 0.0, 319.0, 319.5]), BUMBLEBEE)
    outside = in_view(np.array([-0.51, 319.51, np.nan]), BUMBLEBEE)
    assert inside.all() and not outside.any()
