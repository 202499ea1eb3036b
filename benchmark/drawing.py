"""Small pictures of frames: the colours every modality's drawer uses and a plane-to-pixel mapping.

A modality may draw a frame (:attr:`benchmark.modality.Modality.draw`):
a small ``uint8`` BGR picture of the observation with the truth in
:data:`TRUTH_BGR` and the tracker's estimate in :data:`ESTIMATE_BGR`, so
that a report shows why a frame failed.  Images are drawn on directly;
sensors that deliver no image (a swath, a position) are drawn in a plane
through a :class:`Viewport`.  :func:`encode_png` turns a picture into the
bytes :class:`benchmark.results.Picture` keeps.
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import dataclass

import numpy as np

Colour = tuple[int, int, int]
"""An OpenCV colour: blue, green, red, 0-255."""

TRUTH_BGR: Colour = (0, 255, 0)
"""Green: the ground truth."""

ESTIMATE_BGR: Colour = (0, 0, 255)
"""Red: the tracker's estimate."""

DATA_BGR: Colour = (200, 200, 200)
"""Light grey: what the sensor delivered, where it is not an image."""

PNG_COMPRESSION = 3
"""zlib level of the PNGs: a noisy 320 x 240 camera picture takes about half the bytes of OpenCV's default, as fast."""


@dataclass(frozen=True)
class Viewport:
    """A linear map from a rectangle of a plane to the pixels of a picture.

    ``(left, top)`` lands on the centre of the top-left pixel and
    ``(right, bottom)`` on the centre of the bottom-right one; ``top`` may
    be below or above ``bottom`` (depth grows down, north grows up).

    Attributes
    ----------
    left, right : float
        Plane coordinates at the first and the last column.
    top, bottom : float
        Plane coordinates at the first and the last row.
    width, height : int
        Size of the picture, px.
    """

    left: float
    right: float
    top: float
    bottom: float
    width: int
    height: int

    @classmethod
    def around(
        cls,
        xs: Iterable[float],
        ys: Iterable[float],
        width: int,
        height: int,
        *,
        margin: float = 0.08,
        min_span: float = 1.0,
        y_up: bool = False,
        equal_scale: bool = False,
    ) -> Viewport:
        """The viewport that shows every finite point ``(x, y)`` with a margin on each side.

        Parameters
        ----------
        xs, ys : iterable of float
            Coordinates of the points; non-finite ones are left out.
        width, height : int
            Size of the picture, px.
        margin : float
            Share of each span added on both sides.
        min_span : float
            Smallest span of each axis, positive, so that one point still gets a view around it.
        y_up : bool
            Draw larger ``y`` higher up (north); by default larger ``y`` is lower (depth).
        equal_scale : bool
            Give both axes the same scale (a map), widening the narrower span.
        """
        spans = []
        for values in (xs, ys):
            finite = [float(value) for value in values if math.isfinite(value)] or [0.0]
            low, high = min(finite), max(finite)
            pad = max(high - low, min_span) * (0.5 + margin) - (high - low) / 2
            spans.append((low - pad, high + pad))
        if equal_scale:
            per_px = max((high - low) / max(px - 1, 1) for (low, high), px in zip(spans, (width, height)))
            spans = [
                ((low + high - per_px * (px - 1)) / 2, (low + high + per_px * (px - 1)) / 2)
                for (low, high), px in zip(spans, (width, height))
            ]
        (left, right), (low, high) = spans
        top, bottom = (high, low) if y_up else (low, high)
        return cls(left, right, top, bottom, width, height)

    def pixel(self, x: float, y: float) -> tuple[int, int]:
        """Column and row of the plane point ``(x, y)``, clamped to the picture."""
        u = (x - self.left) / (self.right - self.left) * (self.width - 1)
        v = (y - self.top) / (self.bottom - self.top) * (self.height - 1)
        return _clamp(u, self.width - 1), _clamp(v, self.height - 1)

    def blank(self, colour: Colour = (0, 0, 0)) -> np.ndarray:
        """A picture of the viewport's size filled with ``colour``."""
        return np.full((self.height, self.width, 3), colour, dtype=np.uint8)


def _clamp(value: float, largest: int) -> int:
    if not math.isfinite(value):
        return 0 if value < 0 or math.isnan(value) else largest
    return int(round(min(max(value, 0.0), float(largest))))


def encode_png(picture: np.ndarray) -> bytes:
    """A BGR ``uint8`` picture as PNG bytes.

    Raises
    ------
    ValueError
        If ``picture`` is not an ``(H, W, 3)`` ``uint8`` array with ``H, W >= 1``,
        or OpenCV cannot encode it.
    """
    if not (
        isinstance(picture, np.ndarray)
        and picture.dtype == np.uint8
        and picture.ndim == 3
        and picture.shape[2] == 3
        and picture.shape[0] >= 1
        and picture.shape[1] >= 1
    ):
        shown = f"{picture.dtype} array of shape {picture.shape}" if isinstance(picture, np.ndarray) else repr(picture)
        raise ValueError(f"a picture is an (H, W, 3) uint8 BGR array, not a {shown}")
    import cv2  # here, so that importing the runner does not import OpenCV

    ok, buffer = cv2.imencode(".png", picture, [cv2.IMWRITE_PNG_COMPRESSION, PNG_COMPRESSION])
    if not ok:
        raise ValueError(f"OpenCV could not encode a picture of shape {picture.shape} as PNG")
    return buffer.tobytes()
