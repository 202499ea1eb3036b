"""Definitions of simulated stereo sequences, as plain data.

A stereo sequence follows the simulations of seeds/002, section 3: a chase
boat (CH) with a stereo camera follows a target boat (TG); both move along
parameterised paths with speed profiles of constant-acceleration and
constant-speed legs (seeds/002, Fig. 6(b)).  The sequence is a pure
function of a :class:`StereoSceneSpec`, seed included.  Like the camera
specs (:mod:`benchmark.scenes.spec`), it is a tree of frozen dataclasses
built from a plain mapping by :meth:`StereoSceneSpec.from_dict`, so suites
are TOML files; its fields declare their ranges, and an unknown key or a
bad value is a :class:`benchmark.errors.DataError` naming the file, the key
and the rule.

The tree:

* :class:`BoatSpec` (one for each boat): a :class:`PathSpec` (a straight
  line or a sinusoid about a base course, whose amplitude grows smoothly
  from zero), the distance along it at the start, and the speed profile as
  knots ``(time, speed)`` joined by straight lines, i.e. legs of constant
  acceleration;
* :class:`StereoCameraSpec`: the stereo camera of seeds/002, Tables 3-4;
* :class:`StereoSensorSpec`: GPS and compass noise of CH, and the rule by
  which the stereo front end loses the target.

Positions are North-East in m (``X`` north, ``Y`` east); angles are in
degrees here and clockwise from north; times are in s.
"""

from __future__ import annotations

import math
import typing
from dataclasses import field
from typing import Annotated, Literal

import pydantic
from annotated_types import Ge, Gt, Interval

from benchmark.modalities.stereo.model import StereoCalibration
from benchmark.scenes.spec import (
    SPEC_CONFIG,
    Finite,
    Integer,
    Name,
    NonNegative,
    Number,
    TableSpec,
    Text,
    strictly_increasing,
)

SpeedClass = Literal["slow", "medium", "fast", "custom"]
"""Speed classes of seeds/002, section 3.5 (TG top speed 3.6, 7 and 9 m/s), and one for anything else."""

SPEED_CLASSES = typing.get_args(SpeedClass)

Case = Literal[0, 1, 2, 3]
"""The trajectory cases of seeds/002, section 3.2 (1: both straight; 2: CH straight, TG sinusoidal;
3: both sinusoidal), and 0 for a sequence that is none of them."""

CASES = typing.get_args(Case)


@pydantic.dataclasses.dataclass(frozen=True, config=SPEC_CONFIG)
class PathSpec:
    """A boat's path: a line, or a sinusoid about it (seeds/002, Fig. 8).

    Along-track distance ``u`` runs from ``origin_m`` along ``course_deg``;
    the path is offset to starboard of the course by

        ``amplitude_m * e(u) * sin(2 pi (u - onset_m) / wavelength_m + phase_deg)``,

    where the envelope ``e`` is 0 before ``onset_m``, 1 after
    ``onset_m + ramp_m`` and a quintic smooth step between, so heading and
    turn rate change continuously where the sinusoid begins.

    Attributes
    ----------
    origin_m : tuple of float
        North-East point where ``u = 0``.
    course_deg : float
        Base course, clockwise from north.
    amplitude_m : float
        Lateral amplitude of the sinusoid; 0 for a straight line.
    wavelength_m : float
        Along-track length of one period.
    phase_deg : float
        Phase of the sinusoid at ``u = onset_m``.
    onset_m : float
        Along-track distance where the sinusoid starts to grow.
    ramp_m : float
        Along-track distance over which it grows to full amplitude; 0 makes
        it start at once (a heading jump unless ``phase_deg`` is 0 or 180
        and then a jump of the turn rate).
    """

    origin_m: tuple[Finite, Finite] = (0.0, 0.0)
    course_deg: Finite = 0.0
    amplitude_m: NonNegative = 0.0
    wavelength_m: Annotated[Finite, Gt(0)] = 100.0
    phase_deg: Finite = 0.0
    onset_m: Finite = 0.0
    ramp_m: NonNegative = 0.0

    @property
    def straight(self) -> bool:
        """True for a straight line."""
        return self.amplitude_m == 0.0




def _starts_at_time_zero(knots: tuple[tuple[float, float], ...]) -> tuple[tuple[float, float], ...]:
    """``knots`` unchanged when the first is at time 0, else ``ValueError``."""
    if not knots or knots[0][0] != 0.0:
        raise ValueError(f"must start at time 0, got {list(knots)}")
    return knots


SpeedKnots = Annotated[
    tuple[tuple[Finite, NonNegative], ...],
    pydantic.AfterValidator(_starts_at_time_zero),
    pydantic.AfterValidator(strictly_increasing),
]
"""Points ``(time in s, speed in m/s)`` of a speed profile; linear between, constant after the last.

The first is at time 0, times increase strictly, speeds are ``>= 0``.
"""


@pydantic.dataclasses.dataclass(frozen=True, config=SPEC_CONFIG)
class BoatSpec:
    """One boat: its path, where on it it starts, and its speed profile.

    Attributes
    ----------
    path : PathSpec
        The path it follows.
    start_m : float
        Distance travelled along the path (its arc length from ``u = 0``) at
        time 0.
    speed_knots : SpeedKnots
        Knots ``(t, v)``; the first at ``t = 0``, times strictly increasing,
        speeds ``>= 0``.  Speed is linear between knots (constant
        acceleration) and constant after the last (seeds/002, Fig. 6(b)).
    """

    path: PathSpec = PathSpec()
    start_m: NonNegative = 0.0
    speed_knots: SpeedKnots = ((0.0, 2.0),)

    @property
    def top_speed_mps(self) -> float:
        """The highest speed of the profile."""
        return max(v for _, v in self.speed_knots)


@pydantic.dataclasses.dataclass(frozen=True, config=SPEC_CONFIG)
class StereoCameraSpec:
    """The stereo camera of seeds/002, Tables 3 and 4.

    Attributes
    ----------
    focal_px : float
        Focal length ``f`` in px.  ``f B = 16.896 m px`` gives Table 3 to
        every printed digit: disparity 1 px at 16.896 m, and a depth
        accuracy of 3.3792 m there for a correlation accuracy of 0.2 px.
    baseline_m : float
        Distance between the cameras (Table 4: 12 cm).
    width_px : int
        Horizontal stereo resolution (Table 4: 320 px).
    principal_left_px, principal_right_px : float or None
        ``C_y`` and ``C_y*``; None puts them at the image centre,
        ``(width_px - 1) / 2``.
    range_limit_m : float
        Operational range limit (seeds/002, section 2.2.1: 16 m).
    correlation_accuracy_px : float
        ``m``, the standard deviation of the disparity (seeds/002,
        section 2.2.1: 0.11 px); each of ``y_l`` and ``y_r`` gets noise of
        variance ``Q_f = m^2 / 2`` (eq. 19).
    """

    focal_px: Annotated[Number, Gt(0)] = 140.8
    baseline_m: Annotated[Number, Gt(0)] = 0.12
    width_px: Annotated[Integer, Ge(8)] = 320
    principal_left_px: Number | None = None
    principal_right_px: Number | None = None
    range_limit_m: Annotated[Number, Gt(0)] = 16.0
    correlation_accuracy_px: Annotated[Number, Ge(0)] = 0.11

    def calibration(self) -> StereoCalibration:
        """The camera as a :class:`benchmark.modalities.stereo.model.StereoCalibration`."""
        centre = (self.width_px - 1) / 2.0
        left = centre if self.principal_left_px is None else self.principal_left_px
        right = centre if self.principal_right_px is None else self.principal_right_px
        return StereoCalibration(
            focal_px=self.focal_px,
            baseline_m=self.baseline_m,
            principal_left_px=left,
            principal_right_px=right,
            width_px=self.width_px,
            range_limit_m=self.range_limit_m,
            correlation_accuracy_px=self.correlation_accuracy_px,
        )

    @property
    def pixel_noise_px(self) -> float:
        """Standard deviation of the noise on ``y_l`` and on ``y_r``: ``sqrt(Q_f) = m / sqrt(2)`` (eq. 19)."""
        return self.correlation_accuracy_px / math.sqrt(2.0)


@pydantic.dataclasses.dataclass(frozen=True, config=SPEC_CONFIG)
class StereoSensorSpec:
    """CH's navigation sensors and the stereo front end's failures.

    Attributes
    ----------
    gps_sigma_m : float
        Standard deviation of the GPS error on each of ``X`` and ``Y``.
    gps_correlation_s : float
        Correlation time of the GPS error (a first-order Gauss-Markov
        process); 0 for white noise.
    heading_sigma_deg : float
        Standard deviation of the compass error (white).
    min_disparity_px : float
        The front end loses the target when the disparity it measures is
        at most this (0.3 px: beyond about 56 m).
    dropout_rate : float
        Long-run share in [0, 1) of frames the detector misses for no
        geometric reason (glare, spray, a wrong match).
    dropout_burst_frames : float
        Mean length ``>= 1`` of a run of such misses.
    """

    gps_sigma_m: Annotated[Number, Ge(0)] = 0.3
    gps_correlation_s: Annotated[Number, Ge(0)] = 0.0
    heading_sigma_deg: Annotated[Number, Ge(0)] = 0.5
    min_disparity_px: Annotated[Number, Ge(0)] = 0.3
    dropout_rate: Annotated[Number, Interval(ge=0, lt=1)] = 0.02
    dropout_burst_frames: Annotated[Number, Ge(1)] = 3.0


@pydantic.dataclasses.dataclass(frozen=True, config=SPEC_CONFIG)
class StereoSceneSpec(TableSpec):
    """Everything that defines one simulated stereo sequence (seeds/002, section 3).

    Attributes
    ----------
    name : str
        Sequence name in results, e.g. ``"stereo/case1-slow"``.
    n_frames : int
        Number of frames.
    seed : int
        Seed of the GPS, compass and pixel noise and of the dropouts.
    description : str
        What the sequence is meant to test.
    case : int
        Trajectory case of seeds/002, section 3.2 (see :data:`CASES`).
    speed : str
        Speed class (see :data:`SPEED_CLASSES`).
    frame_interval_s : float
        ``dt``, the measurement cycle (seeds/002, Table 5: 0.2 s).
    camera : StereoCameraSpec
    sensors : StereoSensorSpec
    target : BoatSpec
        TG.
    chase : BoatSpec
        CH; its camera's optical axis points along its heading.
    """

    name: Name
    n_frames: Annotated[Integer, Ge(1)]
    seed: Integer = 0
    description: Text = ""
    case: Case = 0
    speed: SpeedClass = "custom"
    frame_interval_s: Annotated[Number, Gt(0)] = 0.2
    camera: StereoCameraSpec = field(default_factory=StereoCameraSpec)
    sensors: StereoSensorSpec = field(default_factory=StereoSensorSpec)
    target: BoatSpec = BoatSpec(start_m=8.0)
    chase: BoatSpec = BoatSpec()

    @property
    def duration_s(self) -> float:
        """Time of the last frame."""
        return (self.n_frames - 1) * self.frame_interval_s
