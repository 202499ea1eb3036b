"""Ground truth of a rendered frame: the cable's silhouette in the image.

The pipe is the cylinder ``X^2 + Y^2 = r^2`` around the ``Z`` axis
(seeds/004, section II).  Seen from the camera centre ``C``, its outline
consists of two generator lines: the lines where a plane through ``C`` and
parallel to the axis touches the cylinder.  In the ``XY`` plane this is the
classic tangent problem from the point ``(Cx, Cy)`` to a circle of radius
``r``; each tangent point ``(X_t, Y_t)`` gives the generator
``{(X_t, Y_t, Z)}``.

The image of a generator is the line through the images of one of its
points and of its vanishing point (the image of the direction ``Z``), which
is well defined even when the camera looks straight down and the generator
is parallel to the image plane.  The two image lines are the cable borders;
:func:`benchmark.modalities.camera.geometry.cable_from_borders` turns them into the state
``(d, alpha, w, beta)`` of conventions.md section 1.

Unlike Foresti's measurement model, which approximates the borders by the
cylinder's intersection with the plane ``Y = 0`` (seeds/004, section V-B and
Fig. 9), these are the exact occluding contours.
"""

from __future__ import annotations

import math

import numpy as np

from benchmark.modalities.camera.geometry import Line, cable_from_borders
from benchmark.modalities.camera.model import CableState, CameraPose
from benchmark.modalities.camera.scenes.projection import (
    ImageSize,
    homogeneous_line,
    principal_point,
    projection_matrix,
)


def tangent_points(cx: float, cy: float, radius: float) -> tuple[tuple[float, float], tuple[float, float]]:
    """Where the two tangents from ``(cx, cy)`` touch the circle of radius ``radius``.

    Parameters
    ----------
    cx, cy : float
        The camera centre projected on the ``XY`` plane, in m.
    radius : float
        The pipe radius ``r`` in m.

    Returns
    -------
    tuple of (float, float)
        The two tangent points ``(X, Y)``.

    Raises
    ------
    ValueError
        If the point is not outside the circle (the camera is inside the pipe).

    References
    ----------
    seeds/004, section II: the pipe as a cylinder around the ``Z`` axis.
    """
    distance = math.hypot(cx, cy)
    if not distance > radius:
        raise ValueError(f"camera at (X={cx}, Y={cy}) is not outside the pipe of radius {radius}")
    towards_camera = math.atan2(cy, cx)
    spread = math.acos(radius / distance)
    first = (radius * math.cos(towards_camera + spread), radius * math.sin(towards_camera + spread))
    second = (radius * math.cos(towards_camera - spread), radius * math.sin(towards_camera - spread))
    return first, second


def pixel_line_to_model(line: np.ndarray, size: ImageSize) -> Line:
    """A homogeneous pixel line ``a u + b v + c = 0`` as a model-coordinate :class:`Line`.

    Two points of the line (its point nearest the image centre and one 100 px
    along it) go through :meth:`benchmark.modalities.camera.geometry.Line.from_pixels`.

    References
    ----------
    conventions.md section 1 (pixel and model coordinates).
    """
    a, b, c = (float(x) for x in line)
    norm2 = a * a + b * b
    if not norm2 > 0:
        raise ValueError(f"degenerate image line {line!r}")
    u0, v0 = principal_point(size)
    k = (a * u0 + b * v0 + c) / norm2
    foot = (u0 - k * a, v0 - k * b)
    scale = 100.0 / math.sqrt(norm2)
    return Line.from_pixels(foot, (foot[0] - b * scale, foot[1] + a * scale), size)


def cable_truth(pose: CameraPose, radius: float, focal_px: float, size: ImageSize) -> CableState:
    """The projected cable state ``(d, alpha, w, beta)`` of a camera pose.

    Parameters
    ----------
    pose : CameraPose
        Camera pose in the pipeline frame.
    radius : float
        Pipe radius in m.
    focal_px : float
        ``f / dx`` in px.
    size : tuple of int
        Image ``(W, H)``.

    Returns
    -------
    CableState
        With ``beta >= 0`` whenever the camera looks forward and down
        (``0 < phi < 90 deg``), as the borders then converge towards the top.

    References
    ----------
    seeds/000, section 4.2 and Table 4.1; seeds/004, section II;
    conventions.md section 1.
    """
    matrix = projection_matrix(pose, focal_px, size)
    first, second = (
        pixel_line_to_model(homogeneous_line(matrix, (x, y, pose.cz), (0.0, 0.0, 1.0)), size)
        for x, y in tangent_points(pose.cx, pose.cy, radius)
    )
    return cable_from_borders(first, second)
