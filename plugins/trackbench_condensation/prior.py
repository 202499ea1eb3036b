"""The initial particle set: from a known cable state, or uniform within limits.

Seeds/000, section 4.3 starts the filter either from knowledge of the cable
(a hand-marked first image, another detector, or here the first frame's
ground truth) or from a uniform distribution within typical limits of each
variable, eq. (4.1): ``s = r (u_max - u_min) + u_min`` with ``r`` uniform on
``[0, 1]``.  Table 5.2 gives the limits the thesis used.

From a known state every particle is put exactly at it, with zero
velocities.  The set needs no artificial spread: the first drift and
diffusion (eq. 4.9), applied before the first frame is measured, spreads the
particles by the movement model's own noise, exactly as it spreads a
converged set on every later frame.  An extra initial spread would be one
more parameter the thesis does not have.

The 8-dimensional particle of section 6.1 adds ``v_w`` and ``v_beta``;
Table 5.2 gives no limits for them, so they start at 0 in both cases.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from benchmark.modalities.camera.model import CableState


@dataclass(frozen=True)
class InitLimits:
    """Limits of the uniform initialisation (seeds/000, Table 5.2), in Table 5.2's units.

    Attributes
    ----------
    d_px, alpha_deg, w_px, beta_deg, v_d_px, v_alpha_deg : tuple of float
        ``(minimum, maximum)`` of ``d`` (px), ``alpha`` (deg), ``w`` (px),
        ``beta`` (deg), ``v_d`` (px/frame) and ``v_alpha`` (deg/frame).
    """

    d_px: tuple[float, float] = (-150.0, 150.0)
    alpha_deg: tuple[float, float] = (-45.0, 45.0)
    w_px: tuple[float, float] = (5.0, 100.0)
    beta_deg: tuple[float, float] = (0.0, 10.0)
    v_d_px: tuple[float, float] = (-1.0, 1.0)
    v_alpha_deg: tuple[float, float] = (-0.1, 0.1)

    def __post_init__(self) -> None:
        for name in ("d_px", "alpha_deg", "w_px", "beta_deg", "v_d_px", "v_alpha_deg"):
            pair = tuple(float(v) for v in getattr(self, name))
            if len(pair) != 2 or not all(math.isfinite(v) for v in pair) or pair[0] > pair[1]:
                raise ValueError(f"init limits {name} must be (min, max) with min <= max, got {getattr(self, name)}")
            object.__setattr__(self, name, pair)

    def scaled(self, factor: float) -> InitLimits:
        """The limits for a frame ``factor`` times as wide: ``d``, ``w`` and ``v_d`` (px) times ``factor``.

        Raises
        ------
        ValueError
            If ``factor`` is not positive and finite.
        """
        if not (math.isfinite(factor) and factor > 0):
            raise ValueError(f"frame scale factor must be positive and finite, got {factor}")
        return dataclasses.replace(
            self,
            d_px=tuple(factor * v for v in self.d_px),
            w_px=tuple(factor * v for v in self.w_px),
            v_d_px=tuple(factor * v for v in self.v_d_px),
        )

    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        """Lower and upper bounds of ``(d, alpha, w, beta, v_d, v_alpha)`` in px and rad."""
        rows = np.array([self.d_px, self.alpha_deg, self.w_px, self.beta_deg, self.v_d_px, self.v_alpha_deg])
        rows[[1, 3, 5]] *= math.pi / 180.0
        return rows[:, 0], rows[:, 1]


def uniform_particles(n: int, dims: int, limits: InitLimits, rng: np.random.Generator) -> np.ndarray:
    """``n`` particles drawn uniformly within the limits.

    Parameters
    ----------
    n : int
        Number of particles.
    dims : {6, 8}
        Particle dimension; columns 6 and 7 (``v_w``, ``v_beta``) are 0.
    limits : InitLimits
        Table 5.2 or other limits.
    rng : numpy.random.Generator
        Source of the uniform numbers ``r``.

    Returns
    -------
    numpy.ndarray
        ``(n, dims)`` states in px and rad.

    References
    ----------
    seeds/000, eq. (4.1) and Table 5.2.
    """
    low, high = limits.bounds()
    states = np.zeros((n, dims))
    states[:, :6] = rng.random((n, 6)) * (high - low) + low
    return states


def particles_at(state: CableState, n: int, dims: int) -> np.ndarray:
    """``n`` copies of a known cable state with zero velocities.

    Raises
    ------
    ValueError
        If the state is not fully known.

    References
    ----------
    seeds/000, section 4.3 and Fig. 4.10 step 1 (ground-truth knowledge).
    """
    if not state.is_known:
        raise ValueError(f"cannot start from an unknown cable state: {state}")
    states = np.zeros((n, dims))
    states[:, :4] = state.as_array()
    return states
