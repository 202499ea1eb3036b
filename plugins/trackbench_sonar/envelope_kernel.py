"""The compiled pass behind :func:`trackbench_sonar.profile.upper_envelope`, imported on first use."""

from __future__ import annotations

import math

import numba
import numpy as np


@numba.njit(cache=True, nogil=True)
def shallowest_crossings(
    across: np.ndarray, depth: np.ndarray, grid_m: float, first: int, last: int
) -> tuple[np.ndarray, np.ndarray]:  # pragma: no cover - compiled
    """:func:`~trackbench_sonar.profile.upper_envelope` segment by segment: each grid point keeps its shallowest crossing, first of equals."""
    size = last - first + 1
    envelope = np.full(size, np.nan)
    segment = np.full(size, -1, dtype=np.int64)
    for j in range(across.size - 1):
        x0, x1, z0, z1 = across[j], across[j + 1], depth[j], depth[j + 1]
        low = max(int(math.ceil(min(x0, x1) / grid_m)), first)
        high = min(int(math.floor(max(x0, x1) / grid_m)), last)
        run = x1 - x0
        for index in range(low, high + 1):
            share = (index * grid_m - x0) / run if run != 0.0 else 0.0
            crossing = z0 + min(max(share, 0.0), 1.0) * (z1 - z0)
            k = index - first
            best = envelope[k]
            # A sort puts nan last: any number beats it.
            if segment[k] < 0 or crossing < best or (best != best and crossing == crossing):
                envelope[k] = crossing
                segment[k] = j
    return envelope, segment


@numba.njit(cache=True, nogil=True)
def clean_returns(
    across: np.ndarray, depth: np.ndarray, window: int, spike_m: float
) -> tuple[np.ndarray, np.ndarray]:  # pragma: no cover - compiled
    """The finite returns less the spikes, in beam order, as :func:`~trackbench_sonar.profile.spike_mask` keeps them.

    ``window`` odd (an even one is :func:`~trackbench_sonar.profile.running_median`'s pandas case); the
    median of each window is of the returns that exist, as the array form's sort with ``inf`` padding takes it.
    """
    count = 0
    for i in range(across.size):
        if math.isfinite(across[i]) and math.isfinite(depth[i]):
            count += 1
    x = np.empty(count)
    z = np.empty(count)
    k = 0
    for i in range(across.size):
        if math.isfinite(across[i]) and math.isfinite(depth[i]):
            x[k], z[k] = across[i], depth[i]
            k += 1
    if window < 3 or not (0.0 < spike_m < math.inf) or count < 3:
        return x, z
    ranges = np.empty(count)
    for i in range(count):
        ranges[i] = math.hypot(x[i], z[i])
    half = window // 2
    values = np.empty(window)
    keep = np.zeros(count, dtype=np.bool_)
    kept = 0
    for i in range(count):
        start, stop = max(i - half, 0), min(i + half, count - 1)
        size = stop - start + 1
        for j in range(size):
            # Insertion sort of the window's ranges.
            value = ranges[start + j]
            slot = j
            while slot > 0 and values[slot - 1] > value:
                values[slot] = values[slot - 1]
                slot -= 1
            values[slot] = value
        median = (values[(size - 1) // 2] + values[size // 2]) / 2
        cosine = z[i] / ranges[i] if ranges[i] > 0.0 else 1.0
        if abs(ranges[i] - median) * abs(cosine) <= spike_m:
            keep[i] = True
            kept += 1
    return x[keep], z[keep]


@numba.njit(cache=True, nogil=True)
def profile_arrays(
    across: np.ndarray, depth: np.ndarray, grid_m: float, first: int, last: int
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:  # pragma: no cover - compiled
    """A :class:`~trackbench_sonar.profile.Profile`'s arrays from cleaned returns in beam order.

    The grid ``k * grid_m`` for ``k = first .. last``, the shallowest crossings there
    (:func:`shallowest_crossings`), the gap between the returns each was read between, and the returns
    sorted by across-track position (ties in beam order).
    """
    envelope, segment = shallowest_crossings(across, depth, grid_m, first, last)
    grid = np.arange(first, last + 1) * grid_m
    gap = np.empty(segment.size)
    for k in range(segment.size):
        j = segment[k] if segment[k] >= 0 else segment[k] + across.size - 1
        gap[k] = abs(across[j + 1] - across[j])
    order = np.argsort(across, kind="mergesort")
    return grid, envelope, gap, across[order], depth[order]
