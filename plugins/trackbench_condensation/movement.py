"""The movement model: constant-velocity drift of distance and angle, Gaussian diffusion.

A particle of the thesis carries ``(d, alpha, w, beta, v_d, v_alpha)``
(seeds/000, section 4.4): the cable state and the instant velocities of
distance and angle.  One time step is eq. (4.9),

    s_t = s_(t-1) + (v_d, v_alpha, 0, 0, 0, 0) + b,
    b ~ N(0, diag(sigma_d^2, sigma_alpha^2, sigma_w^2, sigma_beta^2,
                  sigma_v_d^2, sigma_v_alpha^2)),

a linear drift plus Gaussian diffusion, which is exactly
:class:`benchmark.filters.LinearDriftDiffusion` with the transition matrix
of :func:`transition_matrix`.

Section 6.1 proposes velocities for width and skew too, for cameras that
pitch and so change ``w`` and ``beta`` quickly: the eight-dimensional
particle ``(d, alpha, w, beta, v_d, v_alpha, v_w, v_beta)`` drifts ``w`` by
``v_w`` and ``beta`` by ``v_beta`` in the same way.

Units.  States hold px, rad, px/frame and rad/frame.  The variances are
given as in Table 5.1, angles in degrees squared, and converted here.
"""

from __future__ import annotations

import math

import numpy as np

from benchmark.filters import LinearDriftDiffusion

D, ALPHA, W, BETA, V_D, V_ALPHA, V_W, V_BETA = range(8)
"""Column of each state variable in a particle array."""

COLUMN_NAMES = ("d_px", "alpha_rad", "w_px", "beta_rad", "v_d_px", "v_alpha_rad", "v_w_px", "v_beta_rad")
"""The names of the columns, in that order; the velocities are per frame."""

DRIFTS = {D: V_D, ALPHA: V_ALPHA, W: V_W, BETA: V_BETA}
"""Which velocity drifts which variable."""


def transition_matrix(dims: int) -> np.ndarray:
    """The drift ``F`` of eq. (4.9) for a 6- or 8-dimensional particle.

    Parameters
    ----------
    dims : {6, 8}
        6: velocities of ``d`` and ``alpha`` (section 4.4); 8: also of ``w``
        and ``beta`` (section 6.1).

    Returns
    -------
    numpy.ndarray
        ``(dims, dims)``: the identity plus a 1 coupling each drifted
        variable to its velocity.

    References
    ----------
    seeds/000, eqs. (4.3)-(4.4) and (4.9); section 6.1.
    """
    if dims not in (6, 8):
        raise ValueError(f"a particle has 6 or 8 dimensions, not {dims}")
    transition = np.eye(dims)
    for variable, velocity in DRIFTS.items():
        if velocity < dims:
            transition[variable, velocity] = 1.0
    return transition


def diffusion_std(
    var_d_px2: float,
    var_alpha_deg2: float,
    var_w_px2: float,
    var_beta_deg2: float,
    var_v_d_px2: float,
    var_v_alpha_deg2: float,
    var_v_w_px2: float | None = None,
    var_v_beta_deg2: float | None = None,
) -> np.ndarray:
    """Standard deviations of the diffusion ``b`` in state units (px, rad).

    Parameters
    ----------
    var_d_px2, var_w_px2, var_v_d_px2, var_v_w_px2 : float
        Variances of the px-valued variables, px^2 (per frame^2 for velocities).
    var_alpha_deg2, var_beta_deg2, var_v_alpha_deg2, var_v_beta_deg2 : float
        Variances of the angles, deg^2, as Table 5.1 states them.
    var_v_w_px2, var_v_beta_deg2 : float, optional
        Given together for the 8-dimensional particle.

    Returns
    -------
    numpy.ndarray
        ``(6,)`` or ``(8,)`` standard deviations; angles converted to rad.

    Raises
    ------
    ValueError
        If a variance is negative or not finite, or only one of the two
        extra variances is given.

    References
    ----------
    seeds/000, eqs. (4.5)-(4.9) and Table 5.1; section 6.1.
    """
    variances = [var_d_px2, var_alpha_deg2, var_w_px2, var_beta_deg2, var_v_d_px2, var_v_alpha_deg2]
    angular = [False, True, False, True, False, True]
    if (var_v_w_px2 is None) != (var_v_beta_deg2 is None):
        raise ValueError("the variances of v_w and v_beta come together (8-dimensional particle)")
    if var_v_w_px2 is not None:
        variances += [var_v_w_px2, var_v_beta_deg2]
        angular += [False, True]
    values = np.asarray(variances, dtype=float)
    if not np.all(np.isfinite(values)) or np.any(values < 0):
        raise ValueError(f"variances must be finite and >= 0, got {variances}")
    std = np.sqrt(values)
    std[np.asarray(angular)] *= math.pi / 180.0
    return std


def movement_model(noise_std: np.ndarray) -> LinearDriftDiffusion:
    """Eq. (4.9) as a :class:`benchmark.filters.LinearDriftDiffusion`.

    Parameters
    ----------
    noise_std : numpy.ndarray
        ``(6,)`` or ``(8,)`` diffusion standard deviations (:func:`diffusion_std`).

    References
    ----------
    seeds/000, eq. (4.9); section 6.1.
    """
    noise_std = np.asarray(noise_std, dtype=float)
    return LinearDriftDiffusion(transition_matrix(noise_std.size), noise_std)
