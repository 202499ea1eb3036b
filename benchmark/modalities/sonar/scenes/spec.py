"""Definitions of simulated multibeam sonar sequences, as plain data.

A sonar sequence follows the data of Tena Ruiz et al. (seeds/003, section
4): a multibeam echo sounder on a vehicle that runs along a pipe, one swath
across the track per ping.  The sequence is a pure function of a
:class:`SonarSceneSpec`, seed included.  Like the camera and stereo specs
(:mod:`benchmark.scenes.spec`, :mod:`benchmark.modalities.stereo.scenes.spec`), it is a
tree of frozen dataclasses built from a plain mapping by
:meth:`SonarSceneSpec.from_dict`, so suites are TOML files; its fields
declare their ranges (:mod:`benchmark.scenes.spec`), and an unknown key or a
bad value is a :class:`benchmark.errors.DataError` naming the file, the key
and the rule.

The tree:

* :class:`SonarSpec`: the echo sounder (beams, opening, beam width) and its
  faults (range noise and missing beams, both growing with the incidence
  angle, so towards the outer beams; outlier spikes);
* :class:`VehicleSpec`: altitude and roll over time, forward speed;
* :class:`SeabedSpec`: across-track slope, :class:`Roughness` (a 2-D field
  correlated between pings), :class:`Ripples` and sand waves (the same
  parallel crests, metres high and tens of metres apart),
  :class:`BoulderField`;
* :class:`PipeSpec`: the tracked pipe, its across-track position (the
  meander, plus an optional smooth :class:`Drift` across the swath), its
  burial, a :class:`TrenchSpec` along it, and the stiffness that makes it
  span the troughs of sand waves instead of following them;
* :class:`SecondPipeSpec`: an optional second pipe, placed relative to the
  first (the pipe-laying scenario of seeds/003, abstract and section 5).

Everything that varies along the track is a
:class:`benchmark.scenes.signal.Signal` of the ping index.  Lengths are in m,
angles in degrees (converted to radians where the scene is built), times in
pings (frames) unless a name says otherwise.
"""

from __future__ import annotations

import math
from dataclasses import field
from typing import Annotated

import numpy as np
import pydantic
from annotated_types import Ge, Gt, Interval

from benchmark.modalities.sonar.model import SonarCalibration
from benchmark.parameters import require_order
from benchmark.scenes.signal import Signal
from benchmark.scenes.spec import (
    SPEC_CONFIG,
    Finite,
    Integer,
    Name,
    NonNegative,
    Number,
    Positive,
    Probability,
    TableSpec,
    Text,
    ordered,
)

MIN_RANGE_RESOLUTION_M = 1e-6
"""The finest range step a sonar may round to, m; finer steps overflow ``range / step``."""


def _no_finer_than_the_finest_step(step: float) -> float:
    """A range resolution of 0 (no rounding) or at least :data:`MIN_RANGE_RESOLUTION_M`, else ``ValueError``."""
    if 0 < step < MIN_RANGE_RESOLUTION_M:
        raise ValueError(f"must be 0 (no rounding) or at least {MIN_RANGE_RESOLUTION_M:g} m, got {step:g}")
    return step


RangeResolution = Annotated[NonNegative, pydantic.AfterValidator(_no_finer_than_the_finest_step)]
"""A range step in m: 0 for none, else at least :data:`MIN_RANGE_RESOLUTION_M`."""

Diameter = Annotated[Finite, Interval(ge=0.05, le=5)]
"""A pipe's outer diameter, between 5 cm and 5 m."""

PositiveRange = Annotated[tuple[Positive, Positive], pydantic.AfterValidator(ordered)]
"""A range ``(low, high)`` with ``0 < low <= high``."""


@pydantic.dataclasses.dataclass(frozen=True, config=SPEC_CONFIG)
class SonarSpec:
    """The multibeam echo sounder and its errors.

    Attributes
    ----------
    model : str
        What the sonar is modelled on, for the sequence's description.
    n_beams : int
        Beams per ping, equiangular over the opening.
    swath_deg : float
        Full across-track opening of the fan.
    beam_width_deg : float
        Across-track width of one beam (-3 dB); its return mixes the ranges
        inside that width.  0 gives one ray per beam.
    range_sigma_m : float
        Standard deviation of the range error of a beam that meets the
        surface head-on (below the sonar, on a level seabed).
    outer_sigma_factor : float
        The range error of a beam that meets the surface at the incidence of
        the outermost beams on a level seabed (half the opening), as a
        multiple of ``range_sigma_m``; in between it grows with
        ``sin^2`` of the incidence angle
        (:func:`benchmark.modalities.sonar.scenes.swath.degrade_ranges`).
    range_resolution_m : float
        Step the ranges are quantised to; 0 for none, else at least
        :data:`MIN_RANGE_RESOLUTION_M`.
    max_range_m : float
        Range gate: nothing farther returns.
    missing_nadir, missing_outer : float
        Probability that a beam meeting the surface head-on, or at the
        incidence of the outermost beams on a level seabed, has no return;
        in between it grows with the fourth power of the incidence angle.
    outlier_rate : float
        Probability that a beam's range is a spike (a return from the water
        column or a multipath).
    outlier_scale_m : float
        Scale of the spikes' range error (Laplace distributed).
    """

    model: Text = ""
    n_beams: Annotated[Integer, Ge(3)] = 240
    swath_deg: Annotated[Number, Interval(gt=0, lt=175)] = 120.0
    beam_width_deg: NonNegative = 0.5
    range_sigma_m: NonNegative = 0.01
    outer_sigma_factor: Annotated[Finite, Ge(1)] = 1.0
    range_resolution_m: RangeResolution = 0.0
    max_range_m: Positive = 40.0
    missing_nadir: Probability = 0.0
    missing_outer: Probability = 0.0
    outlier_rate: Probability = 0.0
    outlier_scale_m: Annotated[Number, Gt(0)] = 1.0

    @property
    def half_swath(self) -> float:
        """Half the opening, rad."""
        return math.radians(self.swath_deg) / 2.0


@pydantic.dataclasses.dataclass(frozen=True, config=SPEC_CONFIG)
class VehicleSpec:
    """The vehicle that carries the sonar.

    Attributes
    ----------
    altitude_m : Signal
        Height of the transducer above the mean seabed below it.
    roll_deg : Signal
        Roll, port down positive (it adds to the beam angles): it turns the fan, whose returns are
        given in the level frame.
    speed_mps : float
        Forward speed; the pings are ``speed_mps * frame_interval_s`` apart.
    """

    altitude_m: Signal = Signal(mean=10.0)
    roll_deg: Signal = Signal()
    speed_mps: Positive = 1.5


@pydantic.dataclasses.dataclass(frozen=True, config=SPEC_CONFIG)
class Roughness:
    """One scale of seabed roughness: a smooth random field over both axes.

    Attributes
    ----------
    std_m : float
        Standard deviation of the height.
    length_m : float
        Standard deviation of the Gaussian that smooths white noise into
        the field, the same along and across the track.
    """

    std_m: NonNegative = 0.0
    length_m: Positive = 1.0


@pydantic.dataclasses.dataclass(frozen=True, config=SPEC_CONFIG)
class Ripples:
    """Sand ripples: parallel crests.

    Attributes
    ----------
    height_m : float
        Crest-to-trough height.
    wavelength_m : float
        Crest spacing.
    crest_deg : float
        Angle between the crests and the track (0: crests run along the
        track, parallel to the pipe).
    """

    height_m: NonNegative = 0.0
    wavelength_m: Positive = 1.0
    crest_deg: Finite = 0.0


@pydantic.dataclasses.dataclass(frozen=True, config=SPEC_CONFIG)
class BoulderField:
    """Boulders scattered over a stretch of the track.

    Each boulder is half an ellipsoid sitting on the seabed, with a
    diameter drawn log-uniformly from ``diameter_m``, a height of
    ``height_ratio`` times its diameter and an along-track length of
    ``elongation`` times its diameter (both drawn uniformly).

    Attributes
    ----------
    per_100m2 : float
        Mean number of boulders per 100 m^2 of seabed.
    diameter_m : tuple of float
        Smallest and largest across-track diameter.
    height_ratio : tuple of float
        Range of height / diameter.
    elongation : tuple of float
        Range of along-track length / diameter.
    clearance_m : float
        No boulder comes closer than this to a pipe.
    start_frame, stop_frame : float
        The stretch of pings the field covers.
    """

    per_100m2: NonNegative = 0.0
    diameter_m: PositiveRange = (0.3, 1.0)
    height_ratio: PositiveRange = (0.3, 0.6)
    elongation: PositiveRange = (0.7, 1.4)
    clearance_m: Annotated[Number, Ge(0)] = 0.3
    start_frame: Number = -math.inf
    stop_frame: Number = math.inf

    def __post_init__(self) -> None:
        require_order(self, ("start_frame", "stop_frame"))


@pydantic.dataclasses.dataclass(frozen=True, config=SPEC_CONFIG)
class SeabedSpec:
    """The seabed the pipes lie on.

    Attributes
    ----------
    slope_deg : Signal
        Across-track slope, positive when the seabed deepens to starboard.
    roughness : tuple of Roughness
        Scales of random relief, summed.
    ripples : Ripples
    sand_waves : Ripples
        Sand waves: crests 0.5-several metres high and tens of metres apart,
        usually across a pipe laid along the current, so that the pipe
        spans their troughs (:attr:`PipeSpec.bend_radius_m`).  None by
        default.
    boulders : tuple of BoulderField
    cell_m : float
        Across-track spacing of the grid the seabed is sampled on (the
        surface is linear between samples).
    """

    slope_deg: Signal = Signal()
    roughness: tuple[Roughness, ...] = ()
    ripples: Ripples = Ripples()
    boulders: tuple[BoulderField, ...] = ()
    cell_m: Annotated[Number, Interval(ge=0.005, le=0.5)] = 0.05
    sand_waves: Ripples = Ripples()


@pydantic.dataclasses.dataclass(frozen=True, config=SPEC_CONFIG)
class TrenchSpec:
    """A trench along a pipe, with spoil heaps on both sides.

    Its cross-section is a trapezoid centred ``offset_m`` from the pipe's
    axis, and each spoil heap a Gaussian mound beside it.

    Attributes
    ----------
    depth_m : Signal
        Depth of the trench along the track (0, or below 0, for none):
        steps in and out of a trenched stretch are its ``events``.
    bottom_width_m, top_width_m : float
        Width of its floor and between the tops of its walls.
    offset_m : float
        Across-track distance of its centre from the pipe's axis.
    berm_ratio : float
        Height of each spoil heap as a share of the trench's depth.
    berm_width_m : float
        Width (standard deviation) of a spoil heap, whose crest is that far
        beyond the top of the wall.
    """

    depth_m: Signal = Signal()
    bottom_width_m: NonNegative = 1.0
    top_width_m: Finite = 4.0
    offset_m: Finite = 0.0
    berm_ratio: NonNegative = 0.0
    berm_width_m: Positive = 1.0

    def __post_init__(self) -> None:
        if not self.bottom_width_m < self.top_width_m:
            raise ValueError(
                f"bottom_width_m must be below top_width_m, got {self.bottom_width_m} >= {self.top_width_m}"
            )


@pydantic.dataclasses.dataclass(frozen=True, config=SPEC_CONFIG)
class Drift:
    """A smooth cross-track drift: the pipe swings across the swath and back at up to a given speed.

    The pipe's across-track position gains ``amplitude_m sin(speed_mps t /
    amplitude_m + phase)`` at time ``t`` (s): a sinusoid whose fastest
    across-track speed is ``speed_mps``, as when a vehicle weaves about the
    pipe it follows, faster than a tracker's random walk may allow for.

    Attributes
    ----------
    amplitude_m : float
        Largest excursion from the mean position, m; 0 for none.
    speed_mps : float
        Fastest across-track speed, m/s; 0 for none.
    phase_deg : float
        Phase at the first ping.
    """

    amplitude_m: NonNegative = 0.0
    speed_mps: NonNegative = 0.0
    phase_deg: Finite = 0.0

    def offsets(self, n_frames: int, frame_interval_s: float) -> np.ndarray:
        """The drift's across-track offset at pings ``0 .. n_frames - 1``, m."""
        if self.amplitude_m == 0 or self.speed_mps == 0:
            return np.zeros(n_frames)
        t = np.arange(n_frames) * frame_interval_s
        return self.amplitude_m * np.sin(self.speed_mps * t / self.amplitude_m + math.radians(self.phase_deg))


@pydantic.dataclasses.dataclass(frozen=True, config=SPEC_CONFIG)
class PipeSpec:
    """The tracked pipe.

    Attributes
    ----------
    diameter_m : float
        Outer diameter, coating included.
    across_m : Signal
        Across-track position of its axis from the sonar's nadir, starboard
        positive: the vehicle's cross-track error plus the pipe's own
        curvature.
    burial : Signal
        Share of the diameter below the seabed it lies on, clipped to
        [0, 1]: 0 proud, 1 covered.
    trench : TrenchSpec
    drift : Drift
        A smooth weave added to ``across_m``; none by default.
    bend_radius_m : float
        Smallest radius the pipe bends to along the track under its own
        weight, m: over a trough narrower than that allows, it hangs
        between the crests instead of resting on the bottom (a free span,
        :func:`benchmark.modalities.sonar.scenes.pipes.span_depth`).  0 (the
        default): the pipe rests on the seabed in every ping.
    """

    diameter_m: Diameter = 0.5
    across_m: Signal = Signal()
    burial: Signal = Signal()
    trench: TrenchSpec = TrenchSpec()
    bend_radius_m: NonNegative = 0.0
    drift: Drift = Drift()


@pydantic.dataclasses.dataclass(frozen=True, config=SPEC_CONFIG)
class SecondPipeSpec:
    """A second pipe near the first, never the one the truth follows.

    Attributes
    ----------
    diameter_m : float
    offset_m : Signal
        Across-track distance of its axis from the first pipe's axis,
        starboard positive.
    burial : Signal
    trench : TrenchSpec
    """

    diameter_m: Diameter = 0.5
    offset_m: Signal = Signal(mean=5.0)
    burial: Signal = Signal()
    trench: TrenchSpec = TrenchSpec()


@pydantic.dataclasses.dataclass(frozen=True, config=SPEC_CONFIG)
class SonarSceneSpec(TableSpec):
    """Everything that defines one simulated sonar sequence (seeds/003, section 4).

    Attributes
    ----------
    name : str
        Sequence name in results, e.g. ``"sonar/autotracker"``.
    n_frames : int
        Number of pings.
    seed : int
        Seed of every random choice (relief, boulders, signals' noise,
        range noise, missing beams, spikes).
    description : str
        What the sequence is meant to test.
    frame_interval_s : float
        Time between pings.
    sonar : SonarSpec
    vehicle : VehicleSpec
    seabed : SeabedSpec
    pipe : PipeSpec
    second_pipe : SecondPipeSpec or None
    """

    name: Name
    n_frames: Annotated[Integer, Ge(1)]
    seed: Integer = 0
    description: Text = ""
    frame_interval_s: Positive = 0.25
    sonar: SonarSpec = field(default_factory=SonarSpec)
    vehicle: VehicleSpec = field(default_factory=VehicleSpec)
    seabed: SeabedSpec = field(default_factory=SeabedSpec)
    pipe: PipeSpec = field(default_factory=PipeSpec)
    second_pipe: SecondPipeSpec | None = None

    @property
    def ping_spacing_m(self) -> float:
        """Along-track distance between consecutive pings."""
        return self.vehicle.speed_mps * self.frame_interval_s

    def calibration(self) -> SonarCalibration:
        """The sonar and the tracked pipe as a :class:`benchmark.modalities.sonar.model.SonarCalibration`."""
        return SonarCalibration(
            n_beams=self.sonar.n_beams,
            swath_angle=math.radians(self.sonar.swath_deg),
            range_sigma_m=self.sonar.range_sigma_m,
            pipe_diameter_m=self.pipe.diameter_m,
            beam_width=math.radians(self.sonar.beam_width_deg),
        )
