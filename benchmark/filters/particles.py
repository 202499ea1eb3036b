"""A weighted particle set: the Monte Carlo picture of a probability density.

``N`` particles of dimension ``D`` are one ``(N, D)`` array of states and one
``(N,)`` array of weights summing to one (seeds/000, section 3.3), so every
operation acts on all particles at once.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from benchmark.lazy import lazy_module

# The compiled loops load on first use, so that importing the filters does not import numba.
_kernels = lazy_module("benchmark.filters.particle_kernels")


def normalise_weights(raw: np.ndarray) -> np.ndarray:
    """Scale non-negative weights to sum to one.

    Parameters
    ----------
    raw : numpy.ndarray
        Unnormalised weights ``pi'``, shape ``(N,)``, finite and ``>= 0``.

    Returns
    -------
    numpy.ndarray
        ``pi = pi' / sum(pi')`` (seeds/000, eq. 4.12 and section 3.4.3).  When
        every weight is zero the set carries no information and the weights
        become uniform.

    Raises
    ------
    ValueError
        If a weight is negative or not finite, or the array is empty.
    """
    weights = checked_weights(raw)
    # Scaling by the largest weight first keeps the sum finite for huge weights.
    return _kernels.normalised(weights)


def checked_weights(raw: np.ndarray) -> np.ndarray:
    """``raw`` as a float array of finite non-negative weights, shape ``(N,)`` with ``N >= 1``.

    Raises
    ------
    ValueError
        If a weight is negative or not finite, or the array is empty or not 1-D.
    """
    weights = np.asarray(raw, dtype=float)
    if weights.ndim != 1 or weights.size == 0:
        raise ValueError(f"weights must be a non-empty 1-D array, got shape {weights.shape}")
    bad = _kernels.first_invalid(weights)
    if bad >= 0:
        raise ValueError(f"weights must be finite and non-negative; weight {bad} is {weights[bad]}")
    return weights


def effective_sample_size(weights: np.ndarray) -> float:
    """Estimated number of effective particles, ``1 / sum(pi^2)``.

    Lies in ``[1, N]`` for normalised weights: ``N`` when they are uniform,
    1 when one particle holds all the weight.

    References
    ----------
    seeds/000, eq. (3.10), after Liu (1996).
    """
    weights = np.asarray(weights, dtype=float)
    return float(1.0 / np.dot(weights, weights))


@dataclass(frozen=True)
class ParticleSet:
    """``N`` weighted samples of a ``D``-dimensional state.

    Attributes
    ----------
    states : numpy.ndarray
        Shape ``(N, D)``.
    weights : numpy.ndarray
        Shape ``(N,)``, non-negative, summing to one.

    References
    ----------
    seeds/000, section 3.3.
    """

    states: np.ndarray
    weights: np.ndarray

    def __post_init__(self) -> None:
        states = np.asarray(self.states, dtype=float)
        weights = np.asarray(self.weights, dtype=float)
        _check_shapes(states, weights)
        if not np.all(np.isfinite(weights)) or np.any(weights < 0):
            raise ValueError(f"particle weights must be finite and non-negative, got {weights}")
        object.__setattr__(self, "states", states)
        object.__setattr__(self, "weights", weights)

    @classmethod
    def _valid(cls, states: np.ndarray, weights: np.ndarray) -> ParticleSet:
        """A set of float arrays whose weights are known to be finite and non-negative: only the shapes are checked."""
        _check_shapes(states, weights)
        particles = object.__new__(cls)
        object.__setattr__(particles, "states", states)
        object.__setattr__(particles, "weights", weights)
        return particles

    @classmethod
    def equally_weighted(cls, states: np.ndarray) -> ParticleSet:
        """Particles with weights ``1/N`` (seeds/000, Fig. 4.10, step 1)."""
        states = np.asarray(states, dtype=float)
        n = states.shape[0] if states.ndim == 2 else 0
        return cls._valid(states, np.full(n, 1.0 / max(n, 1)))

    def moved(self, states: np.ndarray) -> ParticleSet:
        """The same weights on new states of the same shape: a drift and diffusion of every particle.

        Raises
        ------
        ValueError
            If ``states`` is not ``(N, D)`` for this set's ``N``.
        """
        return ParticleSet._valid(np.asarray(states, dtype=float), self.weights)

    def reweighted(self, raw: np.ndarray) -> ParticleSet:
        """The same states with the weights :func:`normalise_weights` makes of ``raw`` (seeds/000, eq. 4.12).

        Raises
        ------
        ValueError
            If ``raw`` is not ``(N,)``, or a weight is negative or not finite.
        """
        return ParticleSet._valid(self.states, normalise_weights(raw))

    @property
    def size(self) -> int:
        """The number of particles ``N``."""
        return self.states.shape[0]

    @property
    def effective_size(self) -> float:
        """:func:`effective_sample_size` of the weights (seeds/000, eq. 3.10)."""
        return effective_sample_size(self.weights)

    def mmse(self) -> np.ndarray:
        """Minimum mean square error estimate ``sum_i pi_i s_i`` (seeds/000, eq. 3.11)."""
        return self.weights @ self.states

    def best(self) -> np.ndarray:
        """The state of the highest-weight particle."""
        return self.states[int(np.argmax(self.weights))]

    def quantiles(self, q: np.ndarray | list[float] | float, dimension: int) -> np.ndarray:
        """Weighted quantiles of one dimension of the state.

        Parameters
        ----------
        q : array_like
            Probabilities in ``[0, 1]``.
        dimension : int
            Column of the state.

        Returns
        -------
        numpy.ndarray
            Shape of ``q``: for each, the smallest value of that dimension
            whose cumulative weight (particles in ascending order of the
            value) reaches ``q``.  Unlike a standard deviation, the spread
            between two quantiles ignores how far a few light particles lie
            from the rest.

        Raises
        ------
        ValueError
            If a ``q`` is not in ``[0, 1]``.
        IndexError
            If ``dimension`` is not a column of the state.
        """
        q = np.asarray(q, dtype=float)
        if not np.all((q >= 0.0) & (q <= 1.0)):
            raise ValueError(f"quantiles must be in [0, 1], got {q}")
        values = self.states[:, dimension]
        flat_q = q.reshape(-1)
        # Weights sum to one up to rounding: the kernels compare with the actual total, and stay in range.
        found = _kernels.distinct_quantiles(values, self.weights, np.argsort(values), flat_q)
        if found.size != flat_q.size:
            # Only distinct values have one ascending order; with ties (or NaN)
            # the stable sort fixes the order of the weights that are summed.
            found = _kernels.weighted_quantiles(values, self.weights, np.argsort(values, kind="stable"), flat_q)
        return found.reshape(q.shape)

    def take(self, indices: np.ndarray) -> ParticleSet:
        """The particles at ``indices``, equally weighted: the result of resampling."""
        indices = np.asarray(indices)
        if indices.dtype.kind in "iu":
            # The same rows as ``states[indices]``, copied faster for integer indices.
            return ParticleSet.equally_weighted(np.take(self.states, indices, axis=0))
        return ParticleSet.equally_weighted(self.states[indices])


def _check_shapes(states: np.ndarray, weights: np.ndarray) -> None:
    """Raise ValueError unless ``states`` is ``(N, D)`` and ``weights`` ``(N,)`` with ``N >= 1``."""
    if states.ndim != 2 or weights.shape != (states.shape[0],) or states.shape[0] == 0:
        raise ValueError(f"states (N, D) and weights (N,) do not match: {states.shape} and {weights.shape}")


class ParticleBeliefView:
    """Gives a tracker whose ``particle_set`` is a :class:`ParticleSet` (or None) its ``particles`` and ``weights``.

    Mixed into the particle-filter trackers, so that
    :class:`benchmark.testing.beliefs.ParticleBelief` and its invariant
    checks see their state.  A tracker that also keeps ``prior_set``, the
    predicted set its latest step weighed (None when the step weighed
    nothing), exposes its states as ``prior_particles``
    (:class:`benchmark.testing.beliefs.ParticleUpdate`), so that the kit
    checks that the update only weighed them.
    """

    particle_set: ParticleSet | None
    prior_set: ParticleSet | None = None

    @property
    def particles(self) -> np.ndarray | None:
        """The particles' states, ``(N, D)``; None while the filter has no particles (before it starts)."""
        return None if self.particle_set is None else self.particle_set.states

    @property
    def weights(self) -> np.ndarray | None:
        """The particles' weights, ``(N,)``, summing to one; None while the filter has no particles."""
        return None if self.particle_set is None else self.particle_set.weights

    @property
    def prior_particles(self) -> np.ndarray | None:
        """The predicted states the latest step weighed, ``(N, D)``; None when the step weighed nothing.

        References
        ----------
        seeds/000, Fig. 4.10 step (b) (the set ``S'_t`` after drift and
        diffusion) and step (c) (its weights); seeds/003, eqs. (3)-(4).
        """
        return None if self.prior_set is None else self.prior_set.states
