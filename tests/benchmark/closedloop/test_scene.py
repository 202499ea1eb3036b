"""Tests of benchmark.closedloop.scene through the runner: frames follow the vehicle the estimates steer."""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

from benchmark.closedloop.scene import ClosedLoopScene
from benchmark.modalities.camera.model import CableState, CameraTruth
from benchmark.model import Frame, SequenceInfo
from benchmark.registry import TrackerEntry
from benchmark.runner import run_cell
from benchmark.tracker import Tracker

from ..conftest import make_cell

ROUTE = {
    "name": "routes/test",
    "legs": [{"length_m": 1.0}, {"length_m": 1.5, "turn_deg": 4.0}],
    "frame_size": [96, 72],
    "focal_px": 114.0,
    "start_offset_m": 0.1,
}


class Oracle(Tracker):
    """Reports the true cable, moved ``bias_px`` along its normal."""

    name = "oracle"
    version = "1.0"
    modality = "camera"
    bias_px = 0.0

    def reset(self, info: SequenceInfo, rng: np.random.Generator, init: Any = None) -> None:
        pass

    def step(self, frame: Frame[np.ndarray, CameraTruth]) -> CableState | None:
        cable = frame.truth.cable
        return CableState(cable.d + self.bias_px, cable.alpha, cable.w, cable.beta) if cable.is_known else None


class Biased(Oracle):
    name = "biased"
    bias_px = 6.0  # the 20 px of a 320 px frame, in a 96 px one


def drive(tracker: type[Tracker]) -> tuple[Any, ClosedLoopScene]:
    scene = ClosedLoopScene.from_dict(ROUTE)
    return run_cell(make_cell(TrackerEntry(tracker.name, tracker, tracker.make_params()), scene)), scene


def test_a_tracker_reporting_the_truth_follows_the_route_to_its_end() -> None:
    result, scene = drive(Oracle)
    track = scene.track
    assert result.status == "ok" and track is not None
    assert track.places[-1].s_m == pytest.approx(scene.spec.route.length_m, abs=0.05)
    assert len(result.scores) == len(track.places) < scene.info.n_frames
    offsets = [abs(place.offset_m) for place in track.places]
    assert max(offsets[len(offsets) // 2 :]) < scene.spec.pipe_diameter_m / 2 < offsets[0] * 1.01  # over the cable


def test_a_tracker_reporting_the_cable_to_one_side_drives_the_vehicle_off_it() -> None:
    _, scene = drive(Biased)
    offsets = np.array([place.offset_m for place in scene.track.places])
    assert np.all(np.abs(offsets[len(offsets) // 2 :]) > scene.spec.pipe_diameter_m / 2)


def test_its_frames_are_never_cached_and_its_identity_is_its_spec() -> None:
    scene = ClosedLoopScene.from_dict(ROUTE)
    assert scene.closed_loop and not scene.cache_frames
    assert scene.identity == ClosedLoopScene.from_dict(ROUTE).identity
    assert scene.identity != ClosedLoopScene.from_dict({**ROUTE, "start_offset_m": 0.2}).identity
