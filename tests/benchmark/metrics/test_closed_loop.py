"""Tests of benchmark.metrics.closed_loop: the following metrics on hand-made frame tables and on boards."""

from __future__ import annotations

import importlib.metadata
import math

import numpy as np
import pandas as pd
import pytest

from benchmark.leaderboard import leaderboards
from benchmark.metrics import CORE, closed_loop
from benchmark.metrics.closed_loop import (
    FOLLOWED,
    FOLLOWED_SHARE,
    HEADING_ERROR,
    LOST_S,
    METRICS,
    OFFSET_MAX,
    OFFSET_MEAN,
    followed_distance,
    followed_per_cell,
)
from benchmark.modalities.camera.modality import CAMERA
from benchmark.registry import Registry
from benchmark.results import LoopValues

INTERVAL_S = 0.5


def loop_frames(in_view: list[int], cell_id: int = 1, offsets: list[float] | None = None) -> pd.DataFrame:
    """A closed-loop cell's frames every :data:`INTERVAL_S`, 1 m apart along the route, the cable in view where 1."""
    count = len(in_view)
    offsets = offsets if offsets is not None else [0.0] * count
    rows = [
        {
            "cell_id": cell_id,
            "frame": index,
            "outcome": "correct",
            **LoopValues(offsets[index], -2.0 * offsets[index], float(index), INTERVAL_S * index, bool(seen)).columns(),
            "step_ms": 1.0,
            "wall_ms": 1.0,
        }
        for index, seen in enumerate(in_view)
    ]
    return pd.DataFrame(rows)


def open_loop_frames(count: int = 4) -> pd.DataFrame:
    return pd.DataFrame(
        {"cell_id": 9, "frame": range(count), "outcome": "correct", "err_d_px": 1.0, "step_ms": 1.0, "wall_ms": 1.0}
    )


def test_followed_ends_at_the_last_frame_in_view_before_the_cable_is_out_of_view_for_too_long() -> None:
    assert LOST_S == 2.0  # 4 frames of INTERVAL_S: a gap of 4 frames (2 s after the last seen) is not yet lost
    brief_gap = [1, 1, 0, 0, 0, 0, 1, 1]
    assert FOLLOWED.of(loop_frames(brief_gap)) == 7.0
    lost = [1, 1, 1, 0, 0, 0, 0, 0, 1, 1]  # frame 7 is 2.5 s after frame 2, the last in view
    assert FOLLOWED.of(loop_frames(lost)) == 2.0
    assert FOLLOWED.of(loop_frames([0, 0, 0, 0, 0, 0, 1])) == 0.0  # never in view before it was lost (frame 5)
    assert FOLLOWED.of(loop_frames([0, 0, 0, 0, 0, 1])) == 5.0  # frame 4 is not yet over 2 s from the start
    assert FOLLOWED.of(loop_frames([1, 1, 0, 0, 0])) == 1.0  # out of view at the end, never for too long


def test_followed_distance_takes_its_time_limit() -> None:
    along, time = np.arange(6.0), np.arange(6.0)
    seen = np.array([True, True, False, False, True, True])
    assert followed_distance(along, time, seen, lost_s=2.0) == 5.0
    assert followed_distance(along, time, seen, lost_s=1.5) == 1.0


def test_a_run_never_lost_that_passed_the_route_s_end_followed_all_of_it() -> None:
    along, time = np.array([0.0, 1.0, 2.0, 3.0]), np.arange(4.0)
    seen = np.array([True, True, True, True])
    assert followed_distance(along, time, seen, route_m=4.0) == 4.0  # one step on from the last frame: the end
    assert followed_distance(along, time, seen, route_m=4.5) == 3.0  # more than a step short of it
    assert followed_distance(along, time, seen) == 3.0  # no route length said
    lost = np.array([True, False, False, False])
    assert followed_distance(along, time, lost, lost_s=1.5, route_m=4.0) == 0.0  # lost before the end


def test_pooled_cells_are_split_and_followed_is_their_mean() -> None:
    first, second = loop_frames([1] * 5, cell_id=1), loop_frames([1, 1, 0, 0, 0, 0, 0, 1], cell_id=2)
    pooled = pd.concat([first, second], ignore_index=True)
    assert followed_per_cell(pooled).tolist() == [4.0, 1.0]
    assert FOLLOWED.of(pooled) == 2.5
    without_ids = pooled.drop(columns="cell_id")  # a frame index that does not increase starts a cell too
    assert followed_per_cell(without_ids).tolist() == [4.0, 1.0]


def test_offsets_and_heading_errors_are_absolute_and_pool_over_cells() -> None:
    first = loop_frames([1, 1, 1], cell_id=1, offsets=[0.1, -0.3, 0.2])
    second = loop_frames([1], cell_id=2, offsets=[-0.6])
    pooled = pd.concat([first, second], ignore_index=True)
    assert OFFSET_MEAN.of(first) == pytest.approx(0.2)
    assert OFFSET_MAX.of(first) == pytest.approx(0.3)
    assert HEADING_ERROR.of(first) == pytest.approx(0.4)
    assert OFFSET_MEAN.of(pooled) == pytest.approx(0.3)
    assert OFFSET_MAX.of(pooled) == pytest.approx(0.6)
    sums = np.array([OFFSET_MAX.sums(table, 1.0) for table in (first, second)])
    assert OFFSET_MAX.value(OFFSET_MAX.pooled(sums, axis=0), 1.0) == pytest.approx(0.6)


def test_they_are_empty_on_open_loop_frames_and_skip_them_when_pooled() -> None:
    assert all(math.isnan(metric.of(open_loop_frames())) for metric in METRICS)
    assert all(math.isnan(metric.of(open_loop_frames().iloc[0:0])) for metric in METRICS)
    mixed = pd.concat([open_loop_frames(), loop_frames([1, 1, 1], offsets=[0.1, 0.1, 0.4])], ignore_index=True)
    assert FOLLOWED.of(mixed) == 2.0 and OFFSET_MEAN.of(mixed) == pytest.approx(0.2)


def test_a_board_shows_them_only_where_its_frames_have_loop_columns() -> None:
    metrics = CORE
    for metric in METRICS:
        metrics = metrics.adding(metric)
    cells = [
        {"id": cell_id, "tracker": "t", "tracker_key": "k", "dataset": dataset, "dataset_key": dataset,
         "modality": "camera", "seed": 0, "init": "truth", "status": "ok", "message": "", "deterministic": True}
        for cell_id, dataset in ((1, "routes/a"), (9, "camera/S1"))
    ]
    loop = loop_frames([1, 1, 1], offsets=[0.1, 0.1, 0.4])
    names = [metric.name for metric in METRICS if metric is not FOLLOWED_SHARE]  # the frames do not say the route
    open_only = leaderboards(pd.DataFrame(cells[1:]), open_loop_frames(), {"camera": CAMERA}, metrics)["camera"]
    assert not set(names) & set(open_only.columns)
    both = leaderboards(pd.DataFrame(cells), pd.concat([loop, open_loop_frames()]), {"camera": CAMERA}, metrics)
    assert list(both) == ["camera", "camera: routes, closed loop"]
    assert both["camera"]["dataset"].tolist() == ["(all)", "camera/S1"]
    assert not set(names) & set(both["camera"].columns)
    board = both["camera: routes, closed loop"].set_index("dataset")
    assert board.loc["routes/a", names].tolist() == pytest.approx([2.0, 0.2, 0.4, 0.4])
    assert "followed_lo_m" in board.columns and FOLLOWED_SHARE.name not in board.columns


def test_a_metric_requiring_columns_is_kept_off_a_board_without_them() -> None:
    metrics = CORE.adding(FOLLOWED)
    assert FOLLOWED in metrics.for_board("camera", ())
    assert FOLLOWED in metrics.for_board("camera", (), set(FOLLOWED.requires) | {"outcome"})
    assert FOLLOWED not in metrics.for_board("camera", (), {"outcome", "loop_along_m"})
    assert len(metrics.for_board("camera", (), {"outcome"})) == len(CORE.for_board("camera", ()))


def test_they_are_registered_for_every_modality_through_the_hook() -> None:
    registry = Registry()
    closed_loop.trackbench_register_metrics(registry)
    assert [m.name for m in registry.metrics.for_board("camera", ())][-len(METRICS):] == [m.name for m in METRICS]
    assert all(metric.kind == "following" for metric in METRICS)


def test_trackbench_installs_them_as_a_plugin_like_any_other() -> None:
    plugins = {entry.value for entry in importlib.metadata.entry_points(group="trackbench")}
    assert "benchmark.metrics.closed_loop" in plugins
