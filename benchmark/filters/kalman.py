"""Kalman filter steps: linear and extended, on a Gaussian belief.

A belief is a mean and a covariance (:class:`Gaussian`).  The extended
Kalman filter of seeds/002, Table 2 (after Thrun et al.) is two steps:

* :func:`predict`: ``mu = g(mu)``, ``Sigma = G Sigma G^T + R`` (lines 2-3);
* :func:`update`: ``K = Sigma H^T (H Sigma H^T + Q)^-1``,
  ``mu = mu + K (z - h(mu))`` and the covariance (lines 4-6).

seeds/004 writes the same filter with the other names (eqs. 15-16: ``Q``
for the motion noise, ``R`` for the measurement noise); the functions here
take the two covariances by role, ``process_noise`` and
``measurement_noise``, so either paper's names map onto them directly.

Models are given as a function and its Jacobian, each either an array
(a linear model) or a callable evaluated at the current mean, so the linear
filter is the same code with arrays.  A known input ``B u`` (seeds/002
eq. 6, seeds/004 eq. 15a) is added to the predicted mean through
``control``.  When a measurement is missing the filter only predicts
(seeds/004, section V-D, eq. 17): :func:`update` with ``None`` returns the
prediction unchanged.

The covariance update uses the Joseph form ``(I - K H) Sigma (I - K H)^T +
K Q K^T`` instead of Table 2's ``(I - K H) Sigma``: the two agree in exact
arithmetic, but the Joseph form stays positive semi-definite under
round-off.  Every covariance returned is symmetric bit for bit (each pair
of mirrored entries is replaced by their mean), and the gain comes from a
Cholesky factorisation of the innovation covariance rather than from an
explicit inverse.

The matrix algebra is compiled with numba (cached on disk after the first
call): for the small systems of a tracker, a handful of states, the cost of
a step is then that of the few Python calls around it rather than of many
small numpy operations.  The public functions turn their inputs into
contiguous float arrays; the kernels check every shape before they index
(numba does not), and an input with the wrong number of dimensions is named
once the kernel has refused its type.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from benchmark.lazy import lazy_module

_kernels = lazy_module("benchmark.filters.kalman_kernels")
"""The numba kernels, compiled or loaded from numba's cache on the first step (not on import)."""

Model = np.ndarray | Callable[[np.ndarray], np.ndarray]
"""A linear map as a matrix, or a function of the state."""


@dataclass(frozen=True, slots=True)
class Gaussian:
    """A Gaussian belief.

    Attributes
    ----------
    mean : numpy.ndarray
        ``mu``, shape ``(n,)``; any array of ``n`` numbers is flattened.
    covariance : numpy.ndarray
        ``Sigma``, shape ``(n, n)``.

    Both are stored as contiguous float arrays.

    Raises
    ------
    ValueError
        If the covariance is not ``(n, n)`` for a mean of size ``n``.
    """

    mean: np.ndarray
    covariance: np.ndarray

    def __post_init__(self) -> None:
        mean = np.ascontiguousarray(self.mean, dtype=float).reshape(-1)
        covariance = np.ascontiguousarray(self.covariance, dtype=float)
        if covariance.shape != (mean.size, mean.size):
            raise ValueError(f"covariance {covariance.shape} does not match mean of size {mean.size}")
        object.__setattr__(self, "mean", mean)
        object.__setattr__(self, "covariance", covariance)


_set_mean = Gaussian.__dict__["mean"].__set__
_set_covariance = Gaussian.__dict__["covariance"].__set__


def _belief(mean: np.ndarray, covariance: np.ndarray) -> Gaussian:
    """A Gaussian from arrays the kernels made: already checked, so skip ``__post_init__``."""
    belief = object.__new__(Gaussian)
    _set_mean(belief, mean)
    _set_covariance(belief, covariance)
    return belief


# ---------------------------------------------------------------- public steps


_floats = np.ascontiguousarray
_NONE = np.zeros(0)
"""An empty vector: no control input, or a linear model whose kernel applies the matrix itself."""


def _name_bad_dimensions(*inputs: tuple[str, np.ndarray | None, int]) -> None:
    """After a kernel failed to type its arguments, name the input of the wrong dimension."""
    for name, array, ndim in inputs:
        if array is not None and array.ndim != ndim:
            raise ValueError(f"{name} must be {ndim}-dimensional, got shape {array.shape}")


def _linear_map(matrix: np.ndarray, mean: np.ndarray, name: str) -> np.ndarray:
    A = _floats(matrix, float)
    if A.ndim != 2 or A.shape[1] != mean.size:
        raise ValueError(f"{name} {A.shape} does not match the state size {mean.size}")
    return A @ mean


def _linearise(
    model: Model, jacobian: Model | None, mean: np.ndarray, kind: str, output: str
) -> tuple[np.ndarray, np.ndarray]:
    """The model's matrix (or Jacobian at ``mean``) and, for a function, its value at ``mean``.

    A linear model returns ``_NONE`` as its value: the kernels then apply the
    matrix themselves.  ``kind`` and ``output`` name the model in errors.
    """
    if jacobian is None:
        if callable(model):
            raise ValueError(f"a {kind} model given as a function needs its Jacobian")
        return _floats(model, float), _NONE
    matrix = _floats(jacobian(mean) if callable(jacobian) else jacobian, float)
    if not callable(model):
        return matrix, _linear_map(model, mean, f"the {kind} matrix")
    value = _floats(model(mean), float)
    if value.size == 0:
        raise ValueError(f"the {kind} function returned an empty {output}")
    return matrix, value


def predict(
    belief: Gaussian,
    transition: Model,
    jacobian: Model | None,
    process_noise: np.ndarray,
    control: np.ndarray | None = None,
) -> Gaussian:
    """Propagate a belief one step through the motion model.

    Parameters
    ----------
    belief : Gaussian
        ``mu_(t-1)``, ``Sigma_(t-1)``.
    transition : array or callable
        ``g``: the ``(n, n)`` matrix ``A`` of a linear model, or a function
        of the state (which may include a known input itself).
    jacobian : array or callable or None
        ``G``, the Jacobian of ``g`` (a function is evaluated at the
        previous mean); None when ``transition`` is a matrix, which is
        then its own Jacobian.
    process_noise : numpy.ndarray
        ``R`` of seeds/002 (``Q`` of seeds/004), the ``(n, n)`` covariance
        of the motion noise.
    control : numpy.ndarray, optional
        The known input term ``B u``, shape ``(n,)``, added to the
        predicted mean.

    Returns
    -------
    Gaussian
        ``mu_bar = g(mu) + B u``, ``Sigma_bar = G Sigma G^T + R``, the
        covariance exactly symmetric.

    Raises
    ------
    ValueError
        If a shape does not match the state size, or a function model
        comes without its Jacobian.

    References
    ----------
    seeds/002, Table 2, lines 2-3; eqs. (5)-(6).  seeds/004, eqs. (15a)-(15b),
    and eq. (17b) for the prediction after a missing measurement.
    """
    mean = belief.mean
    noise = _floats(process_noise, float)
    offset = _NONE if control is None else _floats(control, float)
    G, predicted = _linearise(transition, jacobian, mean, "transition", "state")
    n = mean.size
    covariance, predicted_mean = np.empty((n, n)), np.empty(n)
    try:
        _kernels.predict_step(G, mean, belief.covariance, noise, predicted, offset, covariance, predicted_mean)
    except _kernels.TypingError:
        _name_bad_dimensions(
            ("the transition matrix" if jacobian is None else "the transition Jacobian", G, 2),
            ("the predicted mean g(mean)", predicted, 1),
            ("process_noise", noise, 2),
            ("control", offset, 1),
        )
        raise
    return _belief(predicted_mean, covariance)


def update(
    belief: Gaussian,
    measurement: np.ndarray | None,
    observe: Model,
    jacobian: Model | None,
    measurement_noise: np.ndarray,
) -> Gaussian:
    """Correct a predicted belief with a measurement.

    Parameters
    ----------
    belief : Gaussian
        The prediction ``mu_bar``, ``Sigma_bar``.
    measurement : numpy.ndarray or None
        ``z``, shape ``(m,)``; None when it is missing, and the prediction
        stands as the estimate.
    observe : array or callable
        ``h``: the ``(m, n)`` matrix ``H`` of a linear model or a function
        of the state.
    jacobian : array or callable or None
        ``H``, the Jacobian of ``h`` (a function is evaluated at the
        predicted mean); None when ``observe`` is a matrix, which is then
        its own Jacobian.
    measurement_noise : numpy.ndarray
        ``Q`` of seeds/002 (``R`` of seeds/004), the ``(m, m)`` covariance
        of the measurement noise.

    Returns
    -------
    Gaussian
        ``mu = mu_bar + K (z - h(mu_bar))`` and the Joseph-form covariance
        ``(I - K H) Sigma_bar (I - K H)^T + K Q K^T``, exactly symmetric;
        ``belief`` itself when ``measurement`` is None.

    Raises
    ------
    ValueError
        If a shape does not match, a function model comes without its
        Jacobian, or the innovation covariance ``H Sigma_bar H^T + Q`` is
        not positive definite.

    References
    ----------
    seeds/002, Table 2, lines 4-6.  seeds/004, eqs. (16a)-(16b), and
    eq. (17a) for a missing measurement.
    """
    if measurement is None:
        return belief
    mean = belief.mean
    z = _floats(measurement, float)
    noise = _floats(measurement_noise, float)
    H, predicted = _linearise(observe, jacobian, mean, "measurement", "measurement")
    n = mean.size
    covariance, corrected_mean = np.empty((n, n)), np.empty(n)
    try:
        _kernels.correct_step(mean, belief.covariance, H, noise, z, predicted, covariance, corrected_mean)
    except _kernels.TypingError:
        _name_bad_dimensions(
            ("the measurement matrix" if jacobian is None else "the measurement Jacobian", H, 2),
            ("the predicted measurement h(mean)", predicted, 1),
            ("measurement_noise", noise, 2),
            ("the measurement", z, 1),
        )
        raise
    return _belief(corrected_mean, covariance)


def compile_kernels() -> None:
    """Compile (or load from numba's cache) the kernels of :func:`predict` and :func:`update` now.

    Trackers call this before their first timed step, so that frames per
    second measure the filter rather than the compiler.
    """
    belief = Gaussian(np.zeros(2), np.eye(2))
    belief = predict(belief, np.eye(2), None, np.eye(2))
    update(belief, np.zeros(1), np.ones((1, 2)), None, np.eye(1))


class GaussianBeliefView:
    """Gives a tracker whose ``belief`` is a :class:`Gaussian` (or None) the ``mean`` and ``covariance`` it exposes.

    Mixed into the Kalman-filter trackers, so that
    :class:`benchmark.testing.beliefs.GaussianBelief` and its invariant
    checks see their state.  A tracker that also keeps ``prior``, the
    prediction its latest step's :func:`update` corrected (None when the
    step made no update), exposes its covariance as ``prior_covariance``
    (:class:`benchmark.testing.beliefs.GaussianUpdate`), so that the kit
    compares prior and posterior of every update.
    """

    belief: Gaussian | None
    prior: Gaussian | None = None

    @property
    def mean(self) -> np.ndarray | None:
        """The belief's mean; None while there is no belief (before ``reset``, or a lost target)."""
        belief = self.belief
        return None if belief is None else belief.mean

    @property
    def covariance(self) -> np.ndarray | None:
        """The belief's covariance; None while there is no belief."""
        belief = self.belief
        return None if belief is None else belief.covariance

    @property
    def prior_covariance(self) -> np.ndarray | None:
        """``Sigma_bar``, the covariance the latest step's update corrected; None when the step made no update.

        References
        ----------
        seeds/002, Table 2, line 3 (the prior) and line 6 (the posterior,
        :attr:`covariance`); seeds/004, eqs. (15b) and (16c).
        """
        prior = self.prior
        return None if prior is None else prior.covariance
