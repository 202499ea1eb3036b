"""Drawn images and hand-made lines for the tests of seeds/004's feature extraction.

``draw.pipe(state)`` is a ``uint8`` image of a pipe of known
:class:`benchmark.modalities.camera.model.CableState`: the region between its
two border lines (:func:`benchmark.modalities.camera.geometry.cable_borders`),
shifted ``contrast`` grey levels from a background of blurred random
texture plus pixel noise, with anti-aliased sub-pixel borders.
``draw.candidate(line)`` turns a model-coordinate line into a
:class:`trackbench_foresti.features.CandidateLine` with a chosen reliability.
"""

from __future__ import annotations

import math
import types

import cv2
import numpy as np
import pytest
from trackbench_foresti.features import CandidateLine

from benchmark.modalities.camera.geometry import Line, cable_borders, model_to_pixel
from benchmark.modalities.camera.model import CableState

SIZE = (320, 240)


def sand(size: tuple[int, int] = SIZE, seed: int = 0, mean: float = 130.0, relief: float = 12.0, grain: float = 5.0):
    """Blurred Gaussian texture of standard deviation ``relief`` plus pixel noise ``grain``, ``float32`` (H, W)."""
    width, height = size
    rng = np.random.default_rng(seed)
    relief_map = cv2.GaussianBlur(rng.standard_normal((height, width)).astype(np.float32), (0, 0), 3.0)
    relief_map *= relief / float(relief_map.std())
    return mean + relief_map + rng.normal(0.0, grain, (height, width)).astype(np.float32)


def _crossing(line: Line, y: float, size: tuple[int, int]) -> tuple[float, float]:
    """The pixel point where a non-horizontal model line crosses height ``y``."""
    s = (y - line.y0) / line.dy
    return model_to_pixel(line.x0 + s * line.dx, y, size)


def pipe(
    state: CableState,
    contrast: float = -50.0,
    seed: int = 0,
    size: tuple[int, int] = SIZE,
    grain: float = 5.0,
) -> np.ndarray:
    """A ``uint8`` image of a pipe (darker than the sand for negative ``contrast``)."""
    width, height = size
    left, right = cable_borders(state)
    reach = 2.0 * height
    quad = [_crossing(left, reach, size), _crossing(right, reach, size)]
    quad += [_crossing(right, -reach, size), _crossing(left, -reach, size)]
    cover = np.zeros((height, width), np.uint8)
    scale = 1 << 4
    cv2.fillPoly(cover, [np.round(np.array(quad) * scale).astype(np.int32)], 255, cv2.LINE_AA, 4)
    image = sand(size, seed, grain=grain) + np.float32(contrast / 255.0) * cover.astype(np.float32)
    return np.clip(np.rint(image), 0, 255).astype(np.uint8)


def normal_form(line: Line) -> tuple[float, float]:
    """``(alpha, rho)`` of a model line, ``x cos(alpha) + y sin(alpha) = rho`` with ``alpha`` in ``[-pi/2, pi/2)``."""
    alpha = math.atan2(line.dx, -line.dy)
    rho = line.x0 * math.cos(alpha) + line.y0 * math.sin(alpha)
    if alpha >= math.pi / 2:
        alpha, rho = alpha - math.pi, -rho
    elif alpha < -math.pi / 2:
        alpha, rho = alpha + math.pi, -rho
    return alpha, rho


def candidate(
    line: Line,
    reliability: float = 0.8,
    domain: np.ndarray | None = None,
    size: tuple[int, int] = SIZE,
) -> CandidateLine:
    """A candidate on a model line; its domain covers every row (or column) unless given."""
    alpha, rho = normal_form(line)
    if domain is None:
        domain = np.ones(size[1] if abs(alpha) <= math.pi / 4 else size[0], dtype=bool)
    return CandidateLine(alpha, rho, 100.0, domain, 0.9, 0.9, 0.9, reliability)


def through_rows(top_u: float, bottom_u: float, size: tuple[int, int] = SIZE) -> Line:
    """The model line through pixel ``(top_u, 0)`` and ``(bottom_u, H-1)``."""
    return Line.from_pixels((top_u, 0.0), (bottom_u, size[1] - 1.0), size)


@pytest.fixture(scope="session")
def draw() -> types.SimpleNamespace:
    """Helpers: ``SIZE``, ``sand``, ``pipe``, ``normal_form``, ``candidate``, ``through_rows``."""
    return types.SimpleNamespace(
        SIZE=SIZE, sand=sand, pipe=pipe, normal_form=normal_form, candidate=candidate, through_rows=through_rows
    )
