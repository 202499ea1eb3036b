"""Which lines of the pipe the image shows as its borders: the paper's approximation, or the outline.

The measurement model (:mod:`trackbench_foresti.measurement`) projects two
world lines parallel to the pipe's axis ``Z``; a line through ``(X, Y)``
projects to the image line ``l = M^-T n`` with ``n = (Y - C_y, C_x - X,
0)``.  Which ``(X, Y)``:

``"plane"``
    seeds/004, section V-B and Fig. 9: "the two straight lines obtained as
    the intersection between the pipeline and the plane ``XZ``", ``X =
    -d/2`` and ``X = +d/2`` at ``Y = 0``, so ``n = (-C_y, C_x +- d/2, 0)``;
``"tangent"``
    the pipe's occluding contours: the generators where the planes through
    the camera centre tangent to the cylinder ``X^2 + Y^2 = r^2`` touch it.
    In the ``XY`` plane these are the tangent points ``T = r (cos psi, sin
    psi)`` from ``(C_x, C_y)``, ``psi = atan2(C_y, C_x) +- acos(r / D)``
    with ``D = |(C_x, C_y)|``; since ``T - C`` is perpendicular to ``T``,
    ``n`` is parallel to ``(cos psi, sin psi, 0)``, which is used (a line's
    image does not depend on the scale of ``n``).

The two agree when ``r / D`` is small.  Where it is not, the plane's lines
lie inside the outline: at the true poses of camera-dev/d04 (a 0.39 m pipe
1.15 m below a 640 x 480 camera) the plane model puts one border 6.8-9.4 px
inside the outline on average, 18.8 px at most; on the camera suite (0.2-0.25 m
pipes) at most 0.7 px.  The outline is nevertheless not the filter's default
(``ForestiParams.border_model``, :mod:`trackbench_foresti.params`): the edges
Canny finds on a shaded pipe lie inside its outline too, and the filter
fed them scores the same with either model.

Each model gives, for the left and right border, ``n`` and its derivatives
along ``C_x`` and ``C_y`` (the angles do not enter ``n``).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Literal

import numpy as np

BorderModelName = Literal["plane", "tangent"]
"""The names of :data:`BORDER_MODELS`."""

BorderModel = Callable[[float, float, float], tuple[np.ndarray, np.ndarray]]
"""``(C_x, C_y, radius) -> (normals, derivatives)``: ``(2, 3)`` and ``(2, 2, 3)`` arrays, left border first; the
derivatives' middle axis is ``(C_x, C_y)``."""

_PLANE_DERIVATIVES = np.array((((0.0, 1.0, 0.0), (-1.0, 0.0, 0.0)),) * 2)


def plane_borders(cx: float, cy: float, radius: float) -> tuple[np.ndarray, np.ndarray]:
    """``n`` of the lines ``X = -r`` and ``X = +r`` at ``Y = 0`` and their derivatives along ``(C_x, C_y)``.

    Returns
    -------
    normals : numpy.ndarray
        ``((-C_y, C_x + r, 0), (-C_y, C_x - r, 0))``.
    derivatives : numpy.ndarray
        ``(2, 2, 3)``: ``d n / d C_x = (0, 1, 0)`` and ``d n / d C_y = (-1, 0, 0)`` for both.

    References
    ----------
    seeds/004, section V-B, Fig. 9 and the Appendix, eqs. (18)-(22).
    """
    normals = np.array(((-cy, cx + radius, 0.0), (-cy, cx - radius, 0.0)))
    return normals, _PLANE_DERIVATIVES.copy()


def tangent_borders(cx: float, cy: float, radius: float) -> tuple[np.ndarray, np.ndarray]:
    """``n`` of the pipe's occluding contours seen from ``(C_x, C_y)`` and their derivatives along ``(C_x, C_y)``.

    Returns
    -------
    normals : numpy.ndarray
        ``(cos psi, sin psi, 0)`` for ``psi = atan2(C_y, C_x) + acos(r / D)``
        (left) and ``- acos(r / D)`` (right); NaN when the camera is not
        outside the pipe (``D <= r``), where no outline exists.
    derivatives : numpy.ndarray
        ``(2, 2, 3)``: ``(-sin psi, cos psi, 0) d psi / d C``.

    References
    ----------
    seeds/004, section II (the pipe as a cylinder around ``Z``); the
    outline replaces the approximation of section V-B, see the module docstring.
    """
    distance = math.hypot(cx, cy)
    if not distance > radius:
        return np.full((2, 3), math.nan), np.full((2, 2, 3), math.nan)
    towards = math.atan2(cy, cx)
    spread = math.acos(radius / distance)
    # d towards / d C and d spread / d C, with d acos(r / D) / d D = r / (D sqrt(D^2 - r^2)).
    d_towards = np.array((-cy, cx)) / distance**2
    d_spread = radius / (distance * math.sqrt(distance**2 - radius**2)) * np.array((cx, cy)) / distance
    normals = np.empty((2, 3))
    derivatives = np.empty((2, 2, 3))
    for border, sign in enumerate((1.0, -1.0)):
        psi = towards + sign * spread
        c, s = math.cos(psi), math.sin(psi)
        normals[border] = (c, s, 0.0)
        derivatives[border] = np.outer(d_towards + sign * d_spread, (-s, c, 0.0))
    return normals, derivatives


BORDER_MODELS: dict[str, BorderModel] = {"plane": plane_borders, "tangent": tangent_borders}
"""The border models by name (``ForestiParams.border_model``)."""
