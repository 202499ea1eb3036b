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
    ``a`` when ``|a| <= |b|``, else ``b``.  Each pixel gathers the marks of
    its four crossings without branching on them, so the loop vectorises.
    """
    height, width = response.shape
    edges = np.zeros((height, width), np.uint8)
    for i in range(height):
        for j in range(width):
            a = response[i, j]
            marked = False
            if j + 1 < width:
                marked |= _marks(a, response[i, j + 1], min_jump)[0]
            if j > 0:
                marked |= _marks(response[i, j - 1], a, min_jump)[1]
            if i + 1 < height:
                marked |= _marks(a, response[i + 1, j], min_jump)[0]
            if i > 0:
                marked |= _marks(response[i - 1, j], a, min_jump)[1]
            edges[i, j] = 255 if marked else 0
    return edges


@numba.njit(cache=True, nogil=True)
def crossing_jumps(response: np.ndarray, stride: int) -> np.ndarray:
    """``|a - b|`` (``float32``) of the crossings between horizontal neighbours on every ``stride``-th row,
    then between vertical neighbours on every ``stride``-th column, each in row-major order."""
    height, width = response.shape
    jumps = np.empty(2 * height * width, np.float32)
    count = 0
    for i in range(0, height, stride):
        for j in range(width - 1):
            a, b = response[i, j], response[i, j + 1]
            if np.signbit(a) != np.signbit(b):
                jumps[count] = abs(a - b)
                count += 1
    for i in range(height - 1):
        for j in range(0, width, stride):
            a, b = response[i, j], response[i + 1, j]
            if np.signbit(a) != np.signbit(b):
                jumps[count] = abs(a - b)
                count += 1
    return jumps[:count]


def compile_kernels() -> None:
    """Compile (or load from numba's cache) the kernels now, on a tiny response."""
    tiny = np.zeros((2, 2), np.float32)
    strong_crossings(tiny, np.float32(1.0))
    crossing_jumps(tiny, 1)
