"""A cable's route on the seabed: where it runs, and where a vehicle stands against it.

A route is the cable's centreline in the seabed plane, built from a start
heading and a list of legs, each a straight stretch or an arc of constant
curvature (a turn of ``turn_deg`` over ``length_m``); an S-bend is two arcs
of opposite turns.  Positions are ``(x, z)`` in metres, ``x`` to the right
of the route's first heading and ``z`` along it, the seabed plane of the
pipeline frame of seeds/004, section II (``Z`` along the pipe, ``X``
horizontal, ``Y`` up).  A heading ``psi`` turns from ``+z`` towards ``+x``,
as the camera's pan ``theta`` does (:mod:`benchmark.modalities.camera.scenes.projection`).

:meth:`Route.locate` answers the two questions a closed-loop run asks every
frame: which point of the cable is nearest the vehicle (its arc length
``s``), and how far and how turned the vehicle is from it (the lateral
offset, positive to the right of the cable, and the heading error).  The
route is a pure function of its spec.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np
import pydantic

from benchmark.scenes.spec import SPEC_CONFIG, Finite, Positive, TableSpec

SAMPLE_M = 0.01
"""Spacing of the points the route is sampled at for :meth:`Route.locate`, m."""

SEARCH_M = 5.0
"""How far along the route, either side of a hint, :meth:`Route.locate` looks for the nearest point, m."""


@pydantic.dataclasses.dataclass(frozen=True, config=SPEC_CONFIG)
class Leg(TableSpec):
    """One leg of a route: ``length_m`` of cable turning by ``turn_deg`` at a constant rate (0: straight).

    Attributes
    ----------
    length_m : float
        Arc length of the leg.
    turn_deg : float
        Change of heading over the leg, positive towards ``+x`` (a right turn).
    """

    length_m: Positive
    turn_deg: Finite = 0.0

    def __post_init__(self) -> None:
        if abs(self.turn_deg) >= 180.0:
            raise ValueError(f"a leg turns by less than 180 deg, got {self.turn_deg}")


@pydantic.dataclasses.dataclass(frozen=True, config=SPEC_CONFIG)
class RouteSpec(TableSpec):
    """A route as data: its legs, in order from the start.

    Attributes
    ----------
    legs : tuple of Leg
        The legs; the route starts at ``(0, 0)`` heading along ``+z``.
    """

    legs: tuple[Leg, ...] = (Leg(100.0),)

    def __post_init__(self) -> None:
        if not self.legs:
            raise ValueError("a route needs at least one leg")


@dataclass(frozen=True)
class Place:
    """Where a vehicle stands against a route.

    Attributes
    ----------
    s_m : float
        Arc length of the route's point nearest the vehicle.
    offset_m : float
        Distance from that point, positive when the vehicle is right of the
        cable (towards the route's normal ``(cos psi, -sin psi)``).
    heading_error : float
        The vehicle's heading minus the route's there, rad, wrapped to ``(-pi, pi]``.
    route_heading : float
        The route's heading at ``s_m``, rad.
    """

    s_m: float
    offset_m: float
    heading_error: float
    route_heading: float


def wrap_angle(angle: float) -> float:
    """``angle`` in ``(-pi, pi]``."""
    wrapped = math.remainder(angle, math.tau)
    return math.pi if wrapped == -math.pi else wrapped


class Route:
    """The centreline a :class:`RouteSpec` declares, sampled every :data:`SAMPLE_M`.

    Parameters
    ----------
    spec : RouteSpec
        Its legs.
    """

    def __init__(self, spec: RouteSpec) -> None:
        self.spec = spec

    @property
    def length_m(self) -> float:
        """Total arc length, m."""
        return float(sum(leg.length_m for leg in self.spec.legs))

    @cached_property
    def _samples(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Arc lengths, points ``(n, 2)`` and headings of the sampled centreline."""
        s_parts, psi_parts, xz_parts = [], [], []
        s0, psi0, x0, z0 = 0.0, 0.0, 0.0, 0.0
        for leg in self.spec.legs:
            n = max(2, math.ceil(leg.length_m / SAMPLE_M) + 1)
            u = np.linspace(0.0, leg.length_m, n)
            kappa = math.radians(leg.turn_deg) / leg.length_m
            psi = psi0 + kappa * u
            if kappa == 0.0:
                x, z = x0 + u * math.sin(psi0), z0 + u * math.cos(psi0)
            else:
                # The arc of curvature kappa: d(x, z)/du = (sin psi, cos psi) with psi = psi0 + kappa u.
                x = x0 + (math.cos(psi0) - np.cos(psi)) / kappa
                z = z0 + (np.sin(psi) - math.sin(psi0)) / kappa
            first = 0 if not s_parts else 1
            s_parts.append(s0 + u[first:])
            psi_parts.append(psi[first:])
            xz_parts.append(np.column_stack((x, z))[first:])
            s0, psi0, x0, z0 = s0 + leg.length_m, float(psi[-1]), float(x[-1]), float(z[-1])
        return np.concatenate(s_parts), np.concatenate(xz_parts), np.concatenate(psi_parts)

    def point(self, s_m: float) -> tuple[float, float]:
        """The centreline's point at arc length ``s_m`` (clamped to the route), ``(x, z)`` in m."""
        s, xz, _ = self._samples
        return float(np.interp(s_m, s, xz[:, 0])), float(np.interp(s_m, s, xz[:, 1]))

    def heading(self, s_m: float) -> float:
        """The centreline's heading at arc length ``s_m`` (clamped to the route), rad."""
        s, _, psi = self._samples
        return float(np.interp(s_m, s, psi))

    def locate(self, x: float, z: float, psi: float, near_s_m: float | None = None) -> Place:
        """Where a vehicle at ``(x, z)`` heading ``psi`` stands against the route.

        Parameters
        ----------
        x, z : float
            The vehicle's position, m.
        psi : float
            Its heading, rad.
        near_s_m : float, optional
            An arc length near the answer (the previous frame's): only
            :data:`SEARCH_M` either side of it is searched, so that where the
            route comes back near itself the vehicle keeps to the stretch it
            follows.  Without it the whole route is searched.

        Returns
        -------
        Place
            The nearest sampled point's arc length, refined by projecting the
            vehicle on the chord to its neighbour, the signed offset and the
            heading error.
        """
        s, xz, headings = self._samples
        if near_s_m is None:
            low, high = 0, len(s)
        else:
            low = int(np.searchsorted(s, near_s_m - SEARCH_M))
            high = int(np.searchsorted(s, near_s_m + SEARCH_M, side="right"))
            low, high = max(0, min(low, len(s) - 2)), max(low + 2, min(high, len(s)))
        window = xz[low:high]
        k = low + int(np.argmin((window[:, 0] - x) ** 2 + (window[:, 1] - z) ** 2))
        k = min(k, len(s) - 2)
        # Refine along the chord from sample k to k + 1, and from k - 1 to k.
        best = None
        for a in (k - 1, k):
            if a < 0:
                continue
            p, q = xz[a], xz[a + 1]
            chord = q - p
            t = float(np.clip(((x - p[0]) * chord[0] + (z - p[1]) * chord[1]) / float(chord @ chord), 0.0, 1.0))
            foot = p + t * chord
            distance2 = (x - foot[0]) ** 2 + (z - foot[1]) ** 2
            if best is None or distance2 < best[0]:
                best = (distance2, float(s[a] + t * (s[a + 1] - s[a])), foot)
        assert best is not None
        _, s_m, foot = best
        route_psi = float(np.interp(s_m, s, headings))
        offset = (x - foot[0]) * math.cos(route_psi) - (z - foot[1]) * math.sin(route_psi)
        return Place(s_m, float(offset), wrap_angle(psi - route_psi), route_psi)
