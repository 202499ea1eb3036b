"""A short clip of rendered stereo image pairs, shared by the stereo trackers' tests.

``stereo_clip`` is the first :data:`CLIP_FRAMES` frames of the registered
``stereo-images/case1-medium`` sequence, as a :class:`benchmark.model.Sequence`
of its own (rendered once per test run), so that a tracker can run on it
through :func:`benchmark.runner.run_cell` like on any sequence;
``stereo_clip_measured`` is the same frames with what the front end
measures in each pair in place of the pair.
"""

from __future__ import annotations

import dataclasses
import itertools
from collections.abc import Iterator

import pytest

from benchmark.modalities.stereo.frontend import measure
from benchmark.model import Frame, Sequence, SequenceInfo
from benchmark.plugins import load_registry
from benchmark.registry import Registry

CLIP_FRAMES = 10


class Clip(Sequence):
    """The first ``n_frames`` frames of a sequence, rendered once and kept."""

    def __init__(self, sequence: Sequence, n_frames: int) -> None:
        self._info = dataclasses.replace(sequence.info, n_frames=n_frames)
        self._frames = list(itertools.islice(sequence.frames(), n_frames))

    @property
    def info(self) -> SequenceInfo:
        return self._info

    def frames(self) -> Iterator[Frame]:
        return iter(self._frames)


@pytest.fixture(scope="session")
def plugin_registry() -> Registry:
    """Every plugin's trackers and suites."""
    return load_registry()


@pytest.fixture(scope="session")
def stereo_clip(plugin_registry: Registry) -> Clip:
    """The first frames of ``stereo-images/case1-medium``: image pairs with truth and CH's navigation."""
    sequences = {sequence.info.name: sequence for sequence in plugin_registry.suites["stereo-images"].sequences}
    return Clip(sequences["stereo-images/case1-medium"], CLIP_FRAMES)


@pytest.fixture(scope="session")
def stereo_clip_measured(stereo_clip: Clip) -> list[Frame]:
    """The clip's frames with each image pair replaced by what the default front end measures in it."""
    calibration = stereo_clip.info.calibration
    return [
        dataclasses.replace(frame, observation=measure(*frame.observation, calibration))
        for frame in stereo_clip.frames()
    ]
