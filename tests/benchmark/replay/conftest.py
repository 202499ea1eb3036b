"""Fake filter trackers for the replay tests, and recordings of the first-party sonar and stereo filters.

The fakes are a particle filter and a Gaussian one, drawing from the
cell's generator.  ``real_recordings`` records :data:`REAL_FRAMES` frames
of each cell of :data:`REAL_CELLS`: the sonar particle filter on a sonar
sequence, the stereo EKF on a stereo sequence and on a stereo-images one.
"""

from __future__ import annotations

from typing import Any, ClassVar

import numpy as np
import pytest

from benchmark.modalities.camera.model import CableState
from benchmark.model import Frame, SequenceInfo
from benchmark.plugins import load_registry
from benchmark.registry import Registry
from benchmark.replay.record import FrameRange, Recording, record_cell
from benchmark.runner import Cell
from benchmark.tracker import Tracker

from ..conftest import ALL_TRACKERS, make_registry


class Particles(Tracker):
    """500 particles around the first truth, jittered and weighed at random each frame; the estimate their mean.

    Every estimate it returns is kept in :attr:`estimates` (of this process), so that a test can compare runs.
    """

    name = "fake-particles"
    version = "1.0"
    modality = "camera"
    estimates: ClassVar[list[CableState]] = []
    count = 500

    def reset(self, info: SequenceInfo, rng: np.random.Generator, init: Any = None) -> None:
        self.rng = rng
        start = init.cable.as_array() if init is not None else np.array([0.0, 0.0, 10.0, 0.0])
        self.particles = start + rng.normal(0.0, 1.0, (self.count, 4)) * np.array([3.0, 0.05, 1.0, 0.01])
        self.weights = np.full(self.count, 1.0 / self.count)

    def step(self, frame: Frame) -> Any:
        jitter = self.rng.normal(0.0, 1.0, self.particles.shape) * np.array([1.5, 0.01, 0.3, 0.005])
        self.particles = self.particles + jitter
        raw = 0.5 + self.rng.random(self.count)
        self.weights = raw / raw.sum()
        estimate = CableState.from_array(self.weights @ self.particles)
        type(self).estimates.append(estimate)
        return estimate


class Gaussian(Tracker):
    """A mean that walks at random from the first truth with a covariance that grows; no estimate on frame 2."""

    name = "fake-gaussian"
    version = "1.0"
    modality = "camera"

    def reset(self, info: SequenceInfo, rng: np.random.Generator, init: Any = None) -> None:
        self.rng = rng
        self.mean = init.cable.as_array()[:3].copy()
        self.covariance = np.diag([4.0, 0.01, 1.0])

    def step(self, frame: Frame) -> Any:
        self.mean = self.mean + self.rng.normal(0.0, 0.5, 3)
        self.covariance = self.covariance * 1.1
        return None if frame.index == 2 else CableState(*self.mean, 0.0)


@pytest.fixture
def registry() -> Registry:
    """The fake registry with the two filters beside the harness's fakes."""
    return make_registry((*ALL_TRACKERS, Particles, Gaussian))


REAL_CELLS = {
    "sonar": ("sonar_pf", "sonar/concrete"),
    "stereo": ("stereo_ekf", "stereo/case1-medium"),
    "stereo-images": ("stereo_ekf", "stereo-images/case1-medium"),
}
"""Name: tracker and sequence of a recording of a first-party filter."""

REAL_FRAMES = 4


@pytest.fixture(scope="session")
def plugin_registry() -> Registry:
    """Every plugin's trackers and suites."""
    return load_registry()


def real_cell(registry: Registry, name: str, seed: int = 0) -> Cell:
    """The cell of :data:`REAL_CELLS` ``name``, started from the truth."""
    tracker, dataset = REAL_CELLS[name]
    entry = registry.trackers[tracker]
    return Cell(entry, registry.sequence(dataset), seed, "truth", modality=registry.modalities[entry.modality])


@pytest.fixture(scope="session")
def real_recordings(plugin_registry: Registry) -> dict[str, Recording]:
    """The first :data:`REAL_FRAMES` frames of each cell of :data:`REAL_CELLS`, recorded."""
    return {name: record_cell(real_cell(plugin_registry, name), FrameRange(0, REAL_FRAMES)) for name in REAL_CELLS}
