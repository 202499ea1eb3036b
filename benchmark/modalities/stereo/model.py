"""What stereo frames hold: the target measurement, the chase boat's navigation, the truth.

Stereo frames follow a chase boat (CH) that tracks a target boat (TG) with a
stereo camera (seeds/002): the observation is a :class:`StereoMeasurement`
(None when the front end lost the target) or, in the image suites, a pair
of BGR images ``(left, right)``; the navigation is CH's
:class:`ChaseNavigation`, the truth a :class:`StereoTruth`, and an estimate
a :class:`TargetEstimate`.  Positions are North-East coordinates in m
(``X`` north, ``Y`` east) and headings are clockwise from north,
``atan2(Y_dot, X_dot)`` (seeds/002, eq. 10, Fig. 3).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from benchmark.model import Frame


@dataclass(frozen=True, slots=True)
class StereoCalibration:
    """The stereo camera of a stereo sequence (seeds/002, Table 4 and eq. 15).

    Attributes
    ----------
    focal_px : float
        Focal length ``f`` in px.
    baseline_m : float
        Distance ``T_y`` between the two cameras.
    principal_left_px, principal_right_px : float
        Horizontal image coordinate of the principal point, ``C_y`` (left)
        and ``C_y*`` (right).
    width_px : int
        Horizontal resolution of each image.
    range_limit_m : float
        Operational range beyond which measurements are unreliable.
    correlation_accuracy_px : float
        ``m``: standard deviation of the disparity (seeds/002, eq. 19).
    """

    focal_px: float
    baseline_m: float
    principal_left_px: float
    principal_right_px: float
    width_px: int
    range_limit_m: float
    correlation_accuracy_px: float


@dataclass(frozen=True, slots=True)
class StereoMeasurement:
    """What the stereo front end reports about the target in one frame.

    Attributes
    ----------
    left_px, right_px : float
        Horizontal image coordinates ``y_l`` and ``y_r`` of the target in
        the left and right images (seeds/002, eqs. 13 and 15); their
        difference is the disparity ``d = y_l - y_r``.
    relative_m : tuple of float
        ``(x_v, y_v)``: the target relative to the camera by triangulation
        (seeds/002, eq. 15), ``x_v`` ahead, ``y_v`` to starboard.
    """

    left_px: float
    right_px: float
    relative_m: tuple[float, float]


@dataclass(frozen=True, slots=True)
class ChaseNavigation:
    """The chase boat's own sensors: GPS position (North-East, m) and heading (rad)."""

    position_m: tuple[float, float]
    heading: float


@dataclass(frozen=True, slots=True)
class TargetEstimate:
    """Position and velocity of the target boat, North-East (seeds/002, eq. 5 state)."""

    position_m: tuple[float, float]
    velocity_mps: tuple[float, float]

    @property
    def speed_mps(self) -> float:
        return math.hypot(*self.velocity_mps)

    @property
    def heading(self) -> float:
        """Clockwise from north, rad: ``atan2(Y_dot, X_dot)``."""
        return math.atan2(self.velocity_mps[1], self.velocity_mps[0])


@dataclass(frozen=True, slots=True)
class StereoTruth:
    """Ground truth of one stereo frame.

    Attributes
    ----------
    target : TargetEstimate
        The target's true position and velocity (speed and heading follow).
    chase_position_m : tuple of float
        The chase boat's true position.
    chase_heading : float
        The chase boat's true heading, rad.
    """

    target: TargetEstimate
    chase_position_m: tuple[float, float]
    chase_heading: float

    @property
    def range_m(self) -> float:
        """Distance between the boats."""
        return math.dist(self.target.position_m, self.chase_position_m)



StereoObservation = StereoMeasurement | tuple[np.ndarray, np.ndarray] | None
"""A measurement, a pair of ``uint8`` BGR images ``(left, right)``, or None (target lost)."""

StereoFrame = Frame[StereoObservation, StereoTruth]
"""A stereo frame: a :data:`StereoObservation`, a :class:`StereoTruth` or None, and :class:`ChaseNavigation`."""
