"""Compiled numeric helpers of the camera geometry (:mod:`benchmark.modalities.camera.geometry`), bit for bit.

Trackers that compile their pair geometry need the very numbers the shared
Python forms give: :func:`python_hypot` is CPython's ``math.hypot`` (which
:class:`~benchmark.modalities.camera.geometry.Line` and
:func:`~benchmark.modalities.camera.geometry.cable_from_borders` call, and
which differs from libm's ``hypot`` on some inputs), and
:func:`cable_of_borders` is :func:`~benchmark.modalities.camera.geometry.cable_from_borders`
on plain floats.  Only plugins that compile import this module: it imports
numba, which listing the trackers must not.
"""

from __future__ import annotations

import math

import numba


@numba.njit(cache=True, nogil=True)
def _exact_square(x: float) -> tuple[float, float]:
    """``x * x`` as the sum of two doubles (Dekker), after Veltkamp's split of ``x`` into two halves of 26 bits."""
    t = x * 134217729.0
    high = t - (t - x)
    low = x - high
    p = high * high
    q = high * low + low * high
    z = p + q
    return z, p - z + q + low * low


@numba.njit(cache=True, nogil=True)
def python_hypot(x: float, y: float) -> float:
    """``math.hypot(x, y)`` as CPython 3.11 computes it (its ``vector_norm``), bit for bit; ``numpy.hypot`` is libm's.

    The squares are summed in extended precision and the square root
    corrected once, so the result is nearly always the correctly rounded one.
    Below ``2**-1024`` the values are divided by the largest instead of scaled, as CPython does.
    """
    x, y = abs(x), abs(y)
    largest = max(x, y)
    if math.isinf(largest):
        return largest
    if math.isnan(x) or math.isnan(y):
        return math.nan
    if largest == 0.0:
        return largest
    _, exponent = math.frexp(largest)
    if exponent < -1023:
        # Where the scale 2**-exponent would overflow, CPython divides by the largest instead.
        total, frac = 1.0, 0.0
        for value in (x, y):
            square = (value / largest) ** 2
            summed = total + square
            frac += (total - summed) + square
            total = summed
        return largest * math.sqrt(total - 1.0 + frac)
    scale = math.ldexp(1.0, -exponent)
    total, frac1, frac2 = 1.0, 0.0, 0.0
    for value in (x, y):
        high, low = _exact_square(value * scale)
        summed = total + high
        frac2 += (total - summed) + high
        total = summed
        frac1 += low
    h = math.sqrt(total - 1.0 + (frac1 + frac2))
    high, low = _exact_square(h)
    summed = total - high
    frac2 += (total - summed) - high
    total = summed
    frac1 -= low
    h += (total - 1.0 + (frac1 + frac2)) / (2.0 * h)
    return h / scale


@numba.njit(cache=True, nogil=True, error_model="numpy")
def cable_of_borders(
    x1: float, y1: float, ux: float, uy: float, x2: float, y2: float, vx: float, vy: float
) -> tuple[float, float, float, float]:
    """:func:`benchmark.modalities.camera.geometry.cable_from_borders` of two lines ``(x0, y0, dx, dy)``: ``(d, alpha, w, beta)``.

    The same operations in the same order, with CPython's :func:`python_hypot`,
    so the same state to the last bit; a division by zero gives an infinity
    or nan, as it does on the numpy floats the detector's lines are made of.
    """
    wx, wy = vx, vy
    if ux * wx + uy * wy < 0:
        wx, wy = -wx, -wy
    tx, ty = ux + wx, uy + wy
    norm = python_hypot(tx, ty)
    tx, ty = tx / norm, ty / norm
    if ty < 0 or (ty == 0 and tx > 0):
        tx, ty = -tx, -ty
    alpha = math.atan2(-tx, ty)
    nx, ny = ty, -tx
    half_angle = 0.5 * math.atan2(abs(ux * wy - uy * wx), ux * wx + uy * wy)
    m1x, m1y = uy, -ux
    if m1x * nx + m1y * ny < 0:
        m1x, m1y = -m1x, -m1y
    c1 = m1x * x1 + m1y * y1
    m2x, m2y = vy, -vx
    if m2x * nx + m2y * ny < 0:
        m2x, m2y = -m2x, -m2y
    c2 = m2x * x2 + m2y * y2
    d = (c1 + c2) / python_hypot(m1x + m2x, m1y + m2y)
    c0x, c0y = d * nx, d * ny
    crossing1 = (c1 - (m1x * c0x + m1y * c0y)) / (m1x * nx + m1y * ny)
    crossing2 = (c2 - (m2x * c0x + m2y * c0y)) / (m2x * nx + m2y * ny)
    slope1 = -(m1x * tx + m1y * ty) / (m1x * nx + m1y * ny)
    slope2 = -(m2x * tx + m2y * ty) / (m2x * nx + m2y * ny)
    if crossing1 <= crossing2:
        width, converging_up = crossing2 - crossing1, slope2 - slope1 < 0
    else:
        width, converging_up = crossing1 - crossing2, slope1 - slope2 < 0
    return d, alpha, width, half_angle if converging_up else -half_angle
