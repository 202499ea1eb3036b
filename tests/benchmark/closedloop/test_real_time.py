"""Tests of benchmark.closedloop.real_time: a busy tracker skips the frames that arrive meanwhile."""

from __future__ import annotations

import dataclasses
import functools
import math
from typing import Any

import hypothesis.strategies as st
import numpy as np
import pandas as pd
import pydantic
import pytest
from hypothesis import given

from benchmark.closedloop.controller import CableFollower, FollowerGains
from benchmark.closedloop.loop import CameraMount, Loop
from benchmark.closedloop.real_time import MEASURED_SOURCE, RealTime, StepClock, intervals_until_next
from benchmark.closedloop.route import Leg, Route, RouteSpec
from benchmark.closedloop.scene import ClosedLoopScene
from benchmark.closedloop.vehicle import Kinematics, VehicleState
from benchmark.errors import ParameterError
from benchmark.harness import describe_result
from benchmark.leaderboard import REAL_TIME_BOARD, leaderboards
from benchmark.modalities.camera.model import CableState
from benchmark.modalities.camera.scenes.scene import CameraScene
from benchmark.modalities.camera.scenes.silhouette import cable_truth
from benchmark.registry import TrackerEntry
from benchmark.report.summary import summary_text
from benchmark.results import CellResult
from benchmark.runner import run_cell
from benchmark.selection import SelectionError, in_real_time
from benchmark.store import ResultStore

from ..conftest import make_cell
from .test_scene import ROUTE, Oracle, following

INTERVAL_S = 0.04
"""The frame interval of the test route (the scene's default)."""


class Slow(Oracle):
    """The oracle, declared to need 2.5 frame intervals a step."""

    name = "slow"


def entry(tracker: type[Oracle]) -> TrackerEntry:
    return TrackerEntry(tracker.name, tracker, tracker.make_params())


@functools.cache
def drive(tracker: type[Oracle], declared_ms: float | None, *, ordinary: bool = False) -> CellResult:
    """``tracker`` on the test route, in real time with ``declared_ms`` (or measured), or the ordinary run."""
    cell = make_cell(entry(tracker), ClosedLoopScene.from_dict(ROUTE))
    return run_cell(cell if ordinary else dataclasses.replace(cell, real_time=RealTime(declared_ms)))


def loop_values(result: CellResult) -> list[tuple[Any, ...]]:
    """What a cell saw and did, frame by frame, without its step times."""
    return [(s.index, s.outcome, tuple(s.errors.items()), s.loop) for s in result.scores]


@given(st.integers(1, 50), st.floats(1e-6, 1.0), st.floats(1e-3, 1.0))
def test_a_step_within_k_intervals_sees_the_frame_k_intervals_later(k: int, share: float, interval_s: float) -> None:
    busy_s = (k - 1 + share) * interval_s
    assert intervals_until_next(busy_s, interval_s) == k
    assert intervals_until_next(k * interval_s, interval_s) == k  # a frame arriving as the step ends is taken


def test_a_step_shorter_than_an_interval_sees_every_frame_and_a_bad_step_time_is_refused() -> None:
    assert intervals_until_next(0.0, INTERVAL_S) == intervals_until_next(0.039, INTERVAL_S) == 1
    for bad in (-0.01, math.nan, math.inf):
        with pytest.raises(ValueError, match="step time"):
            intervals_until_next(bad, INTERVAL_S)


def test_a_declared_step_time_is_the_same_every_frame_and_names_its_source() -> None:
    real_time = RealTime(17.0)
    clock = real_time.clock()
    assert [clock.busy_s(step) for step in (5.0, 0.001, 0.2)] == [0.017] * 3
    assert real_time.source == "declared 17 ms" and real_time.key == "real-time:declared=17.0ms"
    for bad in (0.0, -1.0, math.nan):
        with pytest.raises(pydantic.ValidationError):
            RealTime(bad)


@given(st.lists(st.floats(0.0, 1.0), min_size=1, max_size=30))
def test_a_measured_step_time_is_the_running_lower_median_of_the_steps_after_the_first(steps: list[float]) -> None:
    clock = StepClock(RealTime())
    busy = [clock.busy_s(step) for step in steps]
    assert busy[0] == 0.0
    for i in range(1, len(steps)):
        so_far = steps[1 : i + 1]
        assert busy[i] == sorted(so_far)[(len(so_far) - 1) // 2]
    assert RealTime().source == MEASURED_SOURCE


def test_one_slow_step_among_the_first_is_not_taken_for_the_pace() -> None:
    clock = StepClock(RealTime())
    assert [clock.busy_s(step) for step in (2.0, 0.001, 1.0, 0.002)] == [0.0, 0.001, 0.001, 0.002]


def test_a_tracker_declared_at_2_5_intervals_sees_one_frame_in_3() -> None:
    ordinary, real_time = drive(Slow, None, ordinary=True), drive(Slow, 2.5 * INTERVAL_S * 1000)
    seen = [score.index for score in real_time.scores]
    assert real_time.status == "ok" and seen[0] == 0 and set(np.diff(seen)) == {3}
    assert len(seen) == pytest.approx(len(ordinary.scores) / 3, abs=2)
    assert [score.loop.time_s for score in real_time.scores] == pytest.approx([INTERVAL_S * i for i in seen])
    assert following(real_time)["followed_m"] == pytest.approx(following(ordinary)["followed_m"], abs=0.1)


def test_a_tracker_faster_than_the_frame_rate_sees_every_frame_as_in_the_ordinary_run() -> None:
    ordinary, real_time = drive(Oracle, None, ordinary=True), drive(Oracle, 10.0)
    assert loop_values(real_time) == loop_values(ordinary)
    assert [score.index for score in real_time.scores] == list(range(len(ordinary.scores)))


def test_the_same_seed_and_declared_step_time_give_the_same_frames_and_results() -> None:
    first = drive(Slow, 100.0)
    cell = make_cell(entry(Slow), ClosedLoopScene.from_dict(ROUTE))
    again = run_cell(dataclasses.replace(cell, real_time=RealTime(100.0)))
    assert loop_values(again) == loop_values(first)
    assert loop_values(drive(Slow, 70.0)) != loop_values(first)  # two intervals, not three


def test_the_vehicle_holds_the_last_command_over_the_skipped_frames_and_obeys_the_new_over_the_last() -> None:
    interval_s, size = 0.2, (320, 240)
    follower = CableFollower(FollowerGains(), interval_s, size[0])
    start = VehicleState(0.3, 0.0, 0.0)
    loop = Loop(Route(RouteSpec((Leg(20.0),))), Kinematics(), CameraMount(), follower, interval_s, start)

    def estimate() -> CableState:
        truth = cable_truth(loop.pose(), 0.1, 380.0, size)
        return CableState(truth.d, truth.alpha, truth.w, truth.beta)

    held = loop.steer(estimate())
    before = loop.state
    obeyed = loop.steer(estimate(), intervals=3)
    advance = functools.partial(loop.kinematics.advance, interval_s=interval_s)
    assert held != obeyed
    assert loop.state == advance(advance(advance(before, held), held), obeyed)
    with pytest.raises(ValueError, match="at least 1 interval"):
        loop.steer(estimate(), intervals=0)


def test_a_measured_step_time_of_a_fast_tracker_sees_every_frame() -> None:
    result = drive(Oracle, None)
    assert result.real_time == MEASURED_SOURCE
    assert [score.index for score in result.scores] == list(range(len(result.scores)))


def test_the_cell_s_key_and_result_record_the_mode_and_its_source() -> None:
    cell = make_cell(entry(Slow), ClosedLoopScene.from_dict(ROUTE))
    declared, measured = (dataclasses.replace(cell, real_time=RealTime(ms)) for ms in (100.0, None))
    assert len({cell.key, declared.key, measured.key}) == 3
    assert declared.label().endswith("real time (declared 100 ms)")
    assert drive(Slow, 100.0).real_time == "declared 100 ms" and drive(Slow, None, ordinary=True).real_time == ""
    assert "real time (declared 100 ms)" in describe_result(drive(Slow, 100.0))
    assert "real time" not in describe_result(drive(Slow, None, ordinary=True))


def test_real_time_on_an_open_loop_sequence_is_refused() -> None:
    scene = CameraScene.from_dict({"name": "test/open", "n_frames": 2, "frame_size": [48, 36], "focal_px": 57.0})
    cell = make_cell(entry(Oracle), scene)
    with pytest.raises(ValueError, match="closed-loop"):
        dataclasses.replace(cell, real_time=RealTime())
    with pytest.raises(SelectionError, match="closed-loop sequences only.*test/open"):
        in_real_time([cell])


def test_step_times_are_declared_per_selected_tracker() -> None:
    cells = [make_cell(entry(tracker), ClosedLoopScene.from_dict(ROUTE)) for tracker in (Oracle, Slow)]
    paced = in_real_time(cells, ["slow=100"])
    assert [cell.real_time for cell in paced] == [RealTime(), RealTime(100.0)]
    words = [("slow", "TRACKER=MS"), ("slow=-3", "positive"), ("=4", "TRACKER=MS"), ("x=4", "not selected")]
    for word, message in words:
        with pytest.raises(ParameterError, match=message):
            in_real_time(cells, [word])


def test_real_time_cells_get_a_board_of_their_own_that_names_each_step_time_source(tmp_path: Any) -> None:
    ordinary, declared, measured = drive(Slow, None, ordinary=True), drive(Slow, 100.0), drive(Oracle, None)
    with ResultStore(tmp_path / "r.sqlite") as store:
        run = store.start_run([], {})
        for result in (ordinary, declared, measured):
            store.add_cell(run, result)
        cells = store.cells()
        frames = store.frame_tables(cells["id"])
    assert sorted(cells["real_time"]) == ["", "declared 100 ms", MEASURED_SOURCE]
    boards = leaderboards(cells, frames, {})
    normal = "camera: routes, closed loop"
    board = boards[normal + REAL_TIME_BOARD]
    assert "real_time" not in boards[normal] and set(boards[normal]["tracker"]) == {"slow"}
    sources = board.drop_duplicates("tracker").set_index("tracker")["real_time"]
    assert sources.to_dict() == {"slow": "declared 100 ms", "oracle": MEASURED_SOURCE}
    assert list(board.columns[board.columns.get_loc("init") :][:2]) == ["init", "real_time"]
    alone = leaderboards(cells[cells["real_time"] == ""], frames, {})[normal]
    pd.testing.assert_frame_equal(boards[normal], alone)
    summary = summary_text(boards, width=200)
    assert f"{normal}, real time: 2 trackers over 1 dataset; step time declared 100 ms; {MEASURED_SOURCE}" in summary
    assert f"{normal}: 1 tracker over 1 dataset\n" in summary


def test_one_tracker_under_two_sources_gets_a_row_for_each() -> None:
    cells = pd.DataFrame(
        {
            "id": [1, 2],
            "tracker": ["slow", "slow"],
            "tracker_key": ["k+real-time:declared=100.0ms", "k+real-time:measured-median"],
            "dataset": ["routes/test"] * 2,
            "dataset_key": ["d"] * 2,
            "modality": ["camera"] * 2,
            "seed": [0, 0],
            "init": ["truth"] * 2,
            "status": ["ok"] * 2,
            "message": [""] * 2,
            "real_time": ["declared 100 ms", MEASURED_SOURCE],
        }
    )
    frames = pd.DataFrame(
        {"cell_id": [1, 2], "frame": [0, 0], "outcome": ["correct", "missed"], "step_ms": [1.0] * 2, "wall_ms": [1.0] * 2}
    )
    board = leaderboards(cells, frames, {})["camera" + REAL_TIME_BOARD]  # no vehicle values: an open-loop layout
    rows = board[board["dataset"] == "routes/test"].set_index("tracker")["real_time"]
    assert rows.to_dict() == {"slow (declared 100 ms)": "declared 100 ms", f"slow ({MEASURED_SOURCE})": MEASURED_SOURCE}
