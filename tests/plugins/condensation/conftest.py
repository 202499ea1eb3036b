"""Drawn images for the condensation tracker's tests.

A cable of known state is drawn as the quadrilateral between its two border
lines (:func:`benchmark.modalities.camera.geometry.cable_borders`), filled with anti-aliased
edges ``contrast`` grey levels brighter (positive) or darker (negative) than
a background of smooth random texture and pixel noise.  Tests use the
helpers through the ``scene`` fixture.
"""

from __future__ import annotations

import types

import cv2
import numpy as np
import pytest

from benchmark.modalities.camera.geometry import Line, cable_borders, model_to_pixel
from benchmark.modalities.camera.model import CableState

SIZE = (320, 240)


def _far_points(line: Line, size: tuple[int, int]) -> list[tuple[float, float]]:
    """Two pixel points of a line far above and far below the image."""
    reach = 4.0 * max(size)
    sign = 1.0 if line.dy >= 0 else -1.0
    return [
        model_to_pixel(line.x0 - sign * reach * line.dx, line.y0 - sign * reach * line.dy, size),
        model_to_pixel(line.x0 + sign * reach * line.dx, line.y0 + sign * reach * line.dy, size),
    ]


def background(
    size: tuple[int, int] = SIZE, seed: int = 0, level: float = 120.0, texture: float = 10.0, noise: float = 4.0
) -> np.ndarray:
    """Smooth random texture around ``level`` plus pixel noise, ``float32`` of shape ``(H, W)``."""
    width, height = size
    rng = np.random.default_rng(seed)
    smooth = cv2.GaussianBlur(rng.standard_normal((height, width)).astype(np.float32), (0, 0), 5.0)
    smooth *= texture / max(float(smooth.std()), 1e-6)
    return (level + smooth + rng.normal(0.0, noise, (height, width))).astype(np.float32)


def paint_band(image: np.ndarray, state: CableState, contrast: float) -> np.ndarray:
    """Add ``contrast`` grey levels inside the cable of a near-vertical state."""
    height, width = image.shape
    size = (width, height)
    left, right = cable_borders(state)
    corners = _far_points(left, size) + _far_points(right, size)[::-1]
    mask = np.zeros((height, width), np.uint8)
    cv2.fillPoly(mask, [np.round(np.array(corners) * 16).astype(np.int32)], 255, lineType=cv2.LINE_AA, shift=4)
    return image + np.float32(contrast) * (mask.astype(np.float32) / 255.0)


def to_uint8(image: np.ndarray) -> np.ndarray:
    """Round and clip to a grey ``uint8`` image."""
    return np.clip(np.round(image), 0, 255).astype(np.uint8)


def draw_cable(
    state: CableState, contrast: float = -60.0, seed: int = 0, size: tuple[int, int] = SIZE, noise: float = 4.0
) -> np.ndarray:
    """A ``uint8`` image of one cable on textured ground (dark cable for negative contrast)."""
    return to_uint8(paint_band(background(size, seed, noise=noise), state, contrast))


def staircase(
    size: tuple[int, int] = SIZE, steps: tuple[float, ...] = (-40.0, 40.0), levels: tuple[int, ...] = (60, 120, 180)
) -> np.ndarray:
    """Vertical stripes of the given grey levels, changing at model x ``steps`` (brighter to the right by default)."""
    width, height = size
    x = np.arange(width) - (width - 1) / 2.0
    image = np.full(width, levels[0], np.float32)
    for position, level in zip(steps, levels[1:], strict=True):
        image[x > position] = level
    return np.tile(image, (height, 1)).astype(np.uint8)


@pytest.fixture(scope="session")
def scene() -> types.SimpleNamespace:
    """The drawing helpers: ``SIZE``, ``background``, ``paint_band``, ``to_uint8``, ``draw_cable``, ``staircase``."""
    return types.SimpleNamespace(
        SIZE=SIZE,
        background=background,
        paint_band=paint_band,
        to_uint8=to_uint8,
        draw_cable=draw_cable,
        staircase=staircase,
    )
