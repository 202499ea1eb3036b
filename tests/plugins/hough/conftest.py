"""Drawn test images for the Hough baseline: a band of known borders on textured sand.

The band is the polygon between the two border lines of a known
:class:`benchmark.modalities.camera.model.CableState` (:func:`benchmark.modalities.camera.geometry.cable_borders`),
filled with sub-pixel, anti-aliased edges, brighter or darker than a
background of smooth random texture plus pixel noise.  Tests reach the
drawing functions through the ``drawing`` fixture.
"""

from __future__ import annotations

import types

import cv2
import numpy as np
import pytest

from benchmark.modalities.camera.geometry import Line, cable_borders, model_to_pixel
from benchmark.modalities.camera.model import CableState

SIZE = (320, 240)


def _points_at_rows(line: Line, size: tuple[int, int], rows: tuple[float, float]) -> list[tuple[float, float]]:
    height = size[1]
    points = []
    for v in rows:
        y = (height - 1) / 2.0 - v
        s = (y - line.y0) / line.dy
        points.append(model_to_pixel(line.x0 + s * line.dx, y, size))
    return points


def background(
    size: tuple[int, int], seed: int, level: float = 120.0, texture: float = 12.0, noise: float = 6.0
) -> np.ndarray:
    """Smooth random texture around ``level`` grey plus pixel noise, as float32."""
    width, height = size
    rng = np.random.default_rng(seed)
    smooth = cv2.GaussianBlur(rng.normal(0.0, 1.0, (height, width)).astype(np.float32), (0, 0), 4.0)
    image = level + smooth * (texture / float(smooth.std())) + rng.normal(0.0, noise, (height, width))
    return image.astype(np.float32)


def paint_band(image: np.ndarray, state: CableState, contrast: float) -> np.ndarray:
    """Add ``contrast`` grey levels inside the band of a near-vertical cable state."""
    height, width = image.shape
    size = (width, height)
    left, right = cable_borders(state)
    rows = (-3.0 * height, 4.0 * height)
    polygon = np.array(_points_at_rows(left, size, rows) + _points_at_rows(right, size, rows)[::-1])
    mask = np.zeros((height, width), np.uint8)
    cv2.fillPoly(mask, [np.round(polygon * 16).astype(np.int32)], 255, lineType=cv2.LINE_AA, shift=4)
    return image + contrast * (mask.astype(np.float32) / 255.0)


def to_uint8(image: np.ndarray) -> np.ndarray:
    """Round and clip to a grey uint8 image."""
    return np.clip(np.round(image), 0, 255).astype(np.uint8)


def draw_cable(state: CableState, contrast: float = 60.0, seed: int = 0, size: tuple[int, int] = SIZE) -> np.ndarray:
    """A grey uint8 image of one cable band on textured background."""
    return to_uint8(paint_band(background(size, seed), state, contrast))


@pytest.fixture(scope="session")
def drawing() -> types.SimpleNamespace:
    """The drawing helpers of this module: ``SIZE``, ``background``, ``paint_band``, ``to_uint8``, ``draw_cable``."""
    return types.SimpleNamespace(
        SIZE=SIZE, background=background, paint_band=paint_band, to_uint8=to_uint8, draw_cable=draw_cable
    )
