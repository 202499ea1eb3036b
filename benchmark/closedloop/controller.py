"""The cable-following controller every closed-loop run shares.

The controller the thesis's tracker was built for needs "the position and
the angle of the cable in the image", the parameters of its centreline, and
steers "the vehicle in such a way that the cable is vertically aligned in
the center of the image" (seeds/000, section 4.1 and Fig. 4.2, on the
controller of Antich and Ortiz).  :class:`CableFollower` is that
controller as a PD law on two errors read off a tracker's estimate
``(d, alpha, w, beta)`` (conventions.md, section 1):

* the lateral error ``e = d / cos(alpha) / (W / 2)``: where the centreline
  crosses the image's middle row, as a share of the half width, positive
  right of the centre;
* the angle error ``alpha``: positive when the cable's top leans left.

A cable right of the centre asks for sway to the right; a cable whose top
leans left asks for a turn to the left:

    sway     = k_e e + k_de de/dt
    yaw rate = -(k_a alpha + k_da dalpha/dt)

The derivatives are differences of consecutive estimates over the time
between their frames (the frame interval, or more when a tracker in
real time skips frames: :mod:`benchmark.closedloop.real_time`), and
restart after a frame without one.  Without an estimate the
controller holds its last command for ``hold_s``; then it searches: it
stops turning and sways towards the side it last saw the cable at
``search_sway_mps``.  The gains belong to the route suite, never to a
tracker, so that every tracker drives the same vehicle.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import pydantic

from benchmark.closedloop.vehicle import Command
from benchmark.modalities.camera.model import CableState
from benchmark.scenes.spec import SPEC_CONFIG, NonNegative, TableSpec


@pydantic.dataclasses.dataclass(frozen=True, config=SPEC_CONFIG)
class FollowerGains(TableSpec):
    """The controller's declared gains and behaviours.

    Attributes
    ----------
    k_offset_mps : float
        Sway per unit of lateral error (the centreline at the image's edge), m/s.
    k_offset_rate_m : float
        Sway per unit of lateral error per second, m.
    k_angle_per_s : float
        Turn rate per radian of the cable's angle, 1/s.
    k_angle_rate : float
        Turn rate per radian per second of the angle's change (dimensionless).
    hold_s : float
        How long the last command is held once the tracker reports nothing, s.
    search_sway_mps : float
        Sway towards the side the cable was last seen, while searching.

    Notes
    -----
    The defaults were set on the loop driven by the true cable alone (no
    tracker, no scored data; ``tests/datasets/suites/test_routes_suite.py``
    drives it on every route): with them the truth brings the vehicle from
    0.3 m beside the cable to within its 0.1 m radius in 5.3 s on the
    ``straight`` route, and keeps it within 2.7 cm of the cable and 2.6 deg
    of its heading over the ``s-bends``.  The hold (1 s) covers a
    tracker's brief misses; the search sway (0.1 m/s) crabs the vehicle at
    12.5 deg to its 0.45 m/s surge.
    """

    k_offset_mps: NonNegative = 0.25
    k_offset_rate_m: NonNegative = 0.05
    k_angle_per_s: NonNegative = 0.6
    k_angle_rate: NonNegative = 0.1
    hold_s: NonNegative = 1.0
    search_sway_mps: NonNegative = 0.1


@dataclass(frozen=True)
class Seen:
    """The errors read off one estimate.

    Attributes
    ----------
    offset : float
        Lateral error, a share of the half width, positive right.
    angle : float
        The centreline's angle, rad.
    """

    offset: float
    angle: float

    @classmethod
    def of(cls, estimate: CableState, width_px: int) -> Seen | None:
        """The errors of ``estimate`` in an image ``width_px`` wide; None when it has no centreline."""
        if not estimate.is_known or abs(math.cos(estimate.alpha)) < 1e-6:
            return None
        return cls(estimate.d / math.cos(estimate.alpha) / (width_px / 2.0), estimate.alpha)


class CableFollower:
    """The PD law of the module docstring, with its hold and search behaviour.

    Parameters
    ----------
    gains : FollowerGains
        The declared gains.
    interval_s : float
        The time between frames, s.
    width_px : int
        The image's width, px.
    """

    def __init__(self, gains: FollowerGains, interval_s: float, width_px: int) -> None:
        self.gains = gains
        self.interval_s = interval_s
        self.width_px = width_px
        self._previous: Seen | None = None
        self._last_seen: Seen | None = None
        self._command = Command()
        self._unseen_s = 0.0

    @property
    def searching(self) -> bool:
        """Whether the cable has been unseen for longer than the hold."""
        return self._unseen_s > self.gains.hold_s

    def command(self, estimate: CableState | None, elapsed_s: float | None = None) -> Command:
        """The command after a frame whose estimate is ``estimate`` (None: the tracker saw nothing).

        ``elapsed_s`` is the time since the previous frame the tracker saw;
        by default the frame interval.
        """
        gains = self.gains
        elapsed_s = self.interval_s if elapsed_s is None else elapsed_s
        seen = Seen.of(estimate, self.width_px) if estimate is not None else None
        if seen is None:
            self._previous = None
            self._unseen_s += elapsed_s
            if self.searching:
                side = 0.0 if self._last_seen is None else math.copysign(1.0, self._last_seen.offset)
                self._command = Command(side * gains.search_sway_mps, 0.0)
            return self._command
        self._unseen_s = 0.0
        offset_rate = angle_rate = 0.0
        if self._previous is not None:
            offset_rate = (seen.offset - self._previous.offset) / elapsed_s
            angle_rate = (seen.angle - self._previous.angle) / elapsed_s
        self._previous = self._last_seen = seen
        self._command = Command(
            gains.k_offset_mps * seen.offset + gains.k_offset_rate_m * offset_rate,
            -(gains.k_angle_per_s * seen.angle + gains.k_angle_rate * angle_rate),
        )
        return self._command
