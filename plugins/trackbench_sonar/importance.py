"""The importance density of the pipe filter: a random walk with injected samples.

seeds/003 draws each particle from an importance density
``q(. | x_(k-1), z_k)`` (eq. 3) without saying which.  The one used here is
the transition prior, ``q = p(x_k | x_(k-1))``, the choice of the SIR filter
the paper names (section 3.4, Gordon et al.): the pipe's across-track
position follows a Gaussian random walk of standard deviation
``walk_sigma_m`` per ping (by default ``walk_speed_mps`` times the ping
interval).  With
this choice the weight update of eq. (4) is the previous weight times the
likelihood, exactly as the paper writes it.

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

    References
    ----------
    seeds/003, eq. (3) and section 3.4.
    """

    walk_sigma_m: float
    inject_fraction: float
    extent: tuple[float, float] | None = None

    _walk: LinearDriftDiffusion = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        if not 0.0 <= self.inject_fraction <= 1.0:
            raise ValueError(f"inject_fraction must be in [0, 1], got {self.inject_fraction!r}")
        object.__setattr__(self, "_walk", LinearDriftDiffusion(np.eye(1), np.array([self.walk_sigma_m])))

    def injected_count(self, n: int) -> int:
        """Particles re-drawn among ``n``: ``round(J n)``, at least one when ``J > 0``."""
        if self.inject_fraction <= 0.0 or self.extent is None:
            return 0
        return min(n, max(1, round(self.inject_fraction * n)))

    def walk(self, states: np.ndarray, rng: np.random.Generator) -> np.ndarray:
        """Move every particle by the random walk alone (the transition prior).

        Raises
        ------
        ValueError
            If ``states`` is not ``(N, 1)``.
        """
        return self._walk.propagate(states, rng)

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
