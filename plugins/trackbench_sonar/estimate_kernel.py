"""The compiled pass behind :func:`trackbench_sonar.estimate.peak_mean`, imported on first use."""

from __future__ import annotations

import math

import numba
import numpy as np

from trackbench_sonar.evidence_kernel import window_bounds


@numba.njit(cache=True, nogil=True)
def heaviest_window_mean(
    positions: np.ndarray, weights: np.ndarray, halfwidth: float
) -> tuple[float, float]:  # pragma: no cover - compiled
    """The weight of the heaviest window ``[x_i - h, x_i + h]`` and the weighted mean of the particles in it.

    The steps of the array form :func:`~trackbench_sonar.estimate.peak_mean` took, to the last bit: a
    stable sort of the positions, running sums of the weights and of the weights times the positions in
    that order (sums taken one after the other, as ``numpy.cumsum`` takes them), each window's
    bounds as ``numpy.searchsorted`` finds them (:func:`~trackbench_sonar.evidence_kernel.window_bounds`) and the first
    window of most weight.
    """
    order = np.argsort(positions, kind="mergesort")
    size = positions.size
    x = positions[order]
    mass = np.zeros(size + 1)
    moment = np.zeros(size + 1)
    for k in range(size):
        w = weights[order[k]]
        # The first sum is the first term itself, as numpy.cumsum has it (0.0 + -0.0 would be 0.0).
        mass[k + 1] = mass[k] + w if k > 0 else w
        moment[k + 1] = moment[k] + w * x[k] if k > 0 else w * x[k]
    low, high = window_bounds(x, x, halfwidth)
    best = -math.inf
    low_best = high_best = 0
    for k in range(size):
        window = mass[high[k]] - mass[low[k]]
        if window > best:
            best, low_best, high_best = window, low[k], high[k]
    return best, (moment[high_best] - moment[low_best]) / best if best > 0.0 else math.nan
