"""Tests of the sonar drawer: the swath's profile, the true pipe in green, the estimated position in red."""

from __future__ import annotations

import math

import numpy as np
import pytest

from benchmark.drawing import DATA_BGR, ESTIMATE_BGR, TRUTH_BGR
from benchmark.modalities.sonar.draw import PICTURE_SIZE, draw_sonar_frame
from benchmark.modalities.sonar.modality import SONAR
from benchmark.modalities.sonar.model import PipeEstimate, SonarTruth, Swath
from benchmark.model import Frame

ACROSS = np.linspace(-10.0, 10.0, 21)
SLOPING = Swath(ACROSS, 20.0 + 0.2 * ACROSS)
"""A bottom that deepens to starboard, 18 m deep at the port edge, 22 m at starboard."""

PIPE = SonarTruth(across_m=2.0, depth_m=19.8, burial=0.0, resolution_m=0.3)


def coloured(picture: np.ndarray, colour: tuple[int, int, int]) -> np.ndarray:
    return np.all(picture == np.array(colour, dtype=np.uint8), axis=2)


def red_columns(picture: np.ndarray) -> list[int]:
    """Columns that are red from top to bottom."""
    return np.flatnonzero(coloured(picture, ESTIMATE_BGR).all(axis=0)).tolist()


def test_the_sonar_modality_draws_with_it() -> None:
    assert SONAR.draw is draw_sonar_frame


def test_the_picture_is_bgr_uint8_of_the_promised_size_and_shows_the_returns_and_the_pipe() -> None:
    picture = draw_sonar_frame(Frame(0, SLOPING, PIPE), None)
    width, height = PICTURE_SIZE
    assert picture.dtype == np.uint8 and picture.shape == (height, width, 3)
    rows, columns = np.nonzero(coloured(picture, DATA_BGR))
    assert np.corrcoef(columns, rows)[0, 1] > 0.95  # deeper to starboard: lower to the right
    assert coloured(picture, TRUTH_BGR).any()
    assert not coloured(picture, ESTIMATE_BGR).any()


def test_an_estimate_on_the_pipe_is_a_red_line_through_the_green_circle() -> None:
    picture = draw_sonar_frame(Frame(0, SLOPING, PIPE), PipeEstimate(PIPE.across_m))
    (column,) = red_columns(picture)
    _, green_columns = np.nonzero(coloured(picture, TRUTH_BGR))
    assert abs((green_columns.min() + green_columns.max()) / 2 - column) <= 1


def test_an_estimate_at_a_return_is_drawn_at_that_return_s_column() -> None:
    port_most = draw_sonar_frame(Frame(0, SLOPING, None), None)
    _, grey_columns = np.nonzero(coloured(port_most, DATA_BGR))
    picture = draw_sonar_frame(Frame(0, SLOPING, None), PipeEstimate(ACROSS[0]))
    (column,) = red_columns(picture)
    assert abs(column - (grey_columns.min() + 1)) <= 1  # a return is a dot of radius 1


@pytest.mark.parametrize(("across", "column"), [(1e6, PICTURE_SIZE[0] - 1), (-1e300, 0)])
def test_an_estimate_outside_the_swath_is_drawn_at_its_edge(across: float, column: int) -> None:
    assert red_columns(draw_sonar_frame(Frame(0, SLOPING, PIPE), PipeEstimate(across))) == [column]


def test_a_ping_without_returns_or_truth_still_gets_a_picture() -> None:
    empty = Swath(np.full(5, math.nan), np.full(5, math.nan))
    picture = draw_sonar_frame(Frame(0, empty, None), PipeEstimate(0.0))
    assert picture.shape == (PICTURE_SIZE[1], PICTURE_SIZE[0], 3)
    assert len(red_columns(picture)) == 1 and not coloured(picture, TRUTH_BGR).any()
