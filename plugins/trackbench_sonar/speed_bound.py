"""The speed bounds of the sonar trackers: their own likelihood scan, and Stone Soup's plain particle filter.

Every ping, both trackers resample the swath into a profile, compute the
likelihood scan of eq. (1) (seeds/003, section 2) and find its maximum (the
detector reports it; the filter's rate of injected samples depends on it):
:class:`ScanOnly` does that alone, with the tracker's own detector and
parameters.  The footprint scan is computed where it is read
(:class:`trackbench_sonar.evidence.EvidenceScan`), so the maximum is part
of the work and not a free read.  ``sonar_pf``
is also held against a peer, a plain one-dimensional particle filter of
Stone Soup (``pip install subsea-trackbench[speed]``) with as many particles
and the same random walk (:func:`trackbench_sonar.particle_filter.walk_sigma`),
updated with the ping's true across-track position through a linear
Gaussian measurement of the sonar's resolution, and resampled
systematically: the filtering a general-purpose library does per ping,
without any of the sonar's evidence.  Goals: issue 34's.
"""

from __future__ import annotations

import datetime
import math
from typing import Any

import numpy as np

from benchmark import hookimpl
from benchmark.model import Frame, SequenceInfo
from benchmark.speed.bounds import BoundContext, BoundUnavailable, MsAtMost, SpeedBound, SpeedBounds, TimesFaster
from trackbench_sonar.detection import SwathDetector
from trackbench_sonar.particle_filter import walk_sigma

DATASET = "sonar/autotracker"
"""The sequence timed: the AUV survey of seeds/003, section 4.1, the sonar suite's first."""
PING_S = 1.0
"""Seconds between the Stone Soup filter's timestamps: its random walk's variance is per ping."""


class ScanOnly:
    """The profile, the likelihood scan and its maximum of each ping, with the tracker's own detector."""

    def __init__(self, params: Any, tracker: str) -> None:
        self.params = params
        self.tracker = tracker
        self.detector: SwathDetector | None = None

    def reset(self, info: SequenceInfo, rng: np.random.Generator, init: Any = None) -> None:
        self.detector = SwathDetector.for_sequence(self.params, info, self.tracker)

    def step(self, frame: Frame) -> Any:
        assert self.detector is not None
        profile, scan = self.detector.scan(frame)
        return profile, scan, scan.maximum()


def scan_of(tracker: str) -> Any:
    def make(context: BoundContext) -> ScanOnly:
        return ScanOnly(context.params, tracker)

    return make


class StoneSoupFilter:
    """A plain 1-D bootstrap particle filter of Stone Soup, as many particles as the tracker's."""

    def __init__(self, context: BoundContext) -> None:
        try:
            from stonesoup.models.measurement.linear import LinearGaussian
            from stonesoup.models.transition.linear import RandomWalk
            from stonesoup.predictor.particle import ParticlePredictor
            from stonesoup.resampler.particle import SystematicResampler
            from stonesoup.updater.particle import ParticleUpdater
        except ImportError as exc:
            raise BoundUnavailable("Stone Soup is not installed (pip install subsea-trackbench[speed])") from exc
        self.params = context.params
        self._random_walk = RandomWalk
        self._linear_gaussian = LinearGaussian
        self._predictor_class = ParticlePredictor
        self._updater_class = ParticleUpdater
        self._resampler = SystematicResampler()
        self.state: Any = None
        self.predictor: Any = None
        self.updater: Any = None
        self.time = datetime.datetime(2000, 1, 1)

    def reset(self, info: SequenceInfo, rng: np.random.Generator, init: Any = None) -> None:
        from stonesoup.types.array import StateVectors
        from stonesoup.types.state import ParticleState

        n = int(self.params.n_particles)
        sigma = walk_sigma(self.params, info, "sonar_pf")
        self.predictor = self._predictor_class(self._random_walk(sigma**2))
        resolution = init.resolution_m if init is not None and math.isfinite(init.resolution_m) else 0.1
        model = self._linear_gaussian(ndim_state=1, mapping=(0,), noise_covar=np.array([[resolution**2]]))
        self.updater = self._updater_class(model, resampler=self._resampler)
        start = init.across_m if init is not None and math.isfinite(init.across_m) else 0.0
        states = start + self.params.init_sigma_m * rng.standard_normal((1, n))
        self.time = datetime.datetime(2000, 1, 1)
        self.state = ParticleState(StateVectors(states), weight=np.full(n, 1.0 / n), timestamp=self.time)

    def step(self, frame: Frame) -> Any:
        from stonesoup.types.detection import Detection
        from stonesoup.types.hypothesis import SingleHypothesis

        self.time += datetime.timedelta(seconds=PING_S)
        prediction = self.predictor.predict(self.state, timestamp=self.time)
        across = frame.truth.across_m if frame.truth is not None else math.nan
        if not math.isfinite(across):
            self.state = prediction
            return prediction.mean
        model = self.updater.measurement_model
        detection = Detection(np.array([[across]]), timestamp=self.time, measurement_model=model)
        self.state = self.updater.update(SingleHypothesis(prediction, detection))
        return self.state.mean


@hookimpl
def trackbench_register_speed_bounds(registry: SpeedBounds) -> None:
    """``sonar_pf`` against Stone Soup and its own scan; ``sonar_detector`` against the same scan."""
    scan = "its profile + likelihood scan + maximum"
    peer = "Stone Soup 1-D particle filter, same N"
    registry.add_bound(SpeedBound("sonar_pf", peer, StoneSoupFilter, DATASET, TimesFaster(2)))
    registry.add_bound(SpeedBound("sonar_pf", scan, scan_of("sonar_pf"), DATASET))
    registry.add_bound(SpeedBound("sonar_detector", scan, scan_of("sonar_detector"), DATASET, MsAtMost(0.6)))
