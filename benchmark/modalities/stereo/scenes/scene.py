"""A simulated stereo sequence: a chase boat measuring a target boat (seeds/002, section 3).

:class:`StereoScene` turns a :class:`~benchmark.modalities.stereo.scenes.spec.StereoSceneSpec`
into frames, the way the paper simulates its three cases: the trajectories
of CH and TG (:mod:`~benchmark.modalities.stereo.scenes.motion`) give the true relative
position of TG; it is projected into both images, perturbed with pixel noise
of variance ``Q_f`` (eq. 19), triangulated again by eq. (15)
(:mod:`~benchmark.modalities.stereo.scenes.sensors`), and CH's GPS position and
heading get their own noise.  The measurement is taken from CH's true pose;
only the navigation data a tracker reads is noisy.

Randomness comes from one seed: a :class:`numpy.random.SeedSequence` of
``spec.seed`` spawns independent streams for the GPS error, the compass
error, the pixel noise and the dropouts, so changing one leaves the others
alone and the same spec gives bit-identical frames.  The trajectories are
deterministic.

The object keeps only its spec; the per-frame arrays (a few kB) are built
on first use and dropped when the scene is pickled
(:class:`~benchmark.scenes.scene.SimulatedScene`).

Each frame carries

* ``observation``: a :class:`benchmark.modalities.stereo.model.StereoMeasurement`, or None
  when the front end lost the target;
* ``truth``: :class:`benchmark.modalities.stereo.model.StereoTruth`, TG's true position and
  velocity (so its speed and heading) and CH's true pose;
* ``navigation``: :class:`benchmark.modalities.stereo.model.ChaseNavigation`, CH's GPS
  position and compass heading.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from benchmark.errors import DataError
from benchmark.modalities.stereo.model import ChaseNavigation, StereoMeasurement, StereoTruth, TargetEstimate
from benchmark.modalities.stereo.scenes.motion import BoatTrack, RelativeGeometry, boat_track, relative_geometry
from benchmark.modalities.stereo.scenes.sensors import (
    Loss,
    MeasurementArrays,
    burst_dropouts,
    correlated_noise,
    stereo_measurements,
)
from benchmark.modalities.stereo.scenes.spec import StereoSceneSpec
from benchmark.model import SequenceInfo
from benchmark.scenes.scene import SimulatedScene

MIN_SEPARATION_M = 2.0
"""The boats must stay at least this far apart."""

# Indices of the independent random streams spawned from the seed.
_GPS, _COMPASS, _PIXELS, _DROPOUTS = range(4)


@dataclass
class _Cache:
    """What a scene computes once and keeps while it lives (never pickled)."""

    chase: BoatTrack
    target: BoatTrack
    geometry: RelativeGeometry
    measurements: MeasurementArrays
    gps_m: np.ndarray
    compass: np.ndarray


class StereoScene(SimulatedScene[StereoSceneSpec, _Cache]):
    """A simulated chase-boat stereo sequence (seeds/002, section 3).

    Parameters
    ----------
    spec : StereoSceneSpec
        The definition, seed included.

    Examples
    --------
    >>> scene = StereoScene.from_dict({"name": "stereo/demo", "n_frames": 3})
    >>> [round(frame.truth.range_m, 1) for frame in scene]
    [8.0, 8.0, 8.0]
    """

    spec_type = StereoSceneSpec

    @property
    def info(self) -> SequenceInfo:
        """Name, length, frame interval and :class:`StereoCalibration` of the sequence."""
        spec = self._spec
        return SequenceInfo(
            name=spec.name,
            modality="stereo",
            n_frames=spec.n_frames,
            frame_interval_s=spec.frame_interval_s,
            calibration=spec.camera.calibration(),
            extra={
                "description": spec.description,
                "case": spec.case,
                "speed": spec.speed,
                "seed": spec.seed,
                "source": "simulated",
                "conditions": self.drawn_conditions,
            },
        )

    def _build_cache(self) -> _Cache:
        spec = self._spec
        n, dt = spec.n_frames, spec.frame_interval_s
        times = np.arange(n) * dt
        chase = boat_track(spec.chase, times)
        target = boat_track(spec.target, times)
        geometry = relative_geometry(chase, target)
        _check_separation(spec, geometry)
        sensors = spec.sensors
        pixel_noise = spec.camera.pixel_noise_px * self._stream(_PIXELS).standard_normal((n, 2))
        dropped = burst_dropouts(self._stream(_DROPOUTS), n, sensors.dropout_rate, sensors.dropout_burst_frames)
        measurements = stereo_measurements(
            geometry.ahead_m,
            geometry.starboard_m,
            spec.camera.calibration(),
            pixel_noise,
            sensors.min_disparity_px,
            dropped,
        )
        gps_error = correlated_noise(self._stream(_GPS), (n, 2), sensors.gps_sigma_m, sensors.gps_correlation_s / dt)
        compass_error = math.radians(sensors.heading_sigma_deg) * self._stream(_COMPASS).standard_normal(n)
        compass = np.mod(chase.heading + compass_error + math.pi, 2.0 * math.pi) - math.pi
        return _Cache(chase, target, geometry, measurements, chase.position_m + gps_error, compass)

    def tracks(self) -> tuple[BoatTrack, BoatTrack]:
        """True tracks ``(chase, target)`` at the frame times."""
        state = self._state()
        return state.chase, state.target

    def relative_geometry(self) -> RelativeGeometry:
        """True position of TG relative to CH (range, bearing, ...) at every frame, without noise."""
        return self._state().geometry

    def losses(self) -> np.ndarray:
        """Why the front end lost the target, per frame (:class:`~benchmark.modalities.stereo.scenes.sensors.Loss`)."""
        return self._state().measurements.loss.copy()

    def truth(self, index: int) -> StereoTruth:
        """Ground truth of frame ``index``: TG's true position and velocity, CH's true pose."""
        k = self._check(index)
        state = self._state()
        target = TargetEstimate(
            position_m=_pair(state.target.position_m[k]), velocity_mps=_pair(state.target.velocity_mps[k])
        )
        return StereoTruth(
            target=target,
            chase_position_m=_pair(state.chase.position_m[k]),
            chase_heading=float(state.chase.heading[k]),
        )

    def navigation(self, index: int) -> ChaseNavigation:
        """CH's GPS position and compass heading at frame ``index``, with their errors."""
        k = self._check(index)
        state = self._state()
        return ChaseNavigation(position_m=_pair(state.gps_m[k]), heading=float(state.compass[k]))

    def measurement(self, index: int) -> StereoMeasurement | None:
        """What the stereo front end reports at frame ``index``; None when it lost the target."""
        k = self._check(index)
        m = self._state().measurements
        if m.loss[k] != Loss.KEPT:
            return None
        return StereoMeasurement(
            left_px=float(m.left_px[k]),
            right_px=float(m.right_px[k]),
            relative_m=(float(m.ahead_m[k]), float(m.starboard_m[k])),
        )

    def observation(self, index: int) -> StereoMeasurement | None:
        """The observation of frame ``index``: :meth:`measurement`."""
        return self.measurement(index)


def _pair(values: np.ndarray) -> tuple[float, float]:
    return float(values[0]), float(values[1])


def _check_separation(spec: StereoSceneSpec, geometry: RelativeGeometry) -> None:
    """The boats must not collide: they stay :data:`MIN_SEPARATION_M` apart."""
    close = np.flatnonzero(geometry.range_m < MIN_SEPARATION_M)
    if close.size:
        k = int(close[0])
        raise DataError(
            f"{spec.name}: at frame {k} the boats are {geometry.range_m[k]:.2f} m apart "
            f"(less than {MIN_SEPARATION_M} m); check their starts and speed profiles"
        )
