"""Pictures of camera frames: the image with the true and the estimated cable borders.

The image is downscaled so that its longer side is at most
:data:`MAX_SIDE` px, then each cable's two border lines
(:func:`~benchmark.modalities.camera.geometry.cable_borders`) are drawn as
chords through the image, the truth's in green, the estimate's in red: the
lines the detection rule compares (seeds/004, section VI-C, Table V;
``conventions.md`` section 3).
"""

from __future__ import annotations

import math

import cv2
import numpy as np

from benchmark.drawing import ESTIMATE_BGR, TRUTH_BGR, Colour
from benchmark.modalities.camera.geometry import ImageSize, Line, cable_borders, model_to_pixel
from benchmark.modalities.camera.model import CableState, CameraTruth
from benchmark.model import Frame

MAX_SIDE = 320
"""Longest side of a camera picture, px."""

_SHIFT = 4
"""Fractional bits of the points handed to :func:`cv2.line`."""


def draw_camera_frame(frame: Frame, estimate: CableState | None) -> np.ndarray:
    """The frame's image with the true cable's borders in green and the estimate's in red.

    Parameters
    ----------
    frame : Frame
        A camera frame: a ``uint8`` grey (or BGR) image and a
        :class:`~benchmark.modalities.camera.model.CameraTruth` or None;
        an unknown cable draws nothing for the truth.
    estimate : CableState or None
        The tracker's estimate; None draws nothing for it.

    Returns
    -------
    numpy.ndarray
        A ``uint8`` BGR picture whose longer side is at most :data:`MAX_SIDE` px.

    References
    ----------
    conventions.md sections 1 and 3 (the cable model and the chord through the image).
    """
    image = np.asarray(frame.observation)
    height, width = image.shape[:2]
    scale = min(1.0, MAX_SIDE / max(width, height))
    picture = _bgr(image)
    if scale < 1.0:
        size = (max(1, round(width * scale)), max(1, round(height * scale)))
        picture = cv2.resize(picture, size, interpolation=cv2.INTER_AREA)
    truth = frame.truth.cable if isinstance(frame.truth, CameraTruth) else None
    for state, colour in ((truth, TRUTH_BGR), (estimate, ESTIMATE_BGR)):
        if state is not None and state.is_known:
            _draw_borders(picture, state, (width, height), colour)
    return picture


def _bgr(image: np.ndarray) -> np.ndarray:
    """A BGR copy of a grey, grey-with-a-channel, BGR or BGRA image."""
    if image.ndim == 2 or image.shape[2] == 1:
        return cv2.cvtColor(image, cv2.COLOR_GRAY2BGR)
    if image.shape[2] == 4:
        return cv2.cvtColor(image, cv2.COLOR_BGRA2BGR)
    return image.copy()


def _draw_borders(picture: np.ndarray, state: CableState, size: ImageSize, colour: Colour) -> None:
    """Draw a cable's two borders, given in the model coordinates of an image of ``size``, onto ``picture``."""
    try:
        borders = cable_borders(state)
    except ValueError:  # a finite state whose border points overflow
        return
    factors = (picture.shape[1] / size[0], picture.shape[0] / size[1])
    for line in borders:
        chord = chord_ends(line, size)
        if chord is not None:
            start, end = (_fixed_point(model_to_pixel(x, y, size), factors) for x, y in chord)
            cv2.line(picture, start, end, colour, 1, cv2.LINE_8, _SHIFT)


def _fixed_point(pixel: tuple[float, float], factors: tuple[float, float]) -> tuple[int, int]:
    """Where pixel ``(u, v)`` of the image lands in the picture, in :func:`cv2.line`'s fixed-point coordinates."""
    (u, v), (factor_u, factor_v) = pixel, factors
    return round(((u + 0.5) * factor_u - 0.5) * 2**_SHIFT), round(((v + 0.5) * factor_v - 0.5) * 2**_SHIFT)


def chord_ends(line: Line, size: ImageSize) -> tuple[tuple[float, float], tuple[float, float]] | None:
    """The ends of a line's chord through the rectangle of pixel centres, in model coordinates; None if it misses."""
    half_w, half_h = (size[0] - 1) / 2.0, (size[1] - 1) / 2.0
    x0, y0 = line.nearest_point_to_origin()
    if math.hypot(x0, y0) > math.hypot(half_w, half_h):
        return None
    s_low, s_high = -math.inf, math.inf
    for p, dp, limit in ((x0, line.dx, half_w), (y0, line.dy, half_h)):
        if abs(dp) < 1e-12:
            if abs(p) > limit:
                return None
            continue
        a, b = (-limit - p) / dp, (limit - p) / dp
        s_low, s_high = max(s_low, min(a, b)), min(s_high, max(a, b))
    if s_low > s_high:
        return None
    return (x0 + s_low * line.dx, y0 + s_low * line.dy), (x0 + s_high * line.dx, y0 + s_high * line.dy)
