"""Pipes on the seabed: where each lies in every ping, how deep, how buried.

The detector of seeds/003 (section 2) describes a pipe in a scan by its
centre, its depth, its burial and the axes ``[M_a, M_i]`` of its
cross-section.  A pipe here is a cylinder of known diameter ``D = 2 r``
lying on the seabed, so in the plane of a swath its cross-section is an
ellipse: vertical semi-axis ``r``, horizontal semi-axis ``r / cos(psi)``,
where ``psi`` is the angle between the pipe and the track, which follows
from how fast the pipe's across-track position changes from ping to ping.

A proud pipe rests on the highest points under it: its axis is as deep as
it can be without the ellipse entering the seabed (:func:`resting_depth`).
A buried pipe has sunk by ``burial * D`` below that, so that ``burial`` is
the share of its diameter below the seabed: 0 proud, 1 covered.  A covered
pipe shows nothing (sand fills over it); a partly buried one shows only
what stands above the seabed, because the sonar sees the first surface a
beam meets (:mod:`benchmark.modalities.sonar.scenes.swath`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class PipeTrack:
    """One pipe at every ping; lengths in m, depths below the transducer.

    Attributes
    ----------
    across_m : numpy.ndarray
        Across-track position of the axis.
    axis_depth_m : numpy.ndarray
        Depth of the axis.
    burial : numpy.ndarray
        Share of the diameter below the seabed, in [0, 1].
    half_width_m : numpy.ndarray
        Horizontal semi-axis of the cross-section in the swath's plane.
    radius_m : float
        Vertical semi-axis, the pipe's radius.
    """

    across_m: np.ndarray
    axis_depth_m: np.ndarray
    burial: np.ndarray
    half_width_m: np.ndarray
    radius_m: float

    @property
    def visible(self) -> np.ndarray:
        """Pings where some of the pipe stands above the seabed."""
        return self.burial < 1.0


def crossing_half_width(across_m: np.ndarray, radius_m: float, ping_spacing_m: float) -> np.ndarray:
    """Horizontal semi-axis ``r / cos(psi)`` of a pipe's cross-section in each swath.

    Parameters
    ----------
    across_m : numpy.ndarray
        Across-track position of the axis at each ping.
    radius_m : float
        The pipe's radius.
    ping_spacing_m : float
        Along-track distance between pings.

    Returns
    -------
    numpy.ndarray
        ``r sqrt(1 + (d across / d along)^2)``, at least ``r``.

    References
    ----------
    seeds/003, section 2: the major axis ``M_a`` of the cross-section.
    """
    if len(across_m) < 2:
        return np.full(len(across_m), radius_m)
    slope = np.gradient(across_m, ping_spacing_m)
    return radius_m * np.sqrt(1.0 + slope**2)


def resting_depth(
    base_m: np.ndarray, across: np.ndarray, centre_m: np.ndarray, half_width_m: np.ndarray, radius_m: float
) -> np.ndarray:
    """Depth of a proud pipe's axis resting on the seabed, at each ping.

    The ellipse of semi-axes ``(half_width, radius)`` centred on the axis
    sits as deep as it can while staying above every grid point under it
    and above the seabed at the axis.

    Parameters
    ----------
    base_m : numpy.ndarray
        Seabed depth, shape ``(n_pings, len(across))``.
    across : numpy.ndarray
        Grid columns, evenly spaced.
    centre_m : numpy.ndarray
        Across-track position of the axis at each ping, inside the grid.
    half_width_m : numpy.ndarray
        Horizontal semi-axis at each ping.
    radius_m : float
        Vertical semi-axis.

    Returns
    -------
    numpy.ndarray
        Axis depth at each ping.
    """
    n = len(centre_m)
    cell = float(across[1] - across[0])
    rows = np.arange(n)
    position = (centre_m - across[0]) / cell
    left = np.clip(np.floor(position).astype(int), 0, len(across) - 2)
    frac = position - left
    under_axis = base_m[rows, left] * (1.0 - frac) + base_m[rows, left + 1] * frac - radius_m
    reach = int(math.ceil(float(np.max(half_width_m)) / cell)) + 1
    columns = np.clip(left[:, None] + np.arange(-reach, reach + 2)[None, :], 0, len(across) - 1)
    offset = (across[columns] - centre_m[:, None]) / half_width_m[:, None]
    inside = np.abs(offset) < 1.0
    lift = radius_m * np.sqrt(np.where(inside, 1.0 - offset**2, 0.0))
    depth = np.where(inside, base_m[rows[:, None], columns] - lift, np.inf)
    return np.minimum(depth.min(axis=1), under_axis)


def pipe_track(
    across_m: np.ndarray,
    burial: np.ndarray,
    radius_m: float,
    ping_spacing_m: float,
    base_m: np.ndarray,
    across: np.ndarray,
) -> PipeTrack:
    """A pipe lying on the seabed along the given positions, buried as given.

    Parameters
    ----------
    across_m : numpy.ndarray
        Across-track position of the axis at each ping.
    burial : numpy.ndarray
        Burial at each ping; clipped to [0, 1].
    radius_m : float
        The pipe's radius.
    ping_spacing_m : float
        Along-track distance between pings.
    base_m : numpy.ndarray
        The seabed it lies on, shape ``(n_pings, len(across))``.
    across : numpy.ndarray
        Grid columns.

    Returns
    -------
    PipeTrack

    References
    ----------
    seeds/003, section 2: centre, depth and burial of a pipe.
    """
    burial = np.clip(burial, 0.0, 1.0)
    half_width = crossing_half_width(across_m, radius_m, ping_spacing_m)
    proud = resting_depth(base_m, across, across_m, half_width, radius_m)
    return PipeTrack(
        across_m=np.asarray(across_m, dtype=float),
        axis_depth_m=proud + 2.0 * radius_m * burial,
        burial=burial,
        half_width_m=half_width,
        radius_m=radius_m,
    )
