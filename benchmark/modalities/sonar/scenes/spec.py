"""Definitions of simulated multibeam sonar sequences, as plain data.

A sonar sequence follows the data of Tena Ruiz et al. (seeds/003, section
4): a multibeam echo sounder on a vehicle that runs along a pipe, one swath
across the track per ping.  The sequence is a pure function of a
:class:`SonarSceneSpec`, seed included.  Like the camera and stereo specs
(:mod:`benchmark.scenes.spec`, :mod:`benchmark.modalities.stereo.scenes.spec`), it is a
tree of frozen dataclasses built from a plain mapping by
:meth:`SonarSceneSpec.from_dict`, so suites are TOML files; an unknown key or
a bad value is a :class:`benchmark.errors.DataError` naming where it was
found.

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
from dataclasses import dataclass, field

import numpy as np

from benchmark.modalities.sonar.model import SonarCalibration
from benchmark.scenes.signal import Signal
from benchmark.scenes.spec import TableSpec

MIN_RANGE_RESOLUTION_M = 1e-6
"""The finest range step a sonar may round to, m; finer steps overflow ``range / step``."""


def _finite(*values: float) -> bool:
    return all(math.isfinite(v) for v in values)


@dataclass(frozen=True)
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

    model: str = ""
    n_beams: int = 240
    swath_deg: float = 120.0
    beam_width_deg: float = 0.5
    range_sigma_m: float = 0.01
    outer_sigma_factor: float = 1.0
    range_resolution_m: float = 0.0
    max_range_m: float = 40.0
    missing_nadir: float = 0.0
    missing_outer: float = 0.0
    outlier_rate: float = 0.0
    outlier_scale_m: float = 1.0

    def __post_init__(self) -> None:
        if self.n_beams < 3:
            raise ValueError(f"n_beams must be >= 3, got {self.n_beams}")
        if not 0 < self.swath_deg < 175:
            raise ValueError(f"swath_deg must be in (0, 175), got {self.swath_deg}")
        if not _finite(self.beam_width_deg, self.range_sigma_m, self.range_resolution_m, self.max_range_m):
            raise ValueError("beam_width_deg, range_sigma_m, range_resolution_m and max_range_m must be finite")
        if min(self.beam_width_deg, self.range_sigma_m, self.range_resolution_m) < 0 or not self.max_range_m > 0:
            raise ValueError("need beam_width_deg, range_sigma_m, range_resolution_m >= 0 and max_range_m > 0")
        if 0 < self.range_resolution_m < MIN_RANGE_RESOLUTION_M:
            raise ValueError(
                f"range_resolution_m must be 0 (no rounding) or at least {MIN_RANGE_RESOLUTION_M:g} m, "
                f"got {self.range_resolution_m:g}"
            )
        if not (math.isfinite(self.outer_sigma_factor) and self.outer_sigma_factor >= 1):
            raise ValueError(f"outer_sigma_factor must be >= 1, got {self.outer_sigma_factor}")
        for name in ("missing_nadir", "missing_outer", "outlier_rate"):
            if not 0 <= getattr(self, name) < 1:
                raise ValueError(f"{name} must be in [0, 1), got {getattr(self, name)}")
        if not self.outlier_scale_m > 0:
            raise ValueError(f"outlier_scale_m must be > 0, got {self.outlier_scale_m}")

    @property
    def half_swath(self) -> float:
        """Half the opening, rad."""
        return math.radians(self.swath_deg) / 2.0


@dataclass(frozen=True)
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
    speed_mps: float = 1.5

    def __post_init__(self) -> None:
        if not (math.isfinite(self.speed_mps) and self.speed_mps > 0):
            raise ValueError(f"speed_mps must be > 0, got {self.speed_mps}")


@dataclass(frozen=True)
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

    std_m: float = 0.0
    length_m: float = 1.0

    def __post_init__(self) -> None:
        if not (_finite(self.std_m, self.length_m) and self.std_m >= 0 and self.length_m > 0):
            raise ValueError("need std_m >= 0 and length_m > 0")


@dataclass(frozen=True)
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

    height_m: float = 0.0
    wavelength_m: float = 1.0
    crest_deg: float = 0.0

    def __post_init__(self) -> None:
        if not (_finite(self.height_m, self.wavelength_m, self.crest_deg) and self.height_m >= 0):
            raise ValueError("need finite values and height_m >= 0")
        if not self.wavelength_m > 0:
            raise ValueError(f"wavelength_m must be > 0, got {self.wavelength_m}")


@dataclass(frozen=True)
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

    per_100m2: float = 0.0
    diameter_m: tuple[float, float] = (0.3, 1.0)
    height_ratio: tuple[float, float] = (0.3, 0.6)
    elongation: tuple[float, float] = (0.7, 1.4)
    clearance_m: float = 0.3
    start_frame: float = -math.inf
    stop_frame: float = math.inf

    def __post_init__(self) -> None:
        pairs = (self.diameter_m, self.height_ratio, self.elongation)
        if not all(_finite(*pair) and 0 < pair[0] <= pair[1] for pair in pairs):
            raise ValueError("diameter_m, height_ratio and elongation need 0 < low <= high")
        if not (math.isfinite(self.per_100m2) and self.per_100m2 >= 0 and self.clearance_m >= 0):
            raise ValueError("need per_100m2 >= 0 and clearance_m >= 0")
        if self.stop_frame < self.start_frame:
            raise ValueError("need start_frame <= stop_frame")


@dataclass(frozen=True)
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
    cell_m: float = 0.05
    sand_waves: Ripples = Ripples()

    def __post_init__(self) -> None:
        if not 0.005 <= self.cell_m <= 0.5:
            raise ValueError(f"cell_m must be in [0.005, 0.5], got {self.cell_m}")


@dataclass(frozen=True)
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
    bottom_width_m: float = 1.0
    top_width_m: float = 4.0
    offset_m: float = 0.0
    berm_ratio: float = 0.0
    berm_width_m: float = 1.0

    def __post_init__(self) -> None:
        if not _finite(self.bottom_width_m, self.top_width_m, self.offset_m, self.berm_ratio, self.berm_width_m):
            raise ValueError("trench values must be finite")
        if not 0 <= self.bottom_width_m < self.top_width_m:
            raise ValueError("need 0 <= bottom_width_m < top_width_m")
        if self.berm_ratio < 0 or not self.berm_width_m > 0:
            raise ValueError("need berm_ratio >= 0 and berm_width_m > 0")


@dataclass(frozen=True)
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

    amplitude_m: float = 0.0
    speed_mps: float = 0.0
    phase_deg: float = 0.0

    def __post_init__(self) -> None:
        if not (_finite(self.amplitude_m, self.speed_mps, self.phase_deg) and self.amplitude_m >= 0):
            raise ValueError("drift values must be finite and amplitude_m >= 0")
        if self.speed_mps < 0:
            raise ValueError(f"speed_mps must be >= 0, got {self.speed_mps}")

    def offsets(self, n_frames: int, frame_interval_s: float) -> np.ndarray:
        """The drift's across-track offset at pings ``0 .. n_frames - 1``, m."""
        if self.amplitude_m == 0 or self.speed_mps == 0:
            return np.zeros(n_frames)
        t = np.arange(n_frames) * frame_interval_s
        return self.amplitude_m * np.sin(self.speed_mps * t / self.amplitude_m + math.radians(self.phase_deg))


def _check_diameter(diameter_m: float) -> None:
    """ValueError unless a pipe diameter is between 5 cm and 5 m."""
    if not (math.isfinite(diameter_m) and 0.05 <= diameter_m <= 5):
        raise ValueError(f"diameter_m must be in [0.05, 5], got {diameter_m}")


@dataclass(frozen=True)
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

    diameter_m: float = 0.5
    across_m: Signal = Signal()
    burial: Signal = Signal()
    trench: TrenchSpec = TrenchSpec()
    bend_radius_m: float = 0.0
    drift: Drift = Drift()

    def __post_init__(self) -> None:
        _check_diameter(self.diameter_m)
        if not (math.isfinite(self.bend_radius_m) and self.bend_radius_m >= 0):
            raise ValueError(f"bend_radius_m must be finite and >= 0, got {self.bend_radius_m}")


@dataclass(frozen=True)
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

    diameter_m: float = 0.5
    offset_m: Signal = Signal(mean=5.0)
    burial: Signal = Signal()
    trench: TrenchSpec = TrenchSpec()

    def __post_init__(self) -> None:
        _check_diameter(self.diameter_m)


@dataclass(frozen=True)
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

    name: str
    n_frames: int
    seed: int = 0
    description: str = ""
    frame_interval_s: float = 0.25
    sonar: SonarSpec = field(default_factory=SonarSpec)
    vehicle: VehicleSpec = field(default_factory=VehicleSpec)
    seabed: SeabedSpec = field(default_factory=SeabedSpec)
    pipe: PipeSpec = field(default_factory=PipeSpec)
    second_pipe: SecondPipeSpec | None = None

    def __post_init__(self) -> None:
        if not self.name:
            raise ValueError("name must not be empty")
        if self.n_frames < 1:
            raise ValueError(f"n_frames must be >= 1, got {self.n_frames}")
        if not (math.isfinite(self.frame_interval_s) and self.frame_interval_s > 0):
            raise ValueError(f"frame_interval_s must be > 0, got {self.frame_interval_s}")

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
