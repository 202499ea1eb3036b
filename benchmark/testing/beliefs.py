"""The beliefs a filter tracker may expose, and the invariants they keep.

A tracker that filters may let the conformance kit look at its belief
through one of two runtime-checkable protocols:

* :class:`ParticleBelief`: a weighted particle set, ``particles`` of shape
  ``(N, D)`` and ``weights`` of shape ``(N,)``;
* :class:`GaussianBelief`: a Gaussian, ``mean`` of shape ``(D,)`` and
  ``covariance`` of shape ``(D, D)``.

Either may be None while the tracker holds no belief (before it has a
start, or while it has lost the target).  :func:`particle_belief_problems`
and :func:`gaussian_belief_problems` list what is wrong with one belief;
the ``belief_invariants`` check of :mod:`benchmark.testing.checks` applies
them after ``reset`` and after every ``step``.
"""

from __future__ import annotations

from typing import Protocol, runtime_checkable

import numpy as np

__all__ = [
    "WEIGHT_SUM_TOLERANCE",
    "declares_belief",
    "GaussianBelief",
    "ParticleBelief",
    "gaussian_belief_problems",
    "particle_belief_problems",
]

WEIGHT_SUM_TOLERANCE = 1e-9
"""How far float64 weights of a particle belief may sum from one; weights of a coarser dtype get ``N * eps``."""

SYMMETRY_TOLERANCE = 1e-9
"""Relative tolerance of a float64 covariance's symmetry and smallest eigenvalue; a coarser dtype gets ``10 * D * eps``."""


def declares_belief(tracker_class: type) -> bool:
    """Whether a tracker class has the attributes of :class:`ParticleBelief` or :class:`GaussianBelief`.

    Asked of the class, since an instance may only be able to answer once it is reset.
    """
    return any(all(hasattr(tracker_class, name) for name in names) for names in (("particles", "weights"), ("mean", "covariance")))


def dtype_tolerance(value: object, floor: float, terms: int) -> float:
    """``floor``, or the rounding a sum of ``terms`` values of ``value``'s float dtype can make, whichever is larger."""
    dtype = getattr(value, "dtype", None)
    eps = float(np.finfo(dtype).eps) if dtype is not None and np.issubdtype(dtype, np.floating) else 0.0
    return max(floor, terms * eps)


@runtime_checkable
class ParticleBelief(Protocol):
    """A tracker whose belief is a weighted particle set.

    Attributes
    ----------
    particles : numpy.ndarray or None
        The states of the particles, shape ``(N, D)``; None while there is no belief.
    weights : numpy.ndarray or None
        Their weights, shape ``(N,)``: finite, non-negative, summing to one.
    """

    @property
    def particles(self) -> np.ndarray | None: ...

    @property
    def weights(self) -> np.ndarray | None: ...


@runtime_checkable
class GaussianBelief(Protocol):
    """A tracker whose belief is a Gaussian.

    Attributes
    ----------
    mean : numpy.ndarray or None
        The mean, shape ``(D,)``; None while there is no belief.
    covariance : numpy.ndarray or None
        The covariance, shape ``(D, D)``: finite, symmetric, positive semi-definite.
    """

    @property
    def mean(self) -> np.ndarray | None: ...

    @property
    def covariance(self) -> np.ndarray | None: ...


def _as_float(value: object, name: str, problems: list[str]) -> np.ndarray | None:
    try:
        return np.asarray(value, dtype=float)
    except (TypeError, ValueError) as exc:
        problems.append(f"{name} is not an array of numbers: {exc}")
        return None


def _all_finite(values: np.ndarray, what: str, problems: list[str]) -> bool:
    """Whether every value is finite; if not, a line saying how many ``what`` are not is added to ``problems``."""
    bad = int(np.count_nonzero(~np.isfinite(values)))
    if bad:
        problems.append(f"{bad} {what} are not finite")
    return not bad


def particle_belief_problems(particles: object, weights: object) -> list[str]:
    """What is wrong with a weighted particle set.

    Parameters
    ----------
    particles : array_like
        The states, shape ``(N, D)`` with ``N >= 1``.
    weights : array_like
        The weights, shape ``(N,)``.

    Returns
    -------
    list of str
        One line per broken invariant, empty when there is none: the shapes
        match, the particles and weights are finite, the weights are
        non-negative and sum to one within :data:`WEIGHT_SUM_TOLERANCE`, and
        the effective sample size ``1 / sum(w^2)`` lies in ``[1, N]``.
    """
    problems: list[str] = []
    states = _as_float(particles, "particles", problems)
    w = _as_float(weights, "weights", problems)
    if states is None or w is None:
        return problems
    if states.ndim != 2 or states.shape[0] == 0:
        problems.append(f"particles must have shape (N, D) with N >= 1, not {states.shape}")
        return problems
    if w.shape != (states.shape[0],):
        problems.append(f"weights of shape {w.shape} do not match particles of shape {states.shape}")
        return problems
    _all_finite(states, "particle coordinates", problems)
    if not _all_finite(w, "weights", problems):
        return problems
    if np.any(w < 0):
        bad = int(np.flatnonzero(w < 0)[0])
        problems.append(f"{int(np.sum(w < 0))} weights are negative (weight {bad} is {w[bad]!r})")
    total = float(np.sum(w))
    tolerance = dtype_tolerance(weights, WEIGHT_SUM_TOLERANCE, w.size)
    if abs(total - 1.0) > tolerance:
        problems.append(f"weights sum to {total!r}, not 1 within {tolerance:g}")
    square = float(np.dot(w, w))
    ess = 1.0 / square if square > 0 else np.inf
    n = w.size
    slack = tolerance * n
    if not (1.0 - slack <= ess <= n + slack):
        problems.append(f"effective sample size 1/sum(w^2) = {ess!r} is outside [1, {n}]")
    return problems


def gaussian_belief_problems(mean: object, cov: object, tol: float = SYMMETRY_TOLERANCE) -> list[str]:
    """What is wrong with a Gaussian belief.

    Parameters
    ----------
    mean : array_like
        The mean, shape ``(D,)``.
    cov : array_like
        The covariance, shape ``(D, D)``.
    tol : float
        Relative tolerance for float64 (:func:`dtype_tolerance` widens it for
        coarser dtypes): with each component scaled by its own standard
        deviation (``C_ij / sqrt(|C_ii| |C_jj|)``), the covariance may be
        asymmetric by ``tol`` and its smallest eigenvalue as low as ``-tol``;
        a negative variance is an error whatever its size.

    Returns
    -------
    list of str
        One line per broken invariant, empty when there is none: the shapes
        match, mean and covariance are finite, the covariance is symmetric
        and positive semi-definite.
    """
    problems: list[str] = []
    mu = _as_float(mean, "mean", problems)
    sigma = _as_float(cov, "covariance", problems)
    if mu is None or sigma is None:
        return problems
    if mu.ndim != 1:
        problems.append(f"mean must have shape (D,), not {mu.shape}")
        return problems
    if sigma.shape != (mu.size, mu.size):
        problems.append(f"covariance of shape {sigma.shape} does not match a mean of shape {mu.shape}")
        return problems
    _all_finite(mu, "mean entries", problems)
    if not _all_finite(sigma, "covariance entries", problems):
        return problems
    if sigma.size == 0:
        return problems
    tol = dtype_tolerance(cov, tol, 10 * mu.size)
    # Each component on its own scale: a negative variance of a component measured in millimetres must not hide
    # behind one in kilometres.
    spread = np.sqrt(np.maximum(np.abs(np.diag(sigma)), 1e-300))
    scaled = sigma / np.outer(spread, spread)
    asymmetry = float(np.max(np.abs(scaled - scaled.T)))
    if asymmetry > tol:
        problems.append(f"covariance is not symmetric: |C - C^T| reaches {asymmetry:.3g} of its components' scales")
        scaled = 0.5 * (scaled + scaled.T)
    negative = [int(i) for i in np.flatnonzero(np.diag(sigma) < 0)]
    if negative:
        problems.append(f"covariance has negative variances: component {negative[0]} is {sigma[negative[0], negative[0]]:.3g}")
    smallest = float(np.min(np.linalg.eigvalsh(scaled)))
    if smallest < -tol:
        problems.append(f"covariance is not positive semi-definite: eigenvalue {smallest:.3g} on its components' scales")
    return problems
