"""Tests of the camera drawer: the image, downscaled, with the true borders in green and the estimate's in red."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings

from benchmark.drawing import ESTIMATE_BGR, TRUTH_BGR
from benchmark.modalities.camera.draw import MAX_SIDE, draw_camera_frame
from benchmark.modalities.camera.geometry import cable_borders, pixel_to_model
from benchmark.modalities.camera.modality import CAMERA
from benchmark.modalities.camera.model import UNKNOWN_CABLE, CableState, CameraTruth
from benchmark.modalities.camera.strategies import cable_states
from benchmark.model import Frame

GREY = 100


def frame_of(width: int, height: int, cable: CableState | None = None, grey: int = GREY) -> Frame:
    image = np.full((height, width), grey, dtype=np.uint8)
    return Frame(0, image, None if cable is None else CameraTruth(cable))


def coloured(picture: np.ndarray, colour: tuple[int, int, int]) -> np.ndarray:
    """Mask of the pixels of exactly ``colour``."""
    return np.all(picture == np.array(colour, dtype=np.uint8), axis=2)


def test_the_camera_modality_draws_with_it() -> None:
    assert CAMERA.draw is draw_camera_frame


@pytest.mark.parametrize(
    ("size", "expected"),
    [((64, 48), (64, 48)), ((640, 480), (320, 240)), ((200, 800), (80, 320)), ((320, 9), (320, 9))],
)
def test_the_picture_is_bgr_uint8_with_its_longer_side_at_most_320(
    size: tuple[int, int], expected: tuple[int, int]
) -> None:
    picture = draw_camera_frame(frame_of(*size, CableState(0.0, 0.0, 10.0, 0.0)), None)
    assert picture.dtype == np.uint8 and picture.shape == (expected[1], expected[0], 3)
    assert max(picture.shape[:2]) <= MAX_SIDE


def test_a_vertical_truth_draws_two_green_columns_at_its_borders_and_nothing_else() -> None:
    picture = draw_camera_frame(frame_of(65, 40, CableState(d=0.0, alpha=0.0, w=20.0, beta=0.0)), None)
    green = coloured(picture, TRUTH_BGR)
    assert green[:, 22].all() and green[:, 42].all()  # u = 32 -+ 10
    assert green.sum() == 2 * 40
    assert (picture[~green] == GREY).all()
    assert not coloured(picture, ESTIMATE_BGR).any()


def test_the_estimate_s_borders_are_red_and_drawn_over_the_truth() -> None:
    frame = frame_of(65, 40, CableState(d=0.0, alpha=0.0, w=20.0, beta=0.0))
    picture = draw_camera_frame(frame, CableState(d=20.0, alpha=0.0, w=20.0, beta=0.0))
    red, green = coloured(picture, ESTIMATE_BGR), coloured(picture, TRUTH_BGR)
    assert red[:, 42].all() and red[:, 62].all() and red.sum() == 2 * 40  # u = 52 -+ 10
    assert green[:, 22].all() and green.sum() == 40  # the truth's right border is under the estimate's left one


def test_a_downscaled_picture_keeps_the_borders_where_they_were() -> None:
    # W = 640: the centre is u = 319.5, so the borders of d = -120, w = 41 are at u = 179 and 220;
    # halved, pixel centres u land on (u + 0.5) / 2 - 0.5: 89.25 and 109.75.
    picture = draw_camera_frame(frame_of(640, 480, CableState(d=-120.0, alpha=0.0, w=41.0, beta=0.0)), None)
    green = coloured(picture, TRUTH_BGR)
    assert green[:, 89].all() and green[:, 110].all()
    assert set(np.flatnonzero(green.any(axis=0))) == {89, 110}


@settings(max_examples=25, deadline=None)
@given(cable_states(81, 61))
def test_every_green_pixel_lies_on_a_true_border(cable: CableState) -> None:
    size = (81, 61)
    picture = draw_camera_frame(frame_of(*size, cable), None)
    rows, columns = np.nonzero(coloured(picture, TRUTH_BGR))
    assert len(rows) > 0  # the cable is in sight
    for v, u in zip(rows, columns):
        x, y = pixel_to_model(float(u), float(v), size)
        distance = min(abs((x - line.x0) * line.dy - (y - line.y0) * line.dx) for line in cable_borders(cable))
        assert distance <= 1.0


def test_an_unknown_or_absent_truth_and_no_estimate_draw_nothing() -> None:
    for frame in (frame_of(30, 20, UNKNOWN_CABLE), frame_of(30, 20)):
        picture = draw_camera_frame(frame, None)
        assert picture.shape == (20, 30, 3) and (picture == GREY).all()


@pytest.mark.parametrize("d", [1e4, -1e300, 1e308])
def test_an_estimate_far_off_the_image_draws_nothing_and_does_not_raise(d: float) -> None:
    picture = draw_camera_frame(frame_of(30, 20), CableState(d, 0.2, 1e308, 0.1))
    assert (picture == GREY).all()


def test_the_frame_s_image_is_left_alone_even_read_only_or_in_colour() -> None:
    frame = frame_of(64, 48, CableState(0.0, 0.0, 10.0, 0.0))
    frame.observation.setflags(write=False)
    draw_camera_frame(frame, CableState(3.0, 0.0, 10.0, 0.0))
    assert (frame.observation == GREY).all()
    colour = np.dstack([frame.observation, frame.observation // 2, frame.observation // 4])
    picture = draw_camera_frame(Frame(0, colour, frame.truth), None)
    assert tuple(picture[0, 0]) == (GREY, GREY // 2, GREY // 4) and (colour[..., 0] == GREY).all()
    assert coloured(picture, TRUTH_BGR)[:, 27].all()
