"""The compiled loops of :mod:`trackbench_hough.edges`: zero crossings of a LoG response in one pass.

Kept apart so that listing the trackers does not import numba; the tracker
loads them on its first frame (:func:`compile_kernels` in ``reset``).  Each
kernel computes exactly what the numpy formulation it replaces computed,
element by element in ``float32``: the same differences, the same
comparisons, so the same bits; only the temporary arrays are gone.
"""

from __future__ import annotations

import math

import numba
import numpy as np


_MARK = np.uint8(255)
"""The value of a border pixel in the edge image."""


@numba.njit(cache=True, nogil=True, inline="always")
def _sign_bit(value: np.float32) -> bool:
    """``numpy.signbit(value)`` (set for -0.0 and for NaNs with the bit set), as a copy of the sign the compiler inlines."""
    return math.copysign(1.0, value) < 0.0


@numba.njit(cache=True, nogil=True, inline="always")
def _marks(a: np.float32, b: np.float32, min_jump: np.float32) -> tuple[bool, bool]:
    """Whether the crossing between neighbours ``a``, ``b`` (if strong) marks ``a``, and whether it marks ``b``."""
    strong = (_sign_bit(a) != _sign_bit(b)) & (abs(a - b) >= min_jump)
    first_nearer = abs(a) <= abs(b)
    return strong & first_nearer, strong & (not first_nearer)


@numba.njit(cache=True, nogil=True)
def strong_crossings_in(response: np.ndarray, min_jump: np.float32, rectangles: np.ndarray) -> np.ndarray:
    """``uint8`` image, inside the rectangles 255 on the nearer-to-zero pixel of each crossing whose jump
    reaches ``min_jump``, 0 elsewhere.

    ``rectangles`` holds rows ``(row0, row1, col0, col1)``, ends excluded.
    A crossing lies between vertical or horizontal neighbours ``a``, ``b``
    (``a`` left of or above ``b``) of opposite sign bits with
    ``|a - b| >= min_jump`` (``float32``); it marks ``a`` when
    ``|a| <= |b|``, else ``b`` (:func:`_marks`).  Each crossing is judged
    once, row by row: the marks a row gets from its horizontal crossings
    and from the row below are gathered in buffers of one row, and the
    marks the row below gets are kept for it.  The crossings with the
    pixels just outside a rectangle are judged too, so that every pixel
    inside gets the value it gets in the whole frame, without cutting the
    response.  The pixels are read from the flat response at unsigned
    offsets, which spares every read the check for a negative index.
    """
    height, width = response.shape
    edges = np.zeros((height, width), np.uint8)
    pixels, marked = response.ravel(), edges.ravel()
    from_above = np.zeros(width, np.uint8)
    from_left = np.zeros(width, np.uint8)
    from_right = np.zeros(width, np.uint8)
    row_length, one = np.uint64(width), np.uint64(1)
    for rectangle in range(rectangles.shape[0]):
        row0, row1 = max(rectangles[rectangle, 0], 0), min(rectangles[rectangle, 1], height)
        col0, col1 = max(rectangles[rectangle, 2], 0), min(rectangles[rectangle, 3], width)
        if col0 >= col1 or row0 >= row1:
            continue
        first, last = np.uint64(col0), np.uint64(col1)
        # Horizontal crossings (j, j + 1) that touch the rectangle's columns; from_left[0] and
        # from_right[width - 1] stay 0, as no crossing marks them.
        pair0, pair1 = np.uint64(max(col0 - 1, 0)), np.uint64(min(col1, width - 1))
        if row0 > 0:
            start = np.uint64(row0) * row_length
            for j in range(first, last):
                from_above[j] = _marks(pixels[start - row_length + j], pixels[start + j], min_jump)[1]
        else:
            for j in range(first, last):
                from_above[j] = 0
        for i in range(row0, row1):
            start = np.uint64(i) * row_length
            for j in range(pair0, pair1):
                from_right[j], from_left[j + one] = _marks(pixels[start + j], pixels[start + j + one], min_jump)
            if i + 1 < height:
                below = start + row_length
                for j in range(first, last):
                    down, up = _marks(pixels[start + j], pixels[below + j], min_jump)
                    marked[start + j] = (from_above[j] | down | from_right[j] | from_left[j]) * _MARK
                    from_above[j] = up
            else:
                for j in range(first, last):
                    marked[start + j] = (from_above[j] | from_right[j] | from_left[j]) * _MARK
    return edges


@numba.njit(cache=True, nogil=True)
def crossing_jumps(response: np.ndarray, stride: int) -> np.ndarray:
    """``|a - b|`` (``float32``) of the crossings between horizontal neighbours on every
    ``stride``-th row, then between vertical neighbours on every ``stride``-th column, each in row-major order.

    Every pair's jump is written and the count advances only at a crossing,
    so the loop does not branch on the signs of noise.  The pixels are
    read from the flat response at unsigned offsets, which spares every
    read the check for a negative index.
    """
    height, width = response.shape
    sampled_rows, sampled_columns = (height + stride - 1) // stride, (width + stride - 1) // stride
    jumps = np.empty(sampled_rows * max(width - 1, 0) + max(height - 1, 0) * sampled_columns + 1, np.float32)
    pixels = response.ravel()
    row_length, one = np.uint64(width), np.uint64(1)
    count = np.uint64(0)
    for i in range(0, height, stride):
        start = np.uint64(i) * row_length
        for j in range(np.uint64(0), np.uint64(max(width - 1, 0))):
            a, b = pixels[start + j], pixels[start + j + one]
            jumps[count] = abs(a - b)
            count += np.uint64(_sign_bit(a) != _sign_bit(b))
    for i in range(height - 1):
        start = np.uint64(i) * row_length
        for j in range(np.uint64(0), row_length, np.uint64(stride)):
            a, b = pixels[start + j], pixels[start + row_length + j]
            jumps[count] = abs(a - b)
            count += np.uint64(_sign_bit(a) != _sign_bit(b))
    return jumps[:count]


@numba.njit(cache=True, nogil=True)
def order_statistics(values: np.ndarray, rank: int) -> tuple[np.float32, np.float32]:
    """The ``rank - 1``-th and ``rank``-th smallest of non-negative, non-NaN ``float32`` values (``1 <= rank < n``).

    The bit patterns of non-negative floats sort as the floats do, so one
    pass finds the range of their upper 16 bits, one counts the values by
    them, the counts locate the one or two bins holding the two ranks, and
    only the values of those bins are sorted.
    """
    bits = values.view(np.uint32)
    lowest, highest = 0xFFFF, 0
    for b in bits:
        key = np.int64(b >> 16)
        lowest, highest = min(lowest, key), max(highest, key)
    counts = np.zeros(highest - lowest + 1, np.int64)
    for b in bits:
        counts[np.int64(b >> 16) - lowest] += 1
    below = 0
    first_bin = -1
    first_below = 0
    second_bin = -1
    for bin_ in range(counts.size):
        reached = below + counts[bin_]
        if first_bin < 0 and reached >= rank:
            first_bin, first_below = bin_, below
        if reached >= rank + 1:
            second_bin = bin_
            break
        below = reached
    size = counts[first_bin] + (counts[second_bin] if second_bin != first_bin else 0)
    picked = np.empty(size, np.float32)
    count = 0
    for index in range(values.size):
        b = np.int64(bits[index] >> 16) - lowest
        if b == first_bin or b == second_bin:
            picked[count] = values[index]
            count += 1
    picked.sort()
    return picked[rank - 1 - first_below], picked[rank - first_below]


@numba.njit(cache=True, nogil=True)
def middle_jumps(response: np.ndarray, stride: int) -> tuple[np.ndarray, bool, np.float32, np.float32]:
    """:func:`crossing_jumps` and, when there are two or more and none is NaN, their ``n // 2 - 1``-th and
    ``n // 2``-th smallest (:func:`order_statistics`); otherwise whether one is NaN, and zeros."""
    jumps = crossing_jumps(response, stride)
    has_nan = False
    for jump in jumps:
        has_nan |= np.isnan(jump)
    if jumps.size < 2 or has_nan:
        return jumps, has_nan, np.float32(0.0), np.float32(0.0)
    below, middle = order_statistics(jumps, jumps.size // 2)
    return jumps, has_nan, below, middle


def compile_kernels() -> None:
    """Compile (or load from numba's cache) the kernels now, on a tiny response."""
    tiny = np.zeros((2, 2), np.float32)
    strong_crossings_in(tiny, np.float32(1.0), np.zeros((1, 4), np.int64))
    crossing_jumps(tiny, 1)
    order_statistics(np.ones(2, np.float32), 1)
    middle_jumps(tiny, 1)
