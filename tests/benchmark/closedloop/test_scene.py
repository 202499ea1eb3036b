"""Tests of benchmark.closedloop.scene through the runner: frames follow the vehicle the estimates steer."""

from __future__ import annotations

import functools
from typing import Any

import numpy as np
import pytest

from benchmark.closedloop.scene import ClosedLoopScene
from benchmark.metrics import CORE
from benchmark.metrics.closed_loop import METRICS
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


@functools.cache
def drive(tracker: type[Tracker], start_offset_m: float = ROUTE["start_offset_m"]) -> tuple[Any, ClosedLoopScene]:
    scene = ClosedLoopScene.from_dict({**ROUTE, "start_offset_m": start_offset_m})
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


def following(result: Any) -> dict[str, float]:
    metrics = CORE
    for metric in METRICS:
        metrics = metrics.adding(metric)
    return result.summary(metrics)


def test_each_frame_s_score_holds_where_the_vehicle_stood_when_it_was_taken() -> None:
    result, scene = drive(Oracle)
    places = scene.track.places
    loops = [score.loop for score in result.scores]
    assert [loop.along_m for loop in loops] == [place.s_m for place in places]
    assert [loop.offset_m for loop in loops] == [place.offset_m for place in places]
    assert [loop.heading_error_deg for loop in loops] == pytest.approx([np.degrees(p.heading_error) for p in places])
    assert [loop.time_s for loop in loops] == pytest.approx([0.04 * i for i in range(len(loops))])
    assert all(loop.in_view for loop in loops)


def test_the_oracle_follows_the_whole_route_closely() -> None:
    result, scene = drive(Oracle)
    summary = following(result)
    assert summary["followed_m"] == pytest.approx(scene.spec.route.length_m, abs=0.05)
    assert summary["offset_max_m"] == pytest.approx(ROUTE["start_offset_m"], rel=0.02)  # where it started
    assert summary["offset_mean_m"] < scene.spec.pipe_diameter_m / 2
    on_cable = following(drive(Oracle, start_offset_m=0.0)[0])
    assert on_cable["followed_m"] == pytest.approx(scene.spec.route.length_m, abs=0.05)
    assert on_cable["offset_max_m"] < 0.02 and on_cable["offset_mean_m"] < 0.01
    assert on_cable["heading_error_deg"] < 2.0


def test_the_biased_tracker_keeps_the_vehicle_off_the_cable() -> None:
    result, scene = drive(Biased)
    assert following(result)["offset_mean_m"] > scene.spec.pipe_diameter_m / 2


def test_a_cell_of_an_open_loop_scene_has_no_loop_values() -> None:
    from benchmark.modalities.camera.scenes.scene import CameraScene

    scene = CameraScene.from_dict({"name": "test/open", "n_frames": 2, "frame_size": [48, 36], "focal_px": 57.0})
    result = run_cell(make_cell(TrackerEntry(Oracle.name, Oracle, Oracle.make_params()), scene))
    assert result.status == "ok" and all(score.loop is None for score in result.scores)
    assert not set(following(result)) & {metric.name for metric in METRICS}


CROSSED = {**ROUTE, "name": "routes/crossed", "crossing": [{"at_m": 1.2, "angle_deg": 50.0}]}


def drive_by_hand(data: dict[str, Any]) -> tuple[list[np.ndarray], list[Any], ClosedLoopScene]:
    """Frames and truths of a route driven by its true cable, without the runner."""
    scene = ClosedLoopScene.from_dict(data)
    images, truths = [], []
    for frame in scene.frames():
        images.append(frame.observation)
        truths.append(frame.truth)
        scene.steer(frame.truth.cable if frame.truth.cable.is_known else None)
    return images, truths, scene


def test_the_oracle_follows_a_route_with_a_crossing_cable_to_its_end() -> None:
    scene = ClosedLoopScene.from_dict(CROSSED)
    assert scene.spec.look().crossing == scene.spec.crossing  # the camera scene draws it
    result = run_cell(make_cell(TrackerEntry(Oracle.name, Oracle, Oracle.make_params()), scene))
    summary = following(result)
    assert result.status == "ok"
    assert summary["followed_m"] == pytest.approx(scene.spec.route.length_m, abs=0.05)
    assert summary["offset_mean_m"] < scene.spec.pipe_diameter_m / 2


def test_a_crossing_cable_changes_the_frames_where_it_is_seen_but_not_the_truth() -> None:
    plain_images, plain_truths, plain = drive_by_hand(ROUTE)
    images, truths, crossed = drive_by_hand(CROSSED)
    assert truths == plain_truths and crossed.track.places == plain.track.places
    changed = np.array([np.count_nonzero(a != b) for a, b in zip(images, plain_images, strict=True)])
    seen_from = [truth.pose.cz for truth in truths]
    # It is in view from the start (about 1 m ahead) until the camera has passed over it.
    assert np.all(changed[np.array(seen_from) < 1.0] > 200)
    assert np.all(changed[np.array(seen_from) > 1.6] == 0)


def test_a_crossing_off_the_route_is_a_data_error() -> None:
    from benchmark.errors import DataError

    with pytest.raises(DataError, match="not on the route"):
        ClosedLoopScene.from_dict({**ROUTE, "crossing": [{"at_m": 3.0, "angle_deg": 50.0}]})
