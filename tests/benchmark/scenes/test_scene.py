"""The scaffolding of simulated scenes: spec, lazy cache dropped by pickling, seeded streams, frames."""

from __future__ import annotations

import pickle
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np
import pytest

from benchmark.model import SequenceInfo
from benchmark.scenes.scene import SimulatedScene


@dataclass(frozen=True)
class ToySpec:
    name: str
    n_frames: int
    seed: int = 0
    frame_interval_s: float = 0.5

    @classmethod
    def from_dict(cls, data: Mapping[str, Any], source: str = "<dict>") -> ToySpec:
        return cls(**data)


class ToyScene(SimulatedScene[ToySpec, np.ndarray]):
    """Frame ``k`` observes a draw of its own stream; the truth is a per-sequence draw kept in the cache."""

    spec_type = ToySpec
    builds = 0

    @property
    def info(self) -> SequenceInfo:
        return SequenceInfo(self.spec.name, "stereo", n_frames=self.spec.n_frames)

    def _build_cache(self) -> np.ndarray:
        type(self).builds += 1
        return self._stream(0).standard_normal(self.spec.n_frames)

    def observation(self, index: int) -> float:
        return float(self._stream(1, self._check(index)).standard_normal())

    def truth(self, index: int) -> float:
        return float(self._state()[self._check(index)])

    def navigation(self, index: int) -> int:
        return -index


def test_a_scene_is_built_from_its_spec_or_a_mapping() -> None:
    scene = ToyScene.from_dict({"name": "toy/a", "n_frames": 3, "seed": 4})
    assert isinstance(scene, ToyScene) and scene.spec == ToySpec("toy/a", 3, 4)


def test_frames_are_the_frames_on_their_own_and_repeat_for_a_seed() -> None:
    scene = ToyScene(ToySpec("toy/a", 4, seed=1))
    frames = list(scene.frames())
    assert [frame.index for frame in frames] == [0, 1, 2, 3]
    assert [frame.time_s for frame in frames] == [0.0, 0.5, 1.0, 1.5]
    assert [frame.navigation for frame in frames] == [0, -1, -2, -3]
    assert frames == [scene.frame(k) for k in range(4)] == list(ToyScene(ToySpec("toy/a", 4, seed=1)))
    other = list(ToyScene(ToySpec("toy/a", 4, seed=2)))
    assert all(a.observation != b.observation and a.truth != b.truth for a, b in zip(frames, other, strict=True))
    # the streams are independent of one another: frame streams differ from each other and from the cache's
    assert len({frame.observation for frame in frames} | {frame.truth for frame in frames}) == 8


def test_the_cache_is_built_once_and_not_pickled() -> None:
    scene = ToyScene(ToySpec("toy/a", 3))
    before = ToyScene.builds
    truths = [scene.truth(k) for k in range(3)]
    assert ToyScene.builds == before + 1
    copy = pickle.loads(pickle.dumps(scene))
    assert copy._cache is None and pickle.dumps(scene) == pickle.dumps(ToyScene(scene.spec))
    assert [copy.truth(k) for k in range(3)] == truths
    assert ToyScene.builds == before + 2


def test_frames_outside_the_sequence_are_named() -> None:
    scene = ToyScene(ToySpec("toy/a", 3))
    for index in (-1, 3):
        with pytest.raises(IndexError, match=rf"toy/a: frame {index} out of range 0\.\.2"):
            scene.frame(index)

