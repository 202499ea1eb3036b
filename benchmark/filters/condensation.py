"""One step of the condensation algorithm from swappable parts.

Isard and Blake's condensation, as the thesis lays it out (seeds/000,
section 3.4 and Fig. 4.10), turns the particle set of time ``t-1`` into that
of time ``t`` in three moves:

1. *resample*, but only when the effective sample size (eq. 3.10) has
   fallen below a threshold, ``N/2`` by default;
2. *drift and diffuse*: the movement model moves every particle;
3. *measure*: the observation model weighs every particle against the new
   observation, and the weights are normalised (eq. 4.12).

A :class:`Condensation` holds the two models and the resampling scheme; a
tracker supplies models for its own state.  :class:`LinearDriftDiffusion`
is the common movement model ``s_t = F s_(t-1) + b`` with Gaussian ``b``.

A note on the threshold: Fig. 4.10 of the thesis reads "if N_eff > N/2,
resample", while the text of section 3.4.1 says the set is resampled when
N_eff *falls below* the threshold, which is also what keeps the particles
from collapsing on the modes.  We follow the text.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Protocol

import numpy as np

from benchmark.filters.particles import ParticleSet
from benchmark.filters.resampling import Resampler, systematic_resample


class MovementModel(Protocol):
    """Drift and diffuse: move every particle one time step (seeds/000, section 3.4.2)."""

    def propagate(self, states: np.ndarray, rng: np.random.Generator) -> np.ndarray:
        """New ``(N, D)`` states from old ones; randomness only from ``rng``."""


class ObservationModel(Protocol):
    """Measure: weigh every particle against an observation (seeds/000, section 3.4.3)."""

    def likelihood(self, states: np.ndarray, observation: Any) -> np.ndarray:
        """Unnormalised, finite, non-negative weights ``pi'`` of shape ``(N,)``."""


@dataclass(frozen=True)
class LinearDriftDiffusion:
    """``s_t = F s_(t-1) + b`` with ``b ~ N(0, diag(noise_std^2))``.

    Parameters
    ----------
    transition : numpy.ndarray
        ``F``, shape ``(D, D)``: the deterministic drift.
    noise_std : numpy.ndarray
        Standard deviations of the diffusion, shape ``(D,)``; zero entries
        leave their dimension deterministic.

    References
    ----------
    seeds/000, section 3.4.2 and eq. (4.9).
    """

    transition: np.ndarray
    noise_std: np.ndarray

    def __post_init__(self) -> None:
        transition = np.asarray(self.transition, dtype=float)
        noise_std = np.asarray(self.noise_std, dtype=float)
        if noise_std.ndim != 1 or transition.shape != (noise_std.size, noise_std.size):
            raise ValueError(f"transition {transition.shape} does not match noise_std {noise_std.shape}")
        if np.any(noise_std < 0) or not np.all(np.isfinite(noise_std)):
            raise ValueError(f"noise_std must be finite and non-negative, got {noise_std}")
        object.__setattr__(self, "transition", transition)
        object.__setattr__(self, "noise_std", noise_std)

    def propagate(self, states: np.ndarray, rng: np.random.Generator) -> np.ndarray:
        states = np.asarray(states, dtype=float)
        if states.ndim != 2 or states.shape[1] != self.noise_std.size:
            raise ValueError(f"states must have shape (N, {self.noise_std.size}), got {states.shape}")
        # In place on the draws: the same products and sums as ``drifted + draws * noise_std``.
        moved = rng.standard_normal(states.shape)
        moved *= self.noise_std
        moved += states @ self.transition.T
        return moved


@dataclass
class Condensation:
    """The condensation step: resample if needed, drift and diffuse, measure.

    Parameters
    ----------
    movement : MovementModel
        Drift and diffusion of the particles.
    observation : ObservationModel
        Weights of the particles given an observation.
    resample : Resampler
        Resampling scheme (:mod:`benchmark.filters.resampling`).
    ess_fraction : float
        Resample when the effective sample size is below ``ess_fraction *
        N`` (0.5: the thesis' ``N/2``).
    carry_weights : bool
        False (the thesis, Fig. 4.10 step c): the new weights are the
        normalised likelihoods ``pi_t = p(z_t | s_t)``.  True: they are the
        previous weights times the likelihoods, the importance-sampling
        update that keeps a set which was not resampled exact.

    References
    ----------
    seeds/000, section 3.4, Figs. 3.5 and 4.10; eqs. (3.8)-(3.11), (4.12).
    """

    movement: MovementModel
    observation: ObservationModel
    resample: Resampler = systematic_resample
    ess_fraction: float = 0.5
    carry_weights: bool = False
    resampled: bool = field(default=False, init=False)
    """Whether the last :meth:`step` resampled."""

    def step(self, particles: ParticleSet, observation: Any, rng: np.random.Generator) -> ParticleSet:
        """Advance the particle set by one observation: :meth:`predict`, then :meth:`update`.

        Returns
        -------
        ParticleSet
            The drifted, diffused and newly weighted particles, approximating
            the posterior of the new time step.
        """
        return self.update(self.predict(particles, rng), observation)

    def predict(self, particles: ParticleSet, rng: np.random.Generator) -> ParticleSet:
        """Resample if needed, then drift and diffuse: the predicted set, before any measurement.

        Returns
        -------
        ParticleSet
            The moved states ``S'_t`` with the weights they carry: those of
            ``particles``, or ``1/N`` after resampling.

        References
        ----------
        seeds/000, Fig. 4.10 steps (a)-(b); eqs. (3.8)-(3.10).
        """
        self.resampled = particles.effective_size < self.ess_fraction * particles.size
        if self.resampled:
            particles = particles.take(self.resample(particles.weights, rng))
        return particles.moved(self.movement.propagate(particles.states, rng))

    def update(self, predicted: ParticleSet, observation: Any) -> ParticleSet:
        """Weigh the predicted set by an observation; the states stay as they are.

        Returns
        -------
        ParticleSet
            The states of ``predicted`` with the normalised likelihoods as
            weights, times the weights they carried when ``carry_weights``.

        References
        ----------
        seeds/000, Fig. 4.10 step (c), section 3.4.3, eq. (4.12); seeds/003, eq. (4).
        """
        raw = self.observation.likelihood(predicted.states, observation)
        if self.carry_weights:
            raw = predicted.weights * raw
        return predicted.reweighted(raw)
