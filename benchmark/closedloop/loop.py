"""The loop itself: from the vehicle's state to the camera's pose, and from an estimate to the next state.

A :class:`Loop` holds a route, the vehicle's kinematics, the camera's
mount and the controller.  Every frame it gives the camera's pose for the
scene to render (:meth:`Loop.pose`), takes the tracker's estimate of that
frame (:meth:`Loop.steer`), turns it into a command and moves the vehicle
by one frame interval, and keeps a :class:`Track` of where the vehicle was.
In real time (:mod:`benchmark.closedloop.real_time`) the next frame the
tracker sees may be several intervals later: the vehicle moves under the
previous command until the last of them, and under the new one over it.

The camera scenes render a straight cylinder along ``Z`` (seeds/004,
section II).  The pose handed to them is the vehicle's pose in the frame
of the route's tangent at the nearest point: ``Cx`` its lateral offset,
``Cz`` the arc length, the pan its heading error.  On a bend the cable is
so drawn straight along that tangent; over the ``L`` metres of cable a
camera sees, a bend of radius ``R`` departs from its tangent by
``L^2 / (8 R)`` at the middle of the view (:func:`bend_sag_m`), which
:data:`MAX_SAG_M` bounds for a route suite's routes.  The thesis assumes
the same of the cables it follows: "the curvature of the cable is very
small so that the cable borders appear as (more or less) straight lines in
the image" (seeds/000, section 4.1).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import pydantic

from benchmark.closedloop.controller import CableFollower
from benchmark.closedloop.route import Place, Route
from benchmark.closedloop.vehicle import Command, Kinematics, VehicleState
from benchmark.modalities.camera.model import CableState, CameraPose
from benchmark.scenes.spec import SPEC_CONFIG, Finite, Positive, TableSpec

MAX_SAG_M = 0.05
"""Largest departure of a drawn-straight bend from the route over the seen length, m."""


def bend_sag_m(seen_length_m: float, radius_m: float) -> float:
    """How far an arc of ``radius_m`` departs from its chord of ``seen_length_m`` at the chord's middle, m."""
    half = seen_length_m / 2.0
    return radius_m - math.sqrt(max(radius_m**2 - half**2, 0.0))


@pydantic.dataclasses.dataclass(frozen=True, config=SPEC_CONFIG)
class CameraMount(TableSpec):
    """The camera on the vehicle, held at a constant height over the cable's axis (seeds/000, section 4.1).

    Attributes
    ----------
    height_m : float
        ``Cy``: the camera's height above the pipe axis.
    tilt_deg : float
        ``phi``: 90 looks straight down (seeds/004, section II).
    """

    height_m: Positive = 2.0
    tilt_deg: Finite = 60.0

    def pose(self, place: Place) -> CameraPose:
        """The camera's pose in the frame of the route's tangent at ``place``."""
        return CameraPose(place.offset_m, self.height_m, place.s_m, place.heading_error, math.radians(self.tilt_deg), 0.0)


@dataclass
class Track:
    """Where the vehicle was at each frame, and what it was told.

    Attributes
    ----------
    places : list of Place
        Per frame, the vehicle against the route.
    states : list of VehicleState
        Per frame, the vehicle itself.
    commands : list of Command
        Per frame, the command the frame's estimate gave.
    searching : list of bool
        Per frame, whether the controller was searching after it.
    """

    places: list[Place] = field(default_factory=list)
    states: list[VehicleState] = field(default_factory=list)
    commands: list[Command] = field(default_factory=list)
    searching: list[bool] = field(default_factory=list)


class Loop:
    """One closed-loop run's vehicle, from the route's start to its end.

    Parameters
    ----------
    route : Route
        The cable.
    kinematics : Kinematics
        How commands move the vehicle.
    mount : CameraMount
        The camera on it.
    follower : CableFollower
        The controller.
    interval_s : float
        Time between frames, s.
    start : VehicleState, optional
        Where the vehicle starts; by default on the cable at its start, heading along it.
    """

    def __init__(
        self,
        route: Route,
        kinematics: Kinematics,
        mount: CameraMount,
        follower: CableFollower,
        interval_s: float,
        start: VehicleState | None = None,
    ) -> None:
        self.route, self.kinematics, self.mount, self.follower = route, kinematics, mount, follower
        self.interval_s = interval_s
        self.state = start or VehicleState(0.0, 0.0, 0.0)
        self.place = route.locate(self.state.x, self.state.z, self.state.psi)
        self.track = Track()
        self._command = Command()
        self._since_seen_s = interval_s

    @property
    def ended(self) -> bool:
        """Whether the vehicle has passed the route's end."""
        return self.place.s_m >= self.route.length_m - 1e-9

    def pose(self) -> CameraPose:
        """The camera's pose now, for the scene to render."""
        return self.mount.pose(self.place)

    def steer(self, estimate: CableState | None, intervals: int = 1) -> Command:
        """Take the estimate of the frame seen from :meth:`pose`, and move the vehicle to the next frame seen.

        Parameters
        ----------
        estimate : CableState or None
            The tracker's estimate of the frame; None when it gave none.
        intervals : int
            Frame intervals to the next frame the tracker sees (1 but in
            real time): the vehicle holds the previous command over all but
            the last, and obeys this estimate's command over the last
            (:mod:`benchmark.closedloop.real_time`).

        Returns
        -------
        Command
            The command this estimate gave.
        """
        if intervals < 1:
            raise ValueError(f"the next frame is at least 1 interval later, got {intervals}")
        command = self.follower.command(estimate, self._since_seen_s)
        self.track.places.append(self.place)
        self.track.states.append(self.state)
        self.track.commands.append(command)
        self.track.searching.append(self.follower.searching)
        for held in [self._command] * (intervals - 1) + [command]:
            self.state = self.kinematics.advance(self.state, held, self.interval_s)
            self.place = self.route.locate(self.state.x, self.state.z, self.state.psi, near_s_m=self.place.s_m)
        self._command, self._since_seen_s = command, intervals * self.interval_s
        return command
