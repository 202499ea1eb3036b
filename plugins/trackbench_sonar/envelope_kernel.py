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
