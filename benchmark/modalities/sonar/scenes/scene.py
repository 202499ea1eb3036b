"""A simulated multibeam sonar sequence: swaths across a pipe on the seabed (seeds/003, section 4).

:class:`SonarScene` turns a :class:`~benchmark.modalities.sonar.scenes.spec.SonarSceneSpec`
into pings, the kind of data Tena Ruiz et al. detect and track pipes in: a
vehicle runs along a pipe at a few metres' to a few tens of metres'
altitude, and its multibeam echo sounder measures one swath across the
track per ping.  The scene is built once, on first use:

* the vehicle's altitude and roll, the seabed's slope, the pipes'
  across-track positions (the meander: the vehicle's cross-track error plus
  the pipe's curvature), their burial and their trenches are
  :class:`benchmark.scenes.signal.Signal` s of the ping index;
* the seabed is a grid of depths over (ping, across-track position)
  (:mod:`~benchmark.modalities.sonar.scenes.seabed`), the pipes rest on it
  (:mod:`~benchmark.modalities.sonar.scenes.pipes`) and boulders are scattered off the
  pipes.

Each ping is then cast on its own (:mod:`~benchmark.modalities.sonar.scenes.swath`):
equiangular beams turned by the roll, first hits on the seabed or a pipe,
the beam pattern, range noise and gaps that grow as the echo weakens with
the incidence angle, spikes.

Randomness comes from one seed: a :class:`numpy.random.SeedSequence` of
``spec.seed`` spawns independent streams for each signal, each roughness
scale and boulder field, and for the range noise, the gaps and the spikes
of each ping, so changing one leaves the others alone, the same spec gives
bit-identical pings, and any ping can be rendered on its own.  The object
keeps only its spec; the grid (a few MB) is dropped when the scene is
pickled (:class:`~benchmark.scenes.scene.SimulatedScene`).

Each frame carries

* ``observation``: a :class:`benchmark.modalities.sonar.model.Swath`;
* ``truth``: :class:`benchmark.modalities.sonar.model.SonarTruth` of the first pipe, even
  where a second pipe is nearer the sonar;
* ``navigation``: None.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from collections.abc import Mapping
from typing import Any, NamedTuple

import numpy as np

from benchmark.errors import DataError
from benchmark.modalities.sonar.model import SonarTruth, Swath, beam_footprint
from benchmark.modalities.sonar.scenes.pipes import PipeTrack, pipe_track
from benchmark.modalities.sonar.scenes.seabed import (
    across_grid,
    boulder_caps,
    ripple_relief,
    roughness_relief,
    scatter_boulders,
    trench_relief,
)
from benchmark.modalities.sonar.scenes.spec import SonarSceneSpec, TrenchSpec
from benchmark.modalities.sonar.scenes.swath import Ellipse, beam_angles, beam_ranges, degrade_ranges, swath_from_ranges
from benchmark.model import SequenceInfo
from benchmark.scenes.scene import SimulatedScene
from benchmark.scenes.signal import Signal, evaluate_signal

MIN_ALTITUDE_M = 1.0
"""The transducer must stay at least this high above the mean seabed."""

MAX_TILT_DEG = 30.0
"""Largest roll and across-track slope a sequence may have."""

# Keys of the independent random streams spawned from the seed.
(
    _ALTITUDE,
    _ROLL,
    _SLOPE,
    _ACROSS,
    _BURIAL,
    _TRENCH,
    _SECOND_OFFSET,
    _SECOND_BURIAL,
    _SECOND_TRENCH,
    _ROUGHNESS,
    _BOULDERS,
    _RANGE_NOISE,
    _MISSING,
    _OUTLIERS,
) = range(14)


class _PipeLayout(NamedTuple):
    """A pipe's signals at every ping, before it is laid on the seabed."""

    radius_m: float
    across_m: np.ndarray
    burial: np.ndarray
    trench: TrenchSpec
    trench_depth_m: np.ndarray
    bend_radius_m: float = 0.0


@dataclass
class _Cache:
    """What a scene computes once and keeps while it lives (never pickled)."""

    across: np.ndarray
    depth: np.ndarray
    altitude: np.ndarray
    roll: np.ndarray
    pipes: tuple[PipeTrack, ...]
    sonar_axes: np.ndarray


class SonarScene(SimulatedScene[SonarSceneSpec, _Cache]):
    """A simulated multibeam sonar sequence along a pipe (seeds/003, section 4).

    Parameters
    ----------
    spec : SonarSceneSpec
        The definition, seed included.

    Examples
    --------
    >>> scene = SonarScene.from_dict({"name": "sonar/demo", "n_frames": 2})
    >>> frame = scene.frame(1)
    >>> frame.observation.across_m.shape, round(frame.truth.across_m, 2)
    ((240,), 0.0)
    """

    spec_type = SonarSceneSpec

    @property
    def info(self) -> SequenceInfo:
        """Name, length, ping interval and :class:`SonarCalibration` of the sequence."""
        spec = self._spec
        return SequenceInfo(
            name=spec.name,
            modality="sonar",
            n_frames=spec.n_frames,
            frame_size=None,
            frame_interval_s=spec.frame_interval_s,
            calibration=spec.calibration(),
            extra={
                "description": spec.description,
                "sonar": spec.sonar.model,
                "ping_spacing_m": spec.ping_spacing_m,
                "second_pipe": spec.second_pipe is not None,
                "seed": spec.seed,
                "source": "simulated",
                "conditions": self.drawn_conditions,
            },
        )

    def conditions(self) -> Mapping[str, Any]:
        """What the sequence was drawn under, and what it makes of the tracked pipe.

        Besides the drawn conditions (:attr:`drawn_conditions`), two that
        follow from several drawn values, computed from the signals alone
        (no ping is cast):

        * ``footprint_ratio``: the across-track footprint of one beam at
          nadir at the mean altitude, ``2 h tan(beam_width / 2)``, over
          the pipe's diameter; at 0.5 and above the beams smooth the
          pipe's arc into a bump (seeds/003, section 2: the model is the
          pipe's cross-section, which the sonar sees through its beams);
        * ``pipe_speed_mps``: the fastest across-track speed of the pipe in
          the swath from ping to ping, m/s (its meander, noise and drift
          together).

        Returns
        -------
        Mapping
            Drawn conditions first; a drawn condition of the same name wins.
        """
        spec = self._spec
        altitude = float(np.mean(self._signal(spec.vehicle.altitude_m, _ALTITUDE)))
        footprint = 2.0 * altitude * math.tan(math.radians(spec.sonar.beam_width_deg) / 2.0)
        speed = float(np.max(np.abs(np.diff(self._across())), initial=0.0)) / spec.frame_interval_s
        derived = {"footprint_ratio": footprint / spec.pipe.diameter_m, "pipe_speed_mps": speed}
        drawn = self.drawn_conditions
        return {**drawn, **{name: value for name, value in derived.items() if name not in drawn}}

    def _across(self) -> np.ndarray:
        """The tracked pipe's across-track position at every ping: its signal plus its drift."""
        pipe, spec = self._spec.pipe, self._spec
        across = self._signal(pipe.across_m, _ACROSS)
        if pipe.drift.amplitude_m > 0 and pipe.drift.speed_mps > 0:
            across = across + pipe.drift.offsets(spec.n_frames, spec.frame_interval_s)
        return across

    def _signal(self, signal: Signal, key: int) -> np.ndarray:
        return evaluate_signal(signal, self._spec.n_frames, self._stream(key))

    def _layout(self) -> list[_PipeLayout]:
        """The pipes' signals, the tracked pipe first."""
        spec = self._spec
        first = spec.pipe
        across = self._across()
        layout = [
            _PipeLayout(
                first.diameter_m / 2.0,
                across,
                self._signal(first.burial, _BURIAL),
                first.trench,
                self._signal(first.trench.depth_m, _TRENCH),
                first.bend_radius_m,
            )
        ]
        second = spec.second_pipe
        if second is not None:
            layout.append(
                _PipeLayout(
                    second.diameter_m / 2.0,
                    across + self._signal(second.offset_m, _SECOND_OFFSET),
                    self._signal(second.burial, _SECOND_BURIAL),
                    second.trench,
                    self._signal(second.trench.depth_m, _SECOND_TRENCH),
                )
            )
        return layout

    def _build_cache(self) -> _Cache:
        spec = self._spec
        n, spacing, sonar = spec.n_frames, spec.ping_spacing_m, spec.sonar
        along = np.arange(n) * spacing
        altitude = self._signal(spec.vehicle.altitude_m, _ALTITUDE)
        roll_deg = self._signal(spec.vehicle.roll_deg, _ROLL)
        slope_deg = self._signal(spec.seabed.slope_deg, _SLOPE)
        self._check_range("altitude", altitude, MIN_ALTITUDE_M, math.inf, "m")
        self._check_range("roll", roll_deg, -MAX_TILT_DEG, MAX_TILT_DEG, "deg")
        self._check_range("seabed slope", slope_deg, -MAX_TILT_DEG, MAX_TILT_DEG, "deg")
        roll = np.radians(roll_deg)

        reach = min(sonar.half_swath + float(np.max(np.abs(roll))) + math.radians(sonar.beam_width_deg), 1.55)
        across = across_grid(sonar.max_range_m * math.sin(reach) + 1.0, spec.seabed.cell_m)
        base = altitude[:, None] + np.tan(np.radians(slope_deg))[:, None] * across[None, :]
        for i, roughness in enumerate(spec.seabed.roughness):
            base += roughness_relief(self._stream(_ROUGHNESS, i), roughness, n, spacing, across)
        base += ripple_relief(spec.seabed.ripples, along, across)
        if spec.seabed.sand_waves.height_m > 0:
            base += ripple_relief(spec.seabed.sand_waves, along, across)

        layout = self._layout()
        for number, pipe in enumerate(layout, start=1):
            reach_m = float(across[-1]) - 1.0 - 2.0 * pipe.radius_m
            self._check_range(f"pipe {number} across-track position", pipe.across_m, -reach_m, reach_m, "m")
            base += trench_relief(pipe.trench, pipe.trench_depth_m, pipe.across_m, across)
        pipes = tuple(
            pipe_track(p.across_m, p.burial, p.radius_m, spacing, base, across, p.bend_radius_m) for p in layout
        )
        for number, pipe in enumerate(pipes, start=1):
            top = pipe.axis_depth_m - pipe.radius_m
            self._check_range(f"pipe {number} top depth below the sonar", top, 0.5, math.inf, "m")

        caps = np.zeros_like(base)
        centres = np.array([p.across_m for p in pipes])
        widths = np.array([p.half_width_m for p in pipes])
        for i, field in enumerate(spec.seabed.boulders):
            boulders = scatter_boulders(self._stream(_BOULDERS, i), field, along, across, centres, widths)
            boulder_caps(boulders, along, across, caps)

        return _Cache(
            across=across,
            depth=base - caps,
            altitude=altitude,
            roll=roll,
            pipes=pipes,
            sonar_axes=beam_angles(sonar.n_beams, math.radians(sonar.swath_deg)),
        )

    def _check_range(self, label: str, values: np.ndarray, low: float, high: float, unit: str) -> None:
        """DataError naming the sequence and the first ping where ``values`` leaves ``[low, high]``."""
        bad = np.flatnonzero(~((values >= low) & (values <= high)))
        if bad.size:
            k = int(bad[0])
            raise DataError(
                f"{self._spec.name}: {label} at frame {k} is {values[k]:.3f} {unit}, outside [{low:.3f}, {high:.3f}]"
            )

    def pipes(self) -> tuple[PipeTrack, ...]:
        """The pipes at every ping: the tracked one first, then the second pipe if any."""
        return self._state().pipes

    def altitudes(self) -> np.ndarray:
        """The transducer's height above the mean seabed at every ping, m."""
        return self._state().altitude.copy()

    def seabed(self) -> tuple[np.ndarray, np.ndarray]:
        """The seabed without the pipes: grid columns ``(n_cols,)`` and depths ``(n_frames, n_cols)``."""
        state = self._state()
        return state.across, state.depth

    def beam_axes(self, index: int) -> np.ndarray:
        """Beam angles from the vertical in the level frame at ping ``index`` (the roll included), rad."""
        state = self._state()
        return state.sonar_axes + state.roll[self._check(index)]

    def true_ranges(self, index: int) -> tuple[np.ndarray, np.ndarray]:
        """Ranges the beams of ping ``index`` would report without noise, spikes or gaps.

        Returns
        -------
        ranges : numpy.ndarray
            One per beam, ``nan`` where a beam meets nothing within the
            range gate.
        incidence : numpy.ndarray
            Incidence angle of each beam on the surface it meets, rad.
        """
        k = self._check(index)
        state, sonar = self._state(), self._spec.sonar
        ellipses = [
            Ellipse(float(p.across_m[k]), float(p.axis_depth_m[k]), float(p.half_width_m[k]), p.radius_m)
            for p in state.pipes
            if p.visible[k]
        ]
        return beam_ranges(
            state.across,
            state.depth[k],
            self.beam_axes(k),
            ellipses,
            math.radians(sonar.beam_width_deg),
            sonar.max_range_m,
        )

    def observation(self, index: int) -> Swath:
        """The swath of ping ``index``: returns with noise, spikes and gaps."""
        k = self._check(index)
        ranges, incidence = self.true_ranges(k)
        ranges = degrade_ranges(
            ranges,
            incidence,
            self._spec.sonar,
            self._stream(_RANGE_NOISE, k),
            self._stream(_MISSING, k),
            self._stream(_OUTLIERS, k),
        )
        return swath_from_ranges(ranges, self.beam_axes(k))

    def truth(self, index: int) -> SonarTruth:
        """The first pipe at ping ``index``: axis position and depth, burial, beam spacing at its top."""
        k = self._check(index)
        pipe = self._state().pipes[0]
        across, depth = float(pipe.across_m[k]), float(pipe.axis_depth_m[k])
        resolution = float(beam_footprint(across, depth - pipe.radius_m, self._spec.calibration().beam_spacing))
        return SonarTruth(across_m=across, depth_m=depth, burial=float(pipe.burial[k]), resolution_m=resolution)

    def navigation(self, index: int) -> None:
        """Sonar frames carry no navigation data."""
        self._check(index)
        return None
