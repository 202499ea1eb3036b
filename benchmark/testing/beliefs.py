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

A snapshot per frame cannot show what a measurement did to the belief, so
a filter may also expose the belief its latest step's measurement update
started from:

* :class:`GaussianUpdate`: ``prior_covariance``, the covariance predicted
  for the step (``Sigma_bar_t`` of seeds/002, Table 2, line 3; ``P_k^-`` of
  seeds/004, eq. 15b), of which the exposed ``covariance`` is the
  posterior.  An update by a measurement of the state, linear or
  linearised, never widens a Gaussian: ``Sigma_bar - Sigma = K S K^T`` is
  positive semi-definite (Table 2, line 6; seeds/004, eq. 16c), and
  :func:`gaussian_update_problems` checks it;
* :class:`ParticleUpdate`: ``prior_particles``, the predicted set the
  update weighed (``S'_t`` of seeds/000, Fig. 4.10 step (b); the samples of
  seeds/003, eq. 3), of which the exposed ``particles`` are the posterior.
  The update only weighs what the prediction drew (seeds/000, section
  3.4.3; seeds/003, eq. 4) and may resample after weighing, so every
  posterior particle is a row of the predicted set, bit for bit
  (:func:`particle_update_problems`).  Whatever moves particles before the
  weighing (resampling, drift and diffusion, injected or re-detected
  samples, a re-initialisation) belongs to the prediction: the prior is the
  set as it stands when the first likelihood is evaluated.  A move after
  the weighing (a local ascent of the particles, say) makes the posterior
  something other than a weighted predicted set, and such a tracker should
  not expose a prior.

Both are None when the latest step made no measurement update (a frame
without a measurement, a measurement the tracker refused, a start from a
measurement) or when there is no belief; the kit then compares nothing for
that step.
"""

from __future__ import annotations

from typing import Protocol, runtime_checkable

import numpy as np

__all__ = [
    "UPDATE_TOLERANCE",
    "WEIGHT_SUM_TOLERANCE",
    "declares_belief",
    "GaussianBelief",
    "GaussianUpdate",
    "ParticleBelief",
    "ParticleUpdate",
    "gaussian_belief_problems",
    "gaussian_update_problems",
    "particle_belief_problems",
    "particle_update_problems",
]

WEIGHT_SUM_TOLERANCE = 1e-9
"""How far float64 weights of a particle belief may sum from one; weights of a coarser dtype get ``N * eps``."""

SYMMETRY_TOLERANCE = 1e-9
"""Relative tolerance of a float64 covariance's symmetry and smallest eigenvalue; a coarser dtype gets ``10 * D * eps``."""

UPDATE_TOLERANCE = 1e-9
"""How far, on the prior's scales, a float64 posterior may exceed its prior; a coarser dtype gets ``10 D^2 eps``."""


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

    A tracker whose particles carry more than its modality's state (its
    velocities, say) may name every column in a tuple ``belief_dimensions``;
    ``trackbench replay`` then shows them all.
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


@runtime_checkable
class GaussianUpdate(GaussianBelief, Protocol):
    """A Gaussian tracker that exposes the prior of its latest measurement update.

    Attributes
    ----------
    prior_covariance : numpy.ndarray or None
        The covariance predicted for the latest step, before that step's
        measurement update, shape ``(D, D)`` and in the coordinates of
        :attr:`covariance`, which is the update's posterior; None when the
        step made no update or there is no belief.
    """

    @property
    def prior_covariance(self) -> np.ndarray | None: ...


@runtime_checkable
class ParticleUpdate(ParticleBelief, Protocol):
    """A particle tracker that exposes the predicted set its latest measurement update weighed.

    Attributes
    ----------
    prior_particles : numpy.ndarray or None
        The states of the particles as the latest step's update found them,
        shape ``(N', D)``: after everything the step did before weighing
        (resampling, drift, diffusion, injected or re-detected samples).
        Every row of :attr:`particles`, the posterior, is one of these rows.
        None when the step made no update or there is no belief.
    """

    @property
    def prior_particles(self) -> np.ndarray | None: ...


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


def _format_vector(vector: np.ndarray, digits: int = 2) -> str:
    return "(" + ", ".join(f"{value:.{digits}g}" for value in vector) + ")"


def gaussian_update_problems(prior_cov: object, posterior_cov: object, tol: float = UPDATE_TOLERANCE) -> list[str]:
    """What is wrong with a measurement update that turned ``prior_cov`` into ``posterior_cov``.

    Parameters
    ----------
    prior_cov : array_like
        The predicted covariance ``Sigma_bar``, shape ``(D, D)``.
    posterior_cov : array_like
        The covariance after the update, ``Sigma``, same shape.
    tol : float
        Relative tolerance for float64 (:func:`dtype_tolerance` widens it to
        ``10 D^2 eps`` of the coarser of the two dtypes): with each component
        scaled by the prior's own standard deviation (``C_ij / sqrt(P_ii
        P_jj)``), the smallest eigenvalue of ``Sigma_bar - Sigma``,
        symmetrised, may be as low as ``-tol``.  The symmetrised difference
        forgives the textbook ``(I - K H) Sigma_bar``, which is not
        symmetric to the last bit.

    Returns
    -------
    list of str
        One line per broken invariant, empty when there is none: the
        shapes match, both are finite, and the posterior does not exceed the
        prior in the Loewner order.  A posterior that does is named by the
        direction it grew along (on the prior's scales), the component that
        leads it, and every component whose variance grew.

    References
    ----------
    seeds/002, Table 2, lines 4 and 6: ``Sigma_bar - Sigma = K (H Sigma_bar
    H^T + Q) K^T`` is positive semi-definite.  seeds/004, eqs. (16a) and
    (16c); with no measurement the posterior is the prior, eq. (17).
    """
    problems: list[str] = []
    prior = _as_float(prior_cov, "prior covariance", problems)
    posterior = _as_float(posterior_cov, "posterior covariance", problems)
    if prior is None or posterior is None:
        return problems
    if prior.ndim != 2 or prior.shape[0] != prior.shape[1]:
        problems.append(f"prior covariance must have shape (D, D), not {prior.shape}")
        return problems
    if posterior.shape != prior.shape:
        problems.append(f"posterior covariance of shape {posterior.shape} does not match the prior's {prior.shape}")
        return problems
    finite = _all_finite(prior, "prior covariance entries", problems)
    if not (_all_finite(posterior, "posterior covariance entries", problems) and finite) or prior.size == 0:
        return problems
    dims = prior.shape[0]
    tol = max(dtype_tolerance(value, tol, 10 * dims * dims) for value in (prior_cov, posterior_cov))
    # On the prior's own scales, as gaussian_belief_problems judges a covariance.
    spread = np.sqrt(np.maximum(np.abs(np.diag(prior)), 1e-300))
    shrink = (prior - posterior) / np.outer(spread, spread)
    shrink = 0.5 * (shrink + shrink.T)
    values, vectors = np.linalg.eigh(shrink)
    if values[0] >= -tol:
        return problems
    direction = vectors[:, 0]
    lead = int(np.argmax(np.abs(direction)))
    direction = direction * np.sign(direction[lead])
    grown = [int(i) for i in np.flatnonzero(np.diag(shrink) < -tol)]
    variances = "; ".join(
        f"variance of component {i} grew from {prior[i, i]:.3g} to {posterior[i, i]:.3g}" for i in grown
    )
    problems.append(
        f"the update widened the belief: the posterior exceeds the prior along {_format_vector(direction)} "
        f"(on the prior's scales, component {lead} leading) by {-values[0]:.3g} of its scale"
        + (f"; {variances}" if variances else "")
    )
    return problems


def _rows(states: np.ndarray) -> np.ndarray:
    """Each row of a float64 ``(N, D)`` array as one opaque value, ``-0.0`` taken as ``0.0``, for set membership."""
    rows = np.ascontiguousarray(states + 0.0)
    return rows.view(np.dtype((np.void, rows.dtype.itemsize * rows.shape[1]))).ravel()


def particle_update_problems(prior_particles: object, posterior_particles: object) -> list[str]:
    """What is wrong with a measurement update that weighed ``prior_particles`` into ``posterior_particles``.

    Parameters
    ----------
    prior_particles : array_like
        The predicted set, shape ``(N', D)`` with ``N' >= 1``.
    posterior_particles : array_like
        The particles after the update, shape ``(N, D)``.

    Returns
    -------
    list of str
        One line per broken invariant, empty when there is none: the shapes
        agree on ``D``, and every posterior particle equals a row of the
        predicted set exactly (an update weighs and may resample, copying
        rows, but moves no particle).  A moved particle is named with its
        index and state.

    References
    ----------
    seeds/000, section 3.4.3 and Fig. 4.10 step (c): the new measurement
    only assigns weights to the predicted states ``s_t``.  seeds/003,
    eqs. (3)-(4): the samples are drawn by the importance density, then
    weighted; SIR resampling (section 3.4) draws among them.
    """
    problems: list[str] = []
    prior = _as_float(prior_particles, "prior particles", problems)
    posterior = _as_float(posterior_particles, "particles", problems)
    if prior is None or posterior is None:
        return problems
    if prior.ndim != 2 or prior.shape[0] == 0:
        problems.append(f"prior particles must have shape (N, D) with N >= 1, not {prior.shape}")
        return problems
    if posterior.ndim != 2 or posterior.shape[1] != prior.shape[1]:
        problems.append(f"particles of shape {posterior.shape} do not match prior particles of shape {prior.shape}")
        return problems
    moved = np.flatnonzero(~np.isin(_rows(posterior), _rows(prior)))
    if moved.size:
        first = int(moved[0])
        problems.append(
            f"the update moved particles: {moved.size} of {posterior.shape[0]} are not particles of the predicted "
            f"set (particle {first} is {_format_vector(posterior[first], 6)}); an update only weighs and resamples"
        )
    return problems
