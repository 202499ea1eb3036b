"""Boat trajectories of the stereo simulations, and the geometry between two boats.

The trajectory generator of seeds/002, section 3 moves each boat along a
parameterised path (a line or a sinusoid, Fig. 8) with a speed profile of
constant-acceleration and constant-speed legs (Fig. 6(b)).  Here a profile
is a list of knots ``(t, v)`` joined by straight lines, so the distance
travelled is exact: piecewise quadratic in time.  The path is parameterised
by its along-track distance ``u``; the boat sits where the path's arc length
equals the distance travelled, found by inverting a fine table of the arc
length.  The velocity is the speed times the unit tangent, so a boat's
heading is the path's direction, ``atan2(Y_dot, X_dot)`` clockwise from
north.

Everything here is deterministic; nothing depends on a seed.  A renderer of
stereo images reuses :func:`boat_track` and :func:`relative_geometry` on the
same :class:`~benchmark.modalities.stereo.scenes.spec.BoatSpec` definitions to put the
target in its images exactly where these sequences measure it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from benchmark.modalities.stereo.geometry import to_camera
from benchmark.modalities.stereo.scenes.spec import BoatSpec, PathSpec, SpeedKnots

ARC_STEP_M = 0.02
"""Step of the along-track grid on which arc length is tabulated."""


def _knot_arrays(knots: SpeedKnots) -> tuple[np.ndarray, np.ndarray]:
    times = np.array([t for t, _ in knots], dtype=float)
    speeds = np.array([v for _, v in knots], dtype=float)
    return times, speeds


def profile_speed(knots: SpeedKnots, times: np.ndarray) -> np.ndarray:
    """Speed of a constant-acceleration profile at ``times``.

    Parameters
    ----------
    knots : SpeedKnots
        ``(t, v)`` points, the first at ``t = 0``; linear between them,
        constant after the last.
    times : numpy.ndarray
        Times ``>= 0`` in s.

    Returns
    -------
    numpy.ndarray
        Speeds in m/s.

    References
    ----------
    seeds/002, section 3 and Fig. 6(b).
    """
    knot_t, knot_v = _knot_arrays(knots)
    return np.interp(np.asarray(times, dtype=float), knot_t, knot_v)


def profile_distance(knots: SpeedKnots, times: np.ndarray) -> np.ndarray:
    """Distance travelled from time 0 under the profile, integrated exactly.

    Parameters
    ----------
    knots : SpeedKnots
        As for :func:`profile_speed`.
    times : numpy.ndarray
        Times ``>= 0`` in s.

    Returns
    -------
    numpy.ndarray
        Distances in m: ``S_j + v_j (t - t_j) + a_j (t - t_j)^2 / 2`` in the
        leg ``j`` that holds ``t``.

    References
    ----------
    seeds/002, section 3: speed changes under constant acceleration.
    """
    knot_t, knot_v = _knot_arrays(knots)
    t = np.asarray(times, dtype=float)
    accel = np.append(np.diff(knot_v) / np.diff(knot_t), 0.0)
    start = np.concatenate(([0.0], np.cumsum(0.5 * (knot_v[1:] + knot_v[:-1]) * np.diff(knot_t))))
    leg = np.clip(np.searchsorted(knot_t, t, side="right") - 1, 0, len(knot_t) - 1)
    since = t - knot_t[leg]
    return start[leg] + knot_v[leg] * since + 0.5 * accel[leg] * since**2


def _envelope(path: PathSpec, u: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Quintic smooth step from 0 to 1 over ``[onset, onset + ramp]`` and its derivative in ``u``."""
    if path.ramp_m == 0.0:
        return (u >= path.onset_m).astype(float), np.zeros_like(u)
    with np.errstate(over="ignore"):  # a ramp too short to resolve is a step: the quotient saturates to +-inf
        x = np.clip((u - path.onset_m) / path.ramp_m, 0.0, 1.0)
    value = x**3 * (10.0 - 15.0 * x + 6.0 * x**2)
    slope = 30.0 * x**2 * (1.0 - x) ** 2 / path.ramp_m
    return value, slope


def _course_axes(path: PathSpec) -> tuple[np.ndarray, np.ndarray]:
    """Unit vectors (North, East) along the course and to its starboard."""
    course = math.radians(path.course_deg)
    return np.array((math.cos(course), math.sin(course))), np.array((-math.sin(course), math.cos(course)))


def path_offset(path: PathSpec, u: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Lateral offset to starboard of the course, and its derivative in ``u``.

    Parameters
    ----------
    path : PathSpec
        The path.
    u : numpy.ndarray
        Along-track distances in m.

    Returns
    -------
    offset, slope : numpy.ndarray
        The offset in m and ``d offset / d u``.

    References
    ----------
    seeds/002, Fig. 8: straight and sinusoidal trajectories.
    """
    u = np.asarray(u, dtype=float)
    if path.straight:
        return np.zeros_like(u), np.zeros_like(u)
    k = 2.0 * math.pi / path.wavelength_m
    angle = k * (u - path.onset_m) + math.radians(path.phase_deg)
    env, env_slope = _envelope(path, u)
    offset = path.amplitude_m * env * np.sin(angle)
    slope = path.amplitude_m * (env_slope * np.sin(angle) + env * k * np.cos(angle))
    return offset, slope


def path_points(path: PathSpec, u: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """North-East points of the path and its unit tangents at along-track distances ``u``.

    Parameters
    ----------
    path : PathSpec
        The path.
    u : numpy.ndarray
        Along-track distances in m.

    Returns
    -------
    points, tangents : numpy.ndarray
        Both of shape ``(len(u), 2)``, columns ``(X, Y)``.
    """
    u = np.asarray(u, dtype=float)
    ahead, starboard = _course_axes(path)
    offset, slope = path_offset(path, u)
    points = np.asarray(path.origin_m) + u[:, None] * ahead + offset[:, None] * starboard
    direction = ahead + slope[:, None] * starboard
    return points, direction / np.hypot(direction[:, 0], direction[:, 1])[:, None]


def along_track(path: PathSpec, arc_m: np.ndarray) -> np.ndarray:
    """Along-track distance ``u`` at which the path's arc length from ``u = 0`` is ``arc_m``.

    Parameters
    ----------
    path : PathSpec
        The path.
    arc_m : numpy.ndarray
        Arc lengths ``>= 0`` in m.

    Returns
    -------
    numpy.ndarray
        ``u`` in m, from a table of the arc length on a grid of
        :data:`ARC_STEP_M` (trapezoid rule; errors are far below 1 mm).
    """
    arc = np.asarray(arc_m, dtype=float)
    if path.straight or arc.size == 0:
        return arc.copy()
    top = float(np.max(arc)) + 1.0
    grid = np.arange(0.0, top + ARC_STEP_M, ARC_STEP_M)
    _, slope = path_offset(path, grid)
    stretch = np.sqrt(1.0 + slope**2)
    table = np.concatenate(([0.0], np.cumsum(0.5 * (stretch[1:] + stretch[:-1]) * ARC_STEP_M)))
    return np.interp(arc, table, grid)


@dataclass(frozen=True)
class BoatTrack:
    """A boat's true state at a series of times.

    Attributes
    ----------
    times_s : numpy.ndarray
        Shape ``(n,)``.
    position_m : numpy.ndarray
        Shape ``(n, 2)``, North-East.
    velocity_mps : numpy.ndarray
        Shape ``(n, 2)``, ``(X_dot, Y_dot)``.
    heading : numpy.ndarray
        Shape ``(n,)``, rad clockwise from north: the direction of the path,
        which is ``atan2(Y_dot, X_dot)`` whenever the boat moves.
    """

    times_s: np.ndarray
    position_m: np.ndarray
    velocity_mps: np.ndarray
    heading: np.ndarray

    def __len__(self) -> int:
        return len(self.times_s)

    @property
    def speed_mps(self) -> np.ndarray:
        """Speed at every time."""
        return np.hypot(self.velocity_mps[:, 0], self.velocity_mps[:, 1])


def boat_track(boat: BoatSpec, times_s: np.ndarray) -> BoatTrack:
    """The true position, velocity and heading of a boat at ``times_s``.

    Parameters
    ----------
    boat : BoatSpec
        Path, start and speed profile.
    times_s : numpy.ndarray
        Times ``>= 0`` in s.

    Returns
    -------
    BoatTrack

    References
    ----------
    seeds/002, section 3: parameterised trajectories with constant-acceleration
    speed changes; eq. (5): the state ``(X, Y, X_dot, Y_dot)``.
    """
    times = np.asarray(times_s, dtype=float)
    arc = boat.start_m + profile_distance(boat.speed_knots, times)
    points, tangents = path_points(boat.path, along_track(boat.path, arc))
    velocity = profile_speed(boat.speed_knots, times)[:, None] * tangents
    heading = np.arctan2(tangents[:, 1], tangents[:, 0])
    return BoatTrack(times_s=times, position_m=points, velocity_mps=velocity, heading=heading)


@dataclass(frozen=True)
class RelativeGeometry:
    """Where the target is as seen from the chase boat, at a series of times.

    Attributes
    ----------
    ahead_m, starboard_m : numpy.ndarray
        ``(x_v, y_v)`` of seeds/002, eq. (11): the target in CH's frame.
    range_m : numpy.ndarray
        Distance between the boats.
    bearing : numpy.ndarray
        Direction of the target, rad clockwise from CH's bow.
    aspect : numpy.ndarray
        TG's heading minus CH's, rad in ``[-pi, pi)``: how the target boat
        is turned in the view.
    """

    ahead_m: np.ndarray
    starboard_m: np.ndarray
    range_m: np.ndarray
    bearing: np.ndarray
    aspect: np.ndarray


def relative_geometry(chase: BoatTrack, target: BoatTrack) -> RelativeGeometry:
    """The true target position relative to the chase boat, eq. (11) without noise.

    Parameters
    ----------
    chase, target : BoatTrack
        Tracks sampled at the same times.

    Returns
    -------
    RelativeGeometry

    References
    ----------
    seeds/002, eqs. (10)-(11) and Fig. 3.
    """
    north, east = target.position_m.T
    ahead, starboard = to_camera(north, east, chase.position_m.T, chase.heading)
    aspect = np.mod(target.heading - chase.heading + math.pi, 2.0 * math.pi) - math.pi
    return RelativeGeometry(
        ahead_m=ahead,
        starboard_m=starboard,
        range_m=np.hypot(ahead, starboard),
        bearing=np.arctan2(starboard, ahead),
        aspect=aspect,
    )
