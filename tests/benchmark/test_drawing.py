"""Tests of benchmark.drawing: the plane-to-pixel viewport and PNG encoding."""

from __future__ import annotations

import math

import cv2
import numpy as np
import pytest

from benchmark.drawing import Viewport, encode_png


def test_a_viewport_puts_its_corners_on_the_corner_pixels_and_clamps_the_rest() -> None:
    view = Viewport(left=-10.0, right=10.0, top=5.0, bottom=15.0, width=21, height=11)
    assert view.pixel(-10.0, 5.0) == (0, 0)
    assert view.pixel(10.0, 15.0) == (20, 10)
    assert view.pixel(0.0, 10.0) == (10, 5)
    assert view.pixel(1e300, -1e300) == (20, 0)
    assert view.pixel(-math.inf, math.inf) == (0, 10)
    assert view.pixel(math.nan, 10.0) == (0, 5)


def test_a_viewport_around_points_shows_them_all_inside_its_margin() -> None:
    view = Viewport.around([-3.0, 7.0, math.nan], [2.0, 4.0, math.inf], 101, 51)
    columns, rows = zip(*(view.pixel(x, y) for x, y in [(-3.0, 2.0), (7.0, 4.0)]))
    assert 0 < min(columns) < 10 and 90 < max(columns) < 100
    assert 0 < min(rows) < 5 and 45 < max(rows) < 50
    assert rows[0] < rows[1]  # larger y lower down by default


def test_a_map_viewport_has_north_up_and_one_scale() -> None:
    view = Viewport.around([0.0, 10.0], [0.0, 1.0], 101, 101, y_up=True, equal_scale=True)
    assert view.pixel(0.0, 1.0)[1] < view.pixel(0.0, 0.0)[1]
    per_px_x = (view.right - view.left) / 100
    per_px_y = (view.top - view.bottom) / 100
    assert per_px_x == pytest.approx(per_px_y) and per_px_x > 0


def test_one_point_gets_the_minimal_span_around_it() -> None:
    view = Viewport.around([5.0], [5.0], 11, 11, min_span=2.0, margin=0.0)
    assert (view.left, view.right, view.top, view.bottom) == (4.0, 6.0, 4.0, 6.0)


def test_a_picture_encodes_to_a_png_that_decodes_to_it() -> None:
    picture = np.random.default_rng(1).integers(0, 256, (7, 9, 3), dtype=np.uint8)
    png = encode_png(picture)
    assert png.startswith(b"\x89PNG")
    np.testing.assert_array_equal(cv2.imdecode(np.frombuffer(png, np.uint8), cv2.IMREAD_COLOR), picture)


@pytest.mark.parametrize(
    "picture",
    [np.zeros((4, 4), np.uint8), np.zeros((4, 4, 3), float), np.zeros((0, 4, 3), np.uint8), "a picture"],
)
def test_anything_but_a_bgr_uint8_picture_is_refused(picture: object) -> None:
    with pytest.raises(ValueError, match=r"\(H, W, 3\) uint8 BGR"):
        encode_png(picture)  # type: ignore[arg-type]
