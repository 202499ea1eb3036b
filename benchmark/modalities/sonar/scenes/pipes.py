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
the share of its diameter below the seabed: 0 proud, 1 covered.  A stiff
pipe does not follow a trough narrower than it can bend into: over sand
waves it rests on the crests and hangs between them, a free span with the
seabed visible below it (:func:`span_depth`).  A covered
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


def span_depth(axis_depth_m: np.ndarray, ping_spacing_m: float, bend_radius_m: float) -> np.ndarray:
    """Depth of a pipe's axis that bends no tighter than ``bend_radius_m`` between its supports.

    The pipe may not sink below where it would rest (``axis_depth_m``), and
    where the bottom falls away faster than the pipe can bend it hangs in
    parabolic arcs of radius ``bend_radius_m`` between the points it rests
    on: the morphological closing of the axis' height along the track by a
    parabola of that radius (a dilation by ``-t^2 / 2R`` followed by an
    erosion by the same), which fills every trough a pipe of that
    stiffness cannot reach and leaves the rest of the profile as it is.

    Parameters
    ----------
    axis_depth_m : numpy.ndarray
        Depth of the axis where the pipe rests on the bottom, at each ping.
    ping_spacing_m : float
        Along-track distance between pings.
    bend_radius_m : float
        Smallest bend radius along the track, m; 0 leaves the depths as they are.

    Returns
    -------
    numpy.ndarray
        The axis' depth at each ping, never deeper than ``axis_depth_m``.

    References
    ----------
    seeds/003, section 2: the model's burial ``B`` of the pipe below the
    local seafloor, negative over a free span.
    """
    depth = np.asarray(axis_depth_m, dtype=float)
    if bend_radius_m <= 0.0 or depth.size < 2:
        return depth.copy()
    along = np.arange(depth.size) * ping_spacing_m
    bowl = (along[:, None] - along[None, :]) ** 2 / (2.0 * bend_radius_m)
    height = -depth
    # Dilation by the cap -t^2/2R, then erosion: the lower envelope of hanging parabolas.
    capped = np.max(height[None, :] - bowl, axis=1)
    hung = np.min(capped[None, :] + bowl, axis=1)
    return np.minimum(depth, -hung)


def pipe_track(
    across_m: np.ndarray,
    burial: np.ndarray,
    radius_m: float,
    ping_spacing_m: float,
    base_m: np.ndarray,
    across: np.ndarray,
    bend_radius_m: float = 0.0,
) -> PipeTrack:
    """A pipe lying on the seabed along the given positions, buried as given, spanning troughs if stiff.

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
    bend_radius_m : float
        Smallest bend radius along the track (:func:`span_depth`); 0: the
        pipe rests on the seabed in every ping.

    Returns
    -------
    PipeTrack
        Over a free span the pipe's burial is 0.

    References
    ----------
    seeds/003, section 2: centre, depth and burial of a pipe.
    """
    burial = np.clip(burial, 0.0, 1.0)
    half_width = crossing_half_width(across_m, radius_m, ping_spacing_m)
    proud = resting_depth(base_m, across, across_m, half_width, radius_m)
    axis = proud + 2.0 * radius_m * burial
    if bend_radius_m > 0.0:
        axis = span_depth(axis, ping_spacing_m, bend_radius_m)
        burial = np.clip((axis - proud) / (2.0 * radius_m), 0.0, 1.0)
    return PipeTrack(
        across_m=np.asarray(across_m, dtype=float),
        axis_depth_m=axis,
        burial=burial,
        half_width_m=half_width,
        radius_m=radius_m,
    )
