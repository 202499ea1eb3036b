"""Pixel labels from a frame's ground truth.

Grau et al. learned their region classes from "a set of underwater cable
images" (seeds/000, section 2.2) whose labelling the thesis does not
describe.  Here the only label a camera frame carries is its cable state
(:class:`benchmark.modalities.camera.model.CameraTruth`): the cable region
is the strip between its two border lines
(:func:`benchmark.modalities.camera.geometry.cable_borders`), everything
else is ground.
"""

from __future__ import annotations

import numpy as np

from benchmark.modalities.camera.geometry import Line, cable_borders
from benchmark.modalities.camera.model import CableState


def model_grid(size: tuple[int, int]) -> tuple[np.ndarray, np.ndarray]:
    """Model coordinates ``(x, y)`` of every pixel centre of a ``(W, H)`` image, each ``(H, W)``."""
    width, height = size
    x = np.arange(width, dtype=float) - (width - 1) / 2.0
    y = (height - 1) / 2.0 - np.arange(height, dtype=float)
    return np.broadcast_to(x[None, :], (height, width)), np.broadcast_to(y[:, None], (height, width))


def signed_distance(line: Line, x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """Distance of model points from a line, positive on the side its normal ``(dy, -dx)`` points to."""
    return (x - line.x0) * line.dy - (y - line.y0) * line.dx


def inside_distances(cable: CableState, x: np.ndarray, y: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Distances of model points from the cable's left and right border, positive on the cable's side.

    A point lies on the cable where both are non-negative.
    """
    left, right = cable_borders(cable)
    # The side of a border the cable lies on is the side the other border's
    # point is on, whatever the lines' stored directions.
    left_side = np.sign(signed_distance(left, np.array(right.x0), np.array(right.y0)))
    right_side = np.sign(signed_distance(right, np.array(left.x0), np.array(left.y0)))
    return signed_distance(left, x, y) * left_side, signed_distance(right, x, y) * right_side


def cable_mask(cable: CableState, size: tuple[int, int]) -> np.ndarray:
    """The pixels whose centres lie between the cable's two borders.

    Parameters
    ----------
    cable : CableState
        A known cable state.
    size : tuple of int
        Image ``(W, H)`` in px.

    Returns
    -------
    numpy.ndarray
        ``bool`` array of shape ``(H, W)``.

    References
    ----------
    conventions.md section 1 (the border construction).
    """
    to_left, to_right = inside_distances(cable, *model_grid(size))
    return (to_left >= 0) & (to_right >= 0)


def outward_offsets(cable: CableState, points: np.ndarray, size: tuple[int, int]) -> np.ndarray:
    """How far pixel points lie outside the cable: beyond its borders, or minus the nearer border's distance inside.

    Parameters
    ----------
    cable : CableState
        A known cable state.
    points : numpy.ndarray
        ``(N, 2)`` pixel coordinates ``(u, v)``.
    size : tuple of int
        Image ``(W, H)`` in px.

    Returns
    -------
    numpy.ndarray
        ``(N,)`` distances in px: positive outside the cable, negative inside.
    """
    width, height = size
    x = points[:, 0] - (width - 1) / 2.0
    y = (height - 1) / 2.0 - points[:, 1]
    to_left, to_right = inside_distances(cable, x, y)
    beyond = np.maximum(np.maximum(-to_left, -to_right), 0.0)
    return np.where(beyond > 0, beyond, -np.minimum(to_left, to_right))
