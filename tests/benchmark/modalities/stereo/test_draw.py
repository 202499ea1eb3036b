"""Tests of the stereo drawer: a North-East map of the boats, the measurement and the estimate."""

from __future__ import annotations

import math

import numpy as np
import pytest

from benchmark.drawing import DATA_BGR, ESTIMATE_BGR, TRUTH_BGR
from benchmark.modalities.stereo.draw import MEASUREMENT_BGR, PICTURE_SIZE, draw_stereo_frame
from benchmark.modalities.stereo.modality import STEREO
from benchmark.modalities.stereo.model import ChaseNavigation, StereoMeasurement, StereoTruth, TargetEstimate
from benchmark.model import Frame

STILL = (0.0, 0.0)


def truth(
    target: tuple[float, float], velocity: tuple[float, float] = STILL, chase_heading: float = 0.0
) -> StereoTruth:
    return StereoTruth(TargetEstimate(target, velocity), chase_position_m=(0.0, 0.0), chase_heading=chase_heading)


def centre(picture: np.ndarray, colour: tuple[int, int, int]) -> np.ndarray:
    """Column and row of the middle of the pixels of ``colour`` (their bounding box, so a heading line moves it)."""
    rows, columns = np.nonzero(np.all(picture == np.array(colour, dtype=np.uint8), axis=2))
    assert len(rows), f"nothing drawn in {colour}"
    return np.array([(columns.min() + columns.max()) / 2, (rows.min() + rows.max()) / 2])


def drawn(picture: np.ndarray, colour: tuple[int, int, int]) -> bool:
    return bool(np.all(picture == np.array(colour, dtype=np.uint8), axis=2).any())


def test_the_stereo_modality_draws_with_it() -> None:
    assert STEREO.draw is draw_stereo_frame


def test_the_picture_is_a_square_bgr_uint8_map_with_north_up_and_east_right() -> None:
    north = draw_stereo_frame(Frame(0, None, truth((10.0, 0.0))), None)
    assert north.dtype == np.uint8 and north.shape == (PICTURE_SIZE, PICTURE_SIZE, 3)
    target, chase = centre(north, TRUTH_BGR), centre(north, DATA_BGR)
    assert target[1] < chase[1] - 50 and abs(target[0] - chase[0]) <= 1
    east = draw_stereo_frame(Frame(0, None, truth((0.0, 10.0), chase_heading=math.pi / 2)), None)
    target, chase = centre(east, TRUTH_BGR), centre(east, DATA_BGR)
    assert target[0] > chase[0] + 50 and abs(target[1] - chase[1]) <= 1
    assert not drawn(east, ESTIMATE_BGR) and not drawn(east, MEASUREMENT_BGR)


def test_one_metre_is_as_long_north_as_east() -> None:
    picture = draw_stereo_frame(Frame(0, None, truth((10.0, 5.0), chase_heading=math.atan2(5.0, 10.0))), None)
    offset = centre(picture, TRUTH_BGR) - centre(picture, DATA_BGR)
    assert offset[0] == pytest.approx(-offset[1] / 2, abs=1.0)


def test_the_heading_is_drawn_from_the_boat_along_its_course() -> None:
    picture = draw_stereo_frame(Frame(0, None, truth((10.0, 0.0), velocity=(0.0, 2.0))), None)  # heading east
    rows, columns = np.nonzero(np.all(picture == np.array(TRUTH_BGR, dtype=np.uint8), axis=2))
    circle = centre(draw_stereo_frame(Frame(0, None, truth((10.0, 0.0))), None), TRUTH_BGR)
    assert columns.max() - circle[0] > 10 and circle[0] - columns.min() <= 5


def test_the_estimate_is_red_where_it_puts_the_target() -> None:
    frame = Frame(0, None, truth((10.0, 0.0)))
    on_target = draw_stereo_frame(frame, TargetEstimate((10.0, 0.0), STILL))
    assert np.allclose(centre(on_target, ESTIMATE_BGR), centre(draw_stereo_frame(frame, None), TRUTH_BGR))
    astern = draw_stereo_frame(frame, TargetEstimate((-5.0, 0.0), STILL))
    assert centre(astern, ESTIMATE_BGR)[1] > centre(astern, DATA_BGR)[1] + 20


@pytest.mark.parametrize("heading", [0.0, math.pi / 2])
def test_a_measurement_is_a_yellow_cross_where_the_chase_boat_s_navigation_puts_it(heading: float) -> None:
    target = (10.0, 0.0) if heading == 0.0 else (0.0, 10.0)
    measurement = StereoMeasurement(left_px=0.0, right_px=0.0, relative_m=(10.0, 0.0))
    frame = Frame(0, measurement, truth(target, chase_heading=heading), ChaseNavigation((0.0, 0.0), heading))
    picture = draw_stereo_frame(frame, None)
    assert np.abs(centre(picture, MEASUREMENT_BGR) - centre(picture, TRUTH_BGR)).max() <= 1


def test_an_image_pair_or_a_frame_without_navigation_shows_no_measurement() -> None:
    pair = (np.zeros((4, 6, 3), np.uint8), np.zeros((4, 6, 3), np.uint8))
    measurement = StereoMeasurement(0.0, 0.0, (10.0, 0.0))
    for frame in (
        Frame(0, pair, truth((10.0, 0.0)), ChaseNavigation((0.0, 0.0), 0.0)),
        Frame(0, measurement, truth((10.0, 0.0)), None),
    ):
        picture = draw_stereo_frame(frame, None)
        assert drawn(picture, TRUTH_BGR) and not drawn(picture, MEASUREMENT_BGR)


def test_an_absurd_estimate_is_drawn_at_the_edge_without_hiding_the_boats() -> None:
    picture = draw_stereo_frame(Frame(0, None, truth((10.0, 0.0))), TargetEstimate((1e300, -1e300), STILL))
    assert np.linalg.norm(centre(picture, TRUTH_BGR) - centre(picture, DATA_BGR)) >= 1
    rows, columns = np.nonzero(np.all(picture == np.array(ESTIMATE_BGR, dtype=np.uint8), axis=2))
    assert rows.min() == 0 and columns.min() == 0


def test_a_frame_without_truth_still_gets_a_picture() -> None:
    picture = draw_stereo_frame(Frame(0, None, None), TargetEstimate((3.0, 4.0), (1.0, 0.0)))
    assert picture.shape == (PICTURE_SIZE, PICTURE_SIZE, 3) and drawn(picture, ESTIMATE_BGR)
    assert not drawn(picture, TRUTH_BGR)
