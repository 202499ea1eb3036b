"""Compiled loops of the particle-set operations: weight normalisation, cumulative weights, quantiles.

Each replaces a chain of small NumPy calls on the ``(N,)`` weights, whose
per-call overhead a filter running at thousands of frames per second pays
on every frame, by one compiled pass that computes the same numbers bit for
bit: the same operations on the same values in the same order.  Sums over
the weights use :func:`pairwise_sum`, NumPy's own summation order, and
running sums are sequential as ``numpy.cumsum`` is; the property tests of
``tests/benchmark/filters`` compare every kernel with its NumPy
formulation exactly.

The module imports numba; :mod:`benchmark.filters` loads it on first use,
so that importing the filters (and listing the trackers) does not.
"""

from __future__ import annotations

import math

import numba
import numpy as np

_PAIRWISE_BLOCK = 128
"""Longest run NumPy sums with eight interleaved accumulators before splitting it in two."""


@numba.njit(cache=True, nogil=True)
def _block_sum(values: np.ndarray, start: int, n: int) -> float:
    """Sum of a run of at most ``_PAIRWISE_BLOCK`` values as NumPy adds it: eight interleaved accumulators."""
    if n < 8:
        total = 0.0
        for i in range(start, start + n):
            total += values[i]
        return total
    r = values[start : start + 8].copy()
    i = 8
    while i < n - n % 8:
        for j in range(8):
            r[j] += values[start + i + j]
        i += 8
    total = ((r[0] + r[1]) + (r[2] + r[3])) + ((r[4] + r[5]) + (r[6] + r[7]))
    while i < n:
        total += values[start + i]
        i += 1
    return total


@numba.njit(cache=True, nogil=True, inline="always")
def _left_size(n: int) -> int:
    """Length of the first half NumPy splits a run of ``n`` values into: half of it, down to a multiple of 8."""
    half = n // 2
    return half - half % 8


@numba.njit(cache=True, nogil=True)
def pairwise_sum(values: np.ndarray) -> float:
    """``values.sum()`` of a 1-D float array, bit for bit: NumPy's pairwise summation.

    NumPy (``numpy/_core/src/umath/loops_utils.h``) sums a run of more than
    ``_PAIRWISE_BLOCK`` values as the sum of its two halves, each summed the
    same way, and a shorter run with :func:`_block_sum`.  The recursion is
    walked here with an explicit stack (numba's cache does not keep
    recursive functions reliably): each frame is a run, waiting for its
    left half (phase 1) or its right half (phase 2).
    """
    starts = np.empty(64, dtype=np.int64)
    sizes = np.empty(64, dtype=np.int64)
    phases = np.empty(64, dtype=np.int64)
    lefts = np.empty(64)
    top = 0
    starts[0], sizes[0], phases[0] = 0, values.shape[0], 0
    while True:
        if sizes[top] > _PAIRWISE_BLOCK:
            phases[top] = 1
            starts[top + 1], sizes[top + 1], phases[top + 1] = starts[top], _left_size(sizes[top]), 0
            top += 1
            continue
        total = _block_sum(values, starts[top], sizes[top])
        top -= 1
        while top >= 0 and phases[top] == 2:
            total = lefts[top] + total
            top -= 1
        if top < 0:
            return total
        lefts[top] = total
        phases[top] = 2
        left = _left_size(sizes[top])
        starts[top + 1], sizes[top + 1], phases[top + 1] = starts[top] + left, sizes[top] - left, 0
        top += 1


@numba.njit(cache=True, nogil=True)
def first_invalid(weights: np.ndarray) -> int:
    """Index of the first weight that is negative or not finite; -1 when there is none."""
    for i in range(weights.shape[0]):
        if not (math.isfinite(weights[i]) and weights[i] >= 0.0):
            return i
    return -1


@numba.njit(cache=True, nogil=True)
def normalised(weights: np.ndarray) -> np.ndarray:
    """Finite non-negative weights scaled to sum to one, as :func:`benchmark.filters.particles.normalise_weights`.

    The weights are divided by the largest first, then by the sum of the
    quotients; all zero gives uniform weights.
    """
    n = weights.shape[0]
    peak = weights.max()
    if peak == 0:
        return np.full(n, 1.0 / n)
    scaled = weights / peak
    return scaled / pairwise_sum(scaled)


@numba.njit(cache=True, nogil=True)
def cumulative(weights: np.ndarray) -> np.ndarray:
    """Running sums of valid weights after :func:`normalised`, divided by the last (seeds/000, eqs. 3.8-3.9)."""
    running = np.cumsum(normalised(weights))
    return running / running[-1]


@numba.njit(cache=True, nogil=True)
def walk(weights: np.ndarray, points: np.ndarray, below_one: float) -> np.ndarray:
    """For each point, capped at ``below_one``, the first ``j`` with ``c_j > point`` (``c``: :func:`cumulative`).

    Points in ascending order (systematic and stratified resampling) are
    walked up the cumulative weights in one pass; a point below its
    predecessor is found by binary search.  Either way the index is the
    one ``numpy.searchsorted(c, point, side="right")`` gives.  The walk ends
    because ``c_N`` is exactly 1 and every point is below it.
    """
    running = cumulative(weights)
    indices = np.empty(points.shape[0], dtype=np.int64)
    j = 0
    previous = -math.inf
    for k in range(points.shape[0]):
        point = min(points[k], below_one)
        if point < previous:
            j = np.searchsorted(running, point, side="right")
        else:
            while running[j] <= point:
                j += 1
        indices[k] = j
        previous = point
    return indices


@numba.njit(cache=True, nogil=True)
def weighted_quantiles(
    values: np.ndarray, weights: np.ndarray, order: np.ndarray, q: np.ndarray
) -> np.ndarray:
    """The smallest value whose running weight, in ascending ``order``, reaches ``q`` of the total, for each ``q``."""
    running = np.cumsum(weights[order])
    rows = np.searchsorted(running, q * running[-1], side="left")
    out = np.empty(q.shape[0])
    for k in range(q.shape[0]):
        out[k] = values[order[min(rows[k], values.shape[0] - 1)]]
    return out


@numba.njit(cache=True, nogil=True)
def distinct_quantiles(values: np.ndarray, weights: np.ndarray, order: np.ndarray, q: np.ndarray) -> np.ndarray:
    """:func:`weighted_quantiles` when ``values[order]`` rises strictly; empty otherwise.

    Only distinct values (without NaN) have one ascending order; with ties
    the caller fixes the order by a stable sort.
    """
    for k in range(1, order.shape[0]):
        if not values[order[k]] > values[order[k - 1]]:
            return np.empty(0)
    return weighted_quantiles(values, weights, order, q)
