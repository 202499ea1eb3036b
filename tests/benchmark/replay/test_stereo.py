"""The stereo view: a North-East map with the target, the measurement and the 2-sigma ellipse, the image pair above."""

from __future__ import annotations

import dataclasses
import math

import cv2
import numpy as np
import pytest

from benchmark.errors import DataError
from benchmark.modalities.stereo.geometry import to_north_east
from benchmark.modalities.stereo.model import ChaseNavigation, StereoMeasurement, StereoTruth, TargetEstimate
from benchmark.model import Frame
from benchmark.replay.record import Belief, Recording
from benchmark.replay.stereo import BOAT_RADIUS_PX, HEADING_PX, MAP_SIZE, PAIR_WIDTH, StereoView, grid_step

VIEW = StereoView()

TRUTH = StereoTruth(TargetEstimate((30.0, 20.0), (0.0, 3.0)), chase_position_m=(10.0, 12.0), chase_heading=0.4)
NAVIGATION = ChaseNavigation((10.2, 11.9), 0.41)


def frame_of(observation: object) -> Frame:
    return Frame(3, observation, TRUTH, NAVIGATION, time_s=0.6)


def decoded(jpeg: bytes) -> np.ndarray:
    return cv2.imdecode(np.frombuffer(jpeg, np.uint8), cv2.IMREAD_COLOR)


def test_a_measured_frame_is_a_map_with_the_measurement_as_a_cross() -> None:
    frame = frame_of(StereoMeasurement(400.0, 380.0, (21.0, 2.0)))
    picture = VIEW.picture(frame)
    assert (picture.width, picture.height) == MAP_SIZE == decoded(picture.jpeg).shape[1::-1]
    (cross,) = picture.marks
    north, east = to_north_east(21.0, 2.0, NAVIGATION.position_m, NAVIGATION.heading)
    assert (cross.shape, cross.role) == ("cross", "measurement")
    assert cross.points[:2] == pytest.approx(picture.plane.point(east, north))
    assert picture.plane.du > 0 and picture.plane.du == pytest.approx(-picture.plane.dv)  # one scale, north up
    u_low, v_low, u_high, v_high = picture.plane.box
    for north, east in (TRUTH.target.position_m, TRUTH.chase_position_m):
        u, v = picture.plane.u0 + picture.plane.du * east, picture.plane.v0 + picture.plane.dv * north
        assert u_low < u < u_high and v_low < v < v_high  # the map shows both boats


def test_an_image_pair_sits_side_by_side_above_the_map_and_has_no_measurement() -> None:
    left = np.full((240, 320, 3), (0, 0, 200), np.uint8)
    right = np.full((240, 320, 3), (200, 0, 0), np.uint8)
    picture = VIEW.picture(frame_of((left, right)))
    image = decoded(picture.jpeg)
    pair_height = 240 * PAIR_WIDTH // 320
    assert (picture.width, picture.height) == (2 * PAIR_WIDTH, pair_height + MAP_SIZE[1]) == image.shape[1::-1]
    assert np.abs(image[pair_height // 2, PAIR_WIDTH // 2].astype(int) - (0, 0, 200)).max() < 30
    assert np.abs(image[pair_height // 2, PAIR_WIDTH + PAIR_WIDTH // 2].astype(int) - (200, 0, 0)).max() < 30
    assert picture.plane.box == (0.0, float(pair_height), float(2 * PAIR_WIDTH), float(pair_height + MAP_SIZE[1]))
    assert picture.marks == ()


def test_a_target_is_a_boat_pointing_along_its_heading() -> None:
    frame = frame_of(None)
    picture = VIEW.picture(frame)
    circle, heading = VIEW.overlay(TRUTH, frame, picture)
    u, v = picture.plane.point(20.0, 30.0)
    assert circle.points == pytest.approx((u, v, BOAT_RADIUS_PX, BOAT_RADIUS_PX, 0.0))
    assert heading.points == pytest.approx((u, v, u + HEADING_PX, v))  # due east: to the right
    north = TargetEstimate((30.0, 20.0), (2.0, 0.0))
    assert VIEW.overlay(north, frame, picture)[1].points == pytest.approx((u, v, u, v - HEADING_PX))
    assert len(VIEW.overlay(TargetEstimate((30.0, 20.0), (0.0, 0.0)), frame, picture)) == 1  # at rest: no heading
    assert VIEW.state(TRUTH) == (30.0, 20.0, 0.0, 3.0) and VIEW.overlay(None, frame, picture) == []


def test_the_covariance_ellipse_is_the_two_sigma_ellipse_of_the_position_block() -> None:
    """North variance 4 m^2, east 1 m^2: on the map 2 * 2 m upright and 2 * 1 m across, at the mean."""
    picture = VIEW.picture(frame_of(None))
    covariance = np.diag([4.0, 1.0, 9.0, 9.0])
    covariance[0, 2] = covariance[2, 0] = 1.0  # velocity terms stay out of the ellipse
    belief = Belief("gaussian", mean=np.array([28.0, 21.0, 0.0, 3.0]), variance=np.diag(covariance), covariance=covariance)
    (ellipse,) = VIEW.belief_marks(belief, picture)
    u, v, major, minor, angle = ellipse.points
    scale = picture.plane.du
    assert (ellipse.shape, ellipse.role) == ("ellipse", "covariance")
    assert (u, v) == pytest.approx((picture.plane.u0 + scale * 21.0, picture.plane.v0 + picture.plane.dv * 28.0))
    assert (major, minor) == pytest.approx((4.0 * scale, 2.0 * scale))
    assert abs(math.cos(angle)) < 1e-9
    correlated = covariance.copy()
    correlated[0, 1] = correlated[1, 0] = 1.5  # north and east grow together: the long axis leans north-east
    (leaning,) = VIEW.belief_marks(dataclasses.replace(belief, covariance=correlated), picture)
    lean = leaning.points[4]
    assert math.cos(lean) * math.sin(lean) < 0  # right and up on the canvas (v grows down)
    assert VIEW.belief_marks(dataclasses.replace(belief, covariance=None), picture) == []


@pytest.mark.parametrize(("span", "step"), [(30.0, 5.0), (10.0, 2.0), (100.0, 20.0), (6.0, 1.0), (700.0, 200.0)])
def test_the_grid_spacing_is_one_two_or_five_times_a_power_of_ten(span: float, step: float) -> None:
    assert grid_step(span) == pytest.approx(step)


@pytest.mark.parametrize("name", ["stereo", "stereo-images"])
def test_a_recorded_stereo_filter_keeps_its_covariance_and_draws_its_ellipse(
    real_recordings: dict[str, Recording], name: str
) -> None:
    recording = real_recordings[name]
    assert recording.dimensions == ("north_m", "east_m", "north_mps", "east_mps") and recording.ended == ""
    for frame in recording.frames:
        belief = frame.belief
        assert belief is not None and belief.covariance.shape == (4, 4)
        assert np.array_equal(np.diag(belief.covariance), belief.variance)
        (ellipse,) = VIEW.belief_marks(belief, frame.picture)
        assert ellipse.finite and ellipse.role == "covariance"
        assert frame.picture.height == MAP_SIZE[1] + (180 if name == "stereo-images" else 0)


def test_an_image_pair_that_is_not_of_bgr_bytes_is_refused_naming_the_frame() -> None:
    pair = (np.zeros((24, 32, 3), np.float32), np.zeros((24, 32, 3), np.float32))
    with pytest.raises(DataError, match=r"frame 3: an image of the pair is a float32 array of \(24, 32, 3\)"):
        VIEW.picture(frame_of(pair))
