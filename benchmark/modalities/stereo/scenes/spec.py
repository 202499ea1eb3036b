"""Definitions of simulated stereo sequences, as plain data.

A stereo sequence follows the simulations of seeds/002, section 3: a chase
boat (CH) with a stereo camera follows a target boat (TG); both move along
parameterised paths with speed profiles of constant-acceleration and
constant-speed legs (seeds/002, Fig. 6(b)).  The sequence is a pure
function of a :class:`StereoSceneSpec`, seed included.  Like the camera
specs (:mod:`benchmark.scenes.spec`), it is a tree of frozen dataclasses
built from a plain mapping by :meth:`StereoSceneSpec.from_dict`, so suites
are TOML files; an unknown key or a bad value is a
:class:`benchmark.errors.DataError` naming where it was found.

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
from dataclasses import dataclass, field

from benchmark.modalities.stereo.model import StereoCalibration
from benchmark.scenes.spec import TableSpec

SPEED_CLASSES = ("slow", "medium", "fast", "custom")
"""Speed classes of seeds/002, section 3.5 (TG top speed 3.6, 7 and 9 m/s), and one for anything else."""

CASES = (0, 1, 2, 3)
"""The trajectory cases of seeds/002, section 3.2 (1: both straight; 2: CH straight, TG sinusoidal;
3: both sinusoidal), and 0 for a sequence that is none of them."""


@dataclass(frozen=True)
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

    origin_m: tuple[float, float] = (0.0, 0.0)
    course_deg: float = 0.0
    amplitude_m: float = 0.0
    wavelength_m: float = 100.0
    phase_deg: float = 0.0
    onset_m: float = 0.0
    ramp_m: float = 0.0

    def __post_init__(self) -> None:
        values = (*self.origin_m, self.course_deg, self.amplitude_m, self.wavelength_m, self.phase_deg)
        if not all(math.isfinite(v) for v in (*values, self.onset_m, self.ramp_m)):
            raise ValueError("path values must be finite")
        if not self.wavelength_m > 0 or self.ramp_m < 0 or self.amplitude_m < 0:
            raise ValueError("need wavelength_m > 0, amplitude_m >= 0 and ramp_m >= 0")

    @property
    def straight(self) -> bool:
        """True for a straight line."""
        return self.amplitude_m == 0.0


SpeedKnots = tuple[tuple[float, float], ...]
"""Points ``(time in s, speed in m/s)`` of a speed profile; linear between, constant after the last."""


@dataclass(frozen=True)
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
    start_m: float = 0.0
    speed_knots: SpeedKnots = ((0.0, 2.0),)

    def __post_init__(self) -> None:
        if not (math.isfinite(self.start_m) and self.start_m >= 0):
            raise ValueError(f"start_m must be finite and >= 0, got {self.start_m}")
        knots = self.speed_knots
        if not knots or knots[0][0] != 0.0:
            raise ValueError(f"speed_knots must start at time 0, got {knots}")
        if not all(math.isfinite(t) and math.isfinite(v) and v >= 0 for t, v in knots):
            raise ValueError(f"speed_knots need finite times and finite speeds >= 0, got {knots}")
        times = [t for t, _ in knots]
        if any(b <= a for a, b in zip(times, times[1:])):
            raise ValueError(f"speed_knots times must increase strictly, got {times}")

    @property
    def top_speed_mps(self) -> float:
        """The highest speed of the profile."""
        return max(v for _, v in self.speed_knots)


@dataclass(frozen=True)
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

    focal_px: float = 140.8
    baseline_m: float = 0.12
    width_px: int = 320
    principal_left_px: float | None = None
    principal_right_px: float | None = None
    range_limit_m: float = 16.0
    correlation_accuracy_px: float = 0.11

    def __post_init__(self) -> None:
        if not (self.focal_px > 0 and self.baseline_m > 0 and self.width_px >= 8 and self.range_limit_m > 0):
            raise ValueError("need focal_px > 0, baseline_m > 0, width_px >= 8 and range_limit_m > 0")
        if not self.correlation_accuracy_px >= 0:
            raise ValueError(f"correlation_accuracy_px must be >= 0, got {self.correlation_accuracy_px}")

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


@dataclass(frozen=True)
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

    gps_sigma_m: float = 0.3
    gps_correlation_s: float = 0.0
    heading_sigma_deg: float = 0.5
    min_disparity_px: float = 0.3
    dropout_rate: float = 0.02
    dropout_burst_frames: float = 3.0

    def __post_init__(self) -> None:
        if min(self.gps_sigma_m, self.gps_correlation_s, self.heading_sigma_deg) < 0:
            raise ValueError("gps_sigma_m, gps_correlation_s and heading_sigma_deg must be >= 0")
        if not (0 <= self.dropout_rate < 1 and self.dropout_burst_frames >= 1):
            raise ValueError("need 0 <= dropout_rate < 1 and dropout_burst_frames >= 1")
        if not self.min_disparity_px >= 0:
            raise ValueError(f"min_disparity_px must be >= 0, got {self.min_disparity_px}")


@dataclass(frozen=True)
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

    name: str
    n_frames: int
    seed: int = 0
    description: str = ""
    case: int = 0
    speed: str = "custom"
    frame_interval_s: float = 0.2
    camera: StereoCameraSpec = field(default_factory=StereoCameraSpec)
    sensors: StereoSensorSpec = field(default_factory=StereoSensorSpec)
    target: BoatSpec = BoatSpec(start_m=8.0)
    chase: BoatSpec = BoatSpec()

    def __post_init__(self) -> None:
        if not self.name:
            raise ValueError("name must not be empty")
        if self.n_frames < 1:
            raise ValueError(f"n_frames must be >= 1, got {self.n_frames}")
        if not self.frame_interval_s > 0:
            raise ValueError(f"frame_interval_s must be > 0, got {self.frame_interval_s}")
        if self.case not in CASES:
            raise ValueError(f"case must be one of {CASES}, got {self.case}")
        if self.speed not in SPEED_CLASSES:
            raise ValueError(f"speed must be one of {SPEED_CLASSES}, got {self.speed!r}")

    @property
    def duration_s(self) -> float:
        """Time of the last frame."""
        return (self.n_frames - 1) * self.frame_interval_s
