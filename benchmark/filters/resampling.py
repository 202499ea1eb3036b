"""Resampling: draw ``N`` particles in proportion to their weights.

All four schemes return the indices of the chosen particles, so that the
caller copies states however it stores them.  They share one primitive: the
walk up the cumulative weights ``c_i = c_(i-1) + pi_i`` (seeds/000, eqs.
3.8-3.9, Figs. 3.6-3.7) done by binary search (``numpy.searchsorted``).  The
cumulative weights are divided by their last entry, so they never decrease
and end at exactly one, and the points are kept below one: round-off then
never yields an index past the end nor a particle of weight zero.  Weights
need not sum to one, only be finite and non-negative with a positive sum.
The schemes differ in how the ``N`` points on ``[0, 1)`` are drawn:

* multinomial: ``N`` independent uniforms (the thesis' Fig. 3.6);
* stratified: one uniform in each of the ``N`` strata ``[k/N, (k+1)/N)``;
* systematic: one uniform ``u`` and the points ``(k + u) / N``;
* residual: ``floor(N pi_i)`` copies of each particle, the rest multinomial
  on the residual weights.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Literal

import numpy as np

from benchmark.filters.particles import checked_weights, normalise_weights
from benchmark.lazy import lazy_module

# The compiled loops load on first use, so that importing the filters does not import numba.
_kernels = lazy_module("benchmark.filters.particle_kernels")

_BELOW_ONE = np.nextafter(1.0, 0.0)

Resampler = Callable[[np.ndarray, np.random.Generator], np.ndarray]
"""``(weights, rng) -> indices``: ``N`` indices into the particles."""


def cumulative_weights(weights: np.ndarray) -> np.ndarray:
    """Cumulative weights ``c_1..c_N`` scaled so that ``c_N`` is exactly 1 (seeds/000, eqs. 3.8-3.9).

    The running sums of :func:`~benchmark.filters.particles.normalise_weights`
    divided by the last, in one compiled pass
    (:func:`benchmark.filters.particle_kernels.cumulative`).
    """
    return _kernels.cumulative(checked_weights(weights))


def _walk(weights: np.ndarray, points: np.ndarray) -> np.ndarray:
    """For each point ``r`` in ``[0, 1)`` the first ``j`` with ``c_j > r`` (binary search)."""
    return _kernels.walk(checked_weights(weights), np.asarray(points, dtype=float), _BELOW_ONE)


def multinomial_resample(weights: np.ndarray, rng: np.random.Generator) -> np.ndarray:
    """Draw each index independently with probability ``pi_i``.

    References
    ----------
    seeds/000, section 3.4.1, Figs. 3.6-3.7.
    """
    return _walk(weights, rng.random(len(weights)))


def stratified_resample(weights: np.ndarray, rng: np.random.Generator) -> np.ndarray:
    """One uniform draw in each stratum ``[k/N, (k+1)/N)``."""
    n = len(weights)
    return _walk(weights, (np.arange(n) + rng.random(n)) / n)


def systematic_resample(weights: np.ndarray, rng: np.random.Generator) -> np.ndarray:
    """One uniform offset shared by the ``N`` evenly spaced points ``(k + u)/N``.

    Each particle gets ``floor(N pi_i)`` or ``ceil(N pi_i)`` copies.
    """
    n = len(weights)
    return _walk(weights, (np.arange(n) + rng.random()) / n)


def residual_resample(weights: np.ndarray, rng: np.random.Generator) -> np.ndarray:
    """``floor(N pi_i)`` copies of each particle, the remainder drawn multinomially."""
    weights = normalise_weights(weights)
    n = len(weights)
    expected = n * weights
    # The tolerance keeps e.g. 49 * (1/49) = 0.9999999999999999 at one copy.
    copies = np.floor(expected * (1.0 + 1e-12)).astype(np.int64)
    indices = np.repeat(np.arange(n), copies)
    remaining = n - indices.size
    if remaining == 0:
        return indices
    residual = np.maximum(expected - copies, 0.0)
    if residual.sum() <= 0:
        residual = weights
    return np.concatenate([indices, _walk(residual, rng.random(remaining))])


ResamplerName = Literal["multinomial", "stratified", "systematic", "residual"]
"""The name of a resampling scheme: a tracker parameter's type."""

RESAMPLERS: dict[ResamplerName, Resampler] = {
    "multinomial": multinomial_resample,
    "stratified": stratified_resample,
    "systematic": systematic_resample,
    "residual": residual_resample,
}
"""The resampling schemes by name, for tracker parameters."""
