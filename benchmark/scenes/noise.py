"""Noise every kind of scene draws: smoothed Gaussian noise and a fast table of normal quantiles."""

from __future__ import annotations

import functools
import math
import statistics

import numpy as np


def smoothed_noise(rng: np.random.Generator, n: int, smooth: float) -> np.ndarray:
    """``n`` samples of unit-variance Gaussian noise smoothed by a Gaussian kernel.

    Parameters
    ----------
    rng : numpy.random.Generator
        Source of the white noise.
    n : int
        Number of samples.
    smooth : float
        Standard deviation of the kernel in samples; 0 gives white noise.

    Returns
    -------
    numpy.ndarray
        Stationary noise with unit standard deviation.
    """
    if smooth <= 0:
        return rng.standard_normal(n)
    half = int(math.ceil(4 * smooth))
    taps = np.arange(-half, half + 1, dtype=float)
    kernel = np.exp(-0.5 * (taps / smooth) ** 2)
    kernel /= math.sqrt(float(np.sum(kernel**2)))
    return np.convolve(rng.standard_normal(n + 2 * half), kernel, mode="valid")


@functools.cache
def gaussian_table(bits: int = 16) -> np.ndarray:
    """Quantiles of the standard normal distribution at ``(i + 1/2) / 2^bits``.

    Indexing it with uniform random integers gives standard normal samples
    (truncated beyond about 4.3 standard deviations), several times faster
    than :meth:`numpy.random.Generator.standard_normal`.
    """
    levels = 1 << bits
    normal = statistics.NormalDist()
    table = np.array([normal.inv_cdf((i + 0.5) / levels) for i in range(levels)], dtype=np.float32)
    table.flags.writeable = False
    return table


