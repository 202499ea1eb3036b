"""The vehicle of a closed-loop run: where it is, and how a command moves it.

The thesis's vehicle keeps a constant altitude, so it moves in a plane
parallel to the seabed; it changes its yaw and moves forward, and the
camera is rigidly mounted on it (seeds/000, section 4.1).  The controller
here also sets a sway speed, as a thruster-driven vehicle can.  So the
vehicle's state is its position ``(x, z)`` in the seabed plane and its
heading ``psi`` (:mod:`benchmark.closedloop.route`), and a
:class:`Command` is a sway speed and a yaw rate; the surge speed is the
route's.  Over a frame interval the command is held and the motion
integrated exactly (a body moving at constant body velocities and a
constant turn rate traces an arc).  Each speed is limited, and a change of
command reaches the vehicle through a first-order lag of declared time
constant, the simplest model of a vehicle's inertia.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import pydantic

from benchmark.scenes.spec import SPEC_CONFIG, NonNegative, Positive, TableSpec


@dataclass(frozen=True)
class Command:
    """What the controller asks of the vehicle.

    Attributes
    ----------
    sway_mps : float
        Speed to the vehicle's right, m/s.
    yaw_rate : float
        Turn rate, rad/s, positive turning the heading towards ``+x`` (to the right).
    """

    sway_mps: float = 0.0
    yaw_rate: float = 0.0


@dataclass(frozen=True)
class VehicleState:
    """The vehicle in the seabed plane, with the speeds it is moving at.

    Attributes
    ----------
    x, z : float
        Position, m.
    psi : float
        Heading, rad, from ``+z`` towards ``+x``.
    sway_mps, yaw_rate : float
        The sway speed and turn rate it moves at now (after the lag).
    """

    x: float
    z: float
    psi: float
    sway_mps: float = 0.0
    yaw_rate: float = 0.0


@pydantic.dataclasses.dataclass(frozen=True, config=SPEC_CONFIG)
class Kinematics(TableSpec):
    """The declared kinematic model.

    Attributes
    ----------
    surge_mps : float
        Forward speed, held constant.
    max_sway_mps : float
        Largest sway speed either way.
    max_yaw_rate_dps : float
        Largest turn rate either way, deg/s.
    lag_s : float
        Time constant of the first-order lag between a command and the
        vehicle's speeds; 0 obeys at once.
    """

    surge_mps: Positive = 0.45
    max_sway_mps: Positive = 0.3
    max_yaw_rate_dps: Positive = 15.0
    lag_s: NonNegative = 0.5

    def limited(self, command: Command) -> Command:
        """``command`` with each speed clamped to its limit."""
        max_rate = math.radians(self.max_yaw_rate_dps)
        return Command(
            min(max(command.sway_mps, -self.max_sway_mps), self.max_sway_mps),
            min(max(command.yaw_rate, -max_rate), max_rate),
        )

    def advance(self, state: VehicleState, command: Command, interval_s: float) -> VehicleState:
        """The state ``interval_s`` later, ``command`` held over the interval.

        The speeds first move towards the limited command by the lag's
        factor ``1 - exp(-interval / lag)``; then the body, at surge ``u``,
        sway ``v`` and turn rate ``r``, moves along the arc those constant
        body speeds trace: with ``psi(t) = psi0 + r t``, the velocity in the
        plane is ``u (sin psi, cos psi) + v (cos psi, -sin psi)``, integrated
        in closed form (a straight line where ``r = 0``).
        """
        target = self.limited(command)
        keep = math.exp(-interval_s / self.lag_s) if self.lag_s > 0 else 0.0
        sway = target.sway_mps + (state.sway_mps - target.sway_mps) * keep
        rate = target.yaw_rate + (state.yaw_rate - target.yaw_rate) * keep
        u, v, psi0 = self.surge_mps, sway, state.psi
        psi1 = psi0 + rate * interval_s
        if abs(rate) * interval_s < 1e-12:
            sin_int, cos_int = math.sin(psi0) * interval_s, math.cos(psi0) * interval_s
        else:
            # Integrals of sin(psi) and cos(psi) over the interval.
            sin_int = (math.cos(psi0) - math.cos(psi1)) / rate
            cos_int = (math.sin(psi1) - math.sin(psi0)) / rate
        dx = u * sin_int + v * cos_int
        dz = u * cos_int - v * sin_int
        return VehicleState(state.x + dx, state.z + dz, psi1, sway, rate)
