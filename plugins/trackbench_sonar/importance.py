"""The importance density of the pipe filter: a random walk, drifting, with injected samples.

seeds/003 draws each particle from an importance density
``q(. | x_(0:k-1), z_(1:k))`` (eq. 3) without saying which.  The one used
here is the transition prior, the choice of the SIR filter the paper names
(section 3.4, Gordon et al.): the pipe's across-track position follows a
Gaussian random walk of standard deviation ``walk_sigma_m`` per ping (by
default ``walk_speed_mps`` times the ping interval), shifted by a drift
``drift_m`` per ping.  The drift is the filter's own estimate of how fast
the pipe moves across the swath (from its past estimates, so from
``z_(1:k-1)``, which eq. 3's general form allows;
:class:`trackbench_sonar.particle_filter.SonarParticleFilter`): a walk
alone, tuned for a pipe that wanders, lags a pipe that drifts steadily
faster than the walk's speed.  With a drift of 0 it is the walk of the
paper's filter.  With this choice the weight update of eq. (4) is the
previous weight times the likelihood, exactly as the paper writes it.

Section 3.4 keeps "some noise in the system by generating some rate J of
new random samples as done in the initialization step": after the walk,
``round(J N)`` particles chosen at random (at least one when ``J > 0``) are
re-drawn uniformly over the current swath's across-track extent, the
initialisation of a filter that does not know where the pipe is.  They let
the filter find the pipe again after losing it, and keep the particles from
ever collapsing onto one value.

:class:`RandomWalkInjection` is a movement model of
:class:`benchmark.filters.condensation.Condensation`; it holds the extent
of the swath it injects over, so the filter makes one for each ping.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass, field

import numpy as np

from benchmark.filters.condensation import LinearDriftDiffusion


def uniform_positions(count: int, extent: tuple[float, float], rng: np.random.Generator) -> np.ndarray:
    """``count`` positions drawn uniformly over ``extent = (low, high)``, shape ``(count, 1)``.

    References
    ----------
    seeds/003, section 3.4 ("new random samples as done in the
    initialization step").
    """
    low, high = extent
    return rng.uniform(low, high, size=(count, 1))


@functools.lru_cache(maxsize=16)
def _diffusion(walk_sigma_m: float) -> LinearDriftDiffusion:
    """The walk of one dimension, made (and checked) once per standard deviation: the filter makes a movement each ping."""
    return LinearDriftDiffusion(np.eye(1), np.array([walk_sigma_m]))


@dataclass(frozen=True)
class RandomWalkInjection:
    """Random walk of every particle, then a fraction ``J`` re-drawn uniformly.

    Parameters
    ----------
    walk_sigma_m : float
        Standard deviation of the walk per ping, m, finite and non-negative
        (the diffusion of :class:`benchmark.filters.condensation.LinearDriftDiffusion`).
    inject_fraction : float
        ``J`` in ``[0, 1]``.
    extent : tuple of float or None
        Across-track ``(low, high)`` of the swath to inject over; None
        injects nothing.
    drift_m : float
        Shift of every walked particle this ping, m (finite).

    References
    ----------
    seeds/003, eq. (3) and section 3.4.
    """

    walk_sigma_m: float
    inject_fraction: float
    extent: tuple[float, float] | None = None
    drift_m: float = 0.0

    _walk: LinearDriftDiffusion = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        if not 0.0 <= self.inject_fraction <= 1.0:
            raise ValueError(f"inject_fraction must be in [0, 1], got {self.inject_fraction!r}")
        if not np.isfinite(self.drift_m):
            raise ValueError(f"drift_m must be finite, got {self.drift_m!r}")
        object.__setattr__(self, "_walk", _diffusion(self.walk_sigma_m))

    def injected_count(self, n: int) -> int:
        """Particles re-drawn among ``n``: ``round(J n)``, at least one when ``J > 0``."""
        if self.inject_fraction <= 0.0 or self.extent is None:
            return 0
        return min(n, max(1, round(self.inject_fraction * n)))

    def walk(self, states: np.ndarray, rng: np.random.Generator) -> np.ndarray:
        """Move every particle by the drift and the random walk (the transition prior).

        Raises
        ------
        ValueError
            If ``states`` is not ``(N, 1)``.
        """
        return self._walk.propagate(states, rng) + self.drift_m

    def propagate(self, states: np.ndarray, rng: np.random.Generator) -> np.ndarray:
        """Draw ``x_k^i ~ q(. | x_(k-1)^i)`` (eq. 3) and inject ``J N`` new samples (section 3.4).

        Parameters
        ----------
        states : numpy.ndarray
            Shape ``(N, 1)``: across-track positions.
        rng : numpy.random.Generator
            Source of every draw.

        Returns
        -------
        numpy.ndarray
            The new ``(N, 1)`` positions.
        """
        moved = self.walk(states, rng)
        count = self.injected_count(moved.shape[0])
        if count:
            slots = rng.choice(moved.shape[0], size=count, replace=False)
            moved[slots] = uniform_positions(count, self.extent, rng)
        return moved
