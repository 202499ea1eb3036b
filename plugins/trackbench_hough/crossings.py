"""The compiled loops of :mod:`trackbench_hough.edges`: zero crossings of a LoG response in one pass.

Kept apart so that listing the trackers does not import numba; the tracker
loads them on its first frame (:func:`compile_kernels` in ``reset``).  Each
kernel computes exactly what the numpy formulation it replaces computed,
element by element in ``float32``: the same differences, the same
comparisons, so the same bits; only the temporary arrays are gone.
"""

from __future__ import annotations

import numba
import numpy as np


@numba.njit(cache=True, nogil=True, inline="always")
def _marks(a: np.float32, b: np.float32, min_jump: np.float32) -> tuple[bool, bool]:
    """Whether the crossing between neighbours ``a``, ``b`` (if strong) marks ``a``, and whether it marks ``b``."""
    strong = (np.signbit(a) != np.signbit(b)) & (abs(a - b) >= min_jump)
    first_nearer = abs(a) <= abs(b)
    return strong & first_nearer, strong & (not first_nearer)


@numba.njit(cache=True, nogil=True)
def strong_crossings(response: np.ndarray, min_jump: np.float32) -> np.ndarray:
    """``uint8`` image, 255 on the nearer-to-zero pixel of each crossing whose jump reaches ``min_jump``.

    A crossing lies between vertical or horizontal neighbours ``a``, ``b`` of
    opposite sign bits with ``|a - b| >= min_jump`` (``float32``); it marks
    ``a`` when ``|a| <= |b|``, else ``b``.  Each crossing is judged once, row
    by row: the marks a row gets from its horizontal crossings and from the
    row below are gathered in buffers of one row, whose loops vectorise, and
    the marks the row below gets are kept for it.
    """
    height, width = response.shape
    edges = np.empty((height, width), np.uint8)
    from_above = np.zeros(width, np.uint8)
    from_left = np.zeros(width, np.uint8)
    from_right = np.zeros(width, np.uint8)
    for i in range(height):
        row, out = response[i], edges[i]
        for j in range(width - 1):
            first, second = _marks(row[j], row[j + 1], min_jump)
            from_right[j] = first
            from_left[j + 1] = second
        if i + 1 < height:
            below = response[i + 1]
            for j in range(width):
                first, second = _marks(row[j], below[j], min_jump)
                out[j] = (from_above[j] | first | from_right[j] | from_left[j]) * np.uint8(255)
                from_above[j] = second
        else:
            for j in range(width):
                out[j] = (from_above[j] | from_right[j] | from_left[j]) * np.uint8(255)
    return edges


@numba.njit(cache=True, nogil=True)
def crossing_jumps(response: np.ndarray, stride: int) -> np.ndarray:
    """``|a - b|`` (``float32``) of the crossings between horizontal neighbours on every ``stride``-th row,
    then between vertical neighbours on every ``stride``-th column, each in row-major order.

    Every pair's jump is written and the count advances only at a crossing,
    so the loop does not branch on the signs of noise.
    """
    height, width = response.shape
    jumps = np.empty(2 * height * width + 1, np.float32)
    count = 0
    for i in range(0, height, stride):
        row = response[i]
        for j in range(width - 1):
            a, b = row[j], row[j + 1]
            jumps[count] = abs(a - b)
            count += np.signbit(a) != np.signbit(b)
    for i in range(height - 1):
        row, below = response[i], response[i + 1]
        for j in range(0, width, stride):
            a, b = row[j], below[j]
            jumps[count] = abs(a - b)
            count += np.signbit(a) != np.signbit(b)
    return jumps[:count]


@numba.njit(cache=True, nogil=True)
def order_statistics(values: np.ndarray, rank: int) -> tuple[np.float32, np.float32]:
    """The ``rank - 1``-th and ``rank``-th smallest of non-negative, non-NaN ``float32`` values (``1 <= rank < n``).

    The bit patterns of non-negative floats sort as the floats do, so one
    pass counts the values by their upper 16 bits, the counts locate the
    one or two bins holding the two ranks, and only the values of those
    bins are sorted.
    """
    bits = values.view(np.uint32)
    counts = np.zeros(1 << 16, np.int64)
    for b in bits:
        counts[b >> 16] += 1
    below = 0
    first_bin = -1
    first_below = 0
    second_bin = -1
    for bin_ in range(1 << 16):
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
        b = bits[index] >> 16
        if b == first_bin or b == second_bin:
            picked[count] = values[index]
            count += 1
    picked.sort()
    return picked[rank - 1 - first_below], picked[rank - first_below]


def compile_kernels() -> None:
    """Compile (or load from numba's cache) the kernels now, on a tiny response."""
    tiny = np.zeros((2, 2), np.float32)
    strong_crossings(tiny, np.float32(1.0))
    crossing_jumps(tiny, 1)
    order_statistics(np.ones(2, np.float32), 1)
