"""Drawn images for the segmentation tracker's tests: a cable band of known state on sand or on blank ground.

``scene.cable(state)`` is a ``uint8`` image whose pixels between the two
border lines of ``state`` (:func:`benchmark.modalities.camera.geometry.cable_borders`)
are shifted by ``contrast`` grey levels, with anti-aliased sub-pixel borders,
over a ground that is either uniform (``texture=0``) or blurred random sand
plus pixel noise.  ``scene.segment(a, b, top, bottom)`` is a hand-made
straight segment ``u = a + b v``
(:class:`trackbench_segmentation.lines.Segments`).
"""

from __future__ import annotations

import types

import cv2
import numpy as np
import pytest
from trackbench_segmentation.lines import Segments

from benchmark.modalities.camera.geometry import Line, cable_borders, model_to_pixel
from benchmark.modalities.camera.model import CableState

SIZE = (320, 240)


def ground(size: tuple[int, int], seed: int, level: float, texture: float, noise: float) -> np.ndarray:
    """``float32`` ground of mean ``level``: smooth texture of spread ``texture`` plus pixel noise ``noise``."""
    width, height = size
    image = np.full((height, width), level, np.float32)
    rng = np.random.default_rng(seed)
    if texture > 0:
        relief = cv2.GaussianBlur(rng.standard_normal((height, width)).astype(np.float32), (0, 0), 4.0)
        image += relief * np.float32(texture / float(relief.std()))
    if noise > 0:
        image += rng.normal(0.0, noise, (height, width)).astype(np.float32)
    return image


def _at_height(line: Line, y: float, size: tuple[int, int]) -> tuple[float, float]:
    s = (y - line.y0) / line.dy
    return model_to_pixel(line.x0 + s * line.dx, y, size)


def band(state: CableState, size: tuple[int, int] = SIZE) -> np.ndarray:
    """Coverage in ``[0, 1]`` (``float32``, ``(H, W)``) of the band between the borders of a near-vertical cable."""
    width, height = size
    left, right = cable_borders(state)
    far = 3.0 * height
    polygon = [_at_height(left, far, size), _at_height(right, far, size)]
    polygon += [_at_height(right, -far, size), _at_height(left, -far, size)]
    cover = np.zeros((height, width), np.uint8)
    cv2.fillPoly(cover, [np.round(np.array(polygon) * 16).astype(np.int32)], 255, cv2.LINE_AA, 4)
    return cover.astype(np.float32) / np.float32(255.0)


def cable(
    state: CableState,
    contrast: float = -50.0,
    seed: int = 0,
    level: float = 130.0,
    texture: float = 10.0,
    noise: float = 4.0,
    size: tuple[int, int] = SIZE,
) -> np.ndarray:
    """A ``uint8`` image of one cable band over the ground."""
    image = ground(size, seed, level, texture, noise) + np.float32(contrast) * band(state, size)
    return np.clip(np.rint(image), 0, 255).astype(np.uint8)


def segment(a: float, b: float, top: int, bottom: int, gradient: float = 20.0, wobble: float = 0.0) -> Segments:
    """One segment on ``u = a + b v`` over rows ``top..bottom``, its columns alternately off by ``wobble``."""
    rows = np.arange(bottom, top - 1, -1)
    columns = a + b * rows + wobble * (-1.0) ** rows
    pieces = np.array([[0, len(rows)]])
    modulus = np.full((bottom + 1, int(columns.max()) + 3), gradient, np.float32)
    return Segments.from_pieces(rows, columns, pieces, modulus, (0, 0))


@pytest.fixture(scope="session")
def scene() -> types.SimpleNamespace:
    """The helpers: ``SIZE``, ``ground``, ``band``, ``cable``, ``segment``."""
    return types.SimpleNamespace(SIZE=SIZE, ground=ground, band=band, cable=cable, segment=segment)
