"""Tests of benchmark.leaderboard: pooled rows, ranks, units, one board per modality (writers: see report/)."""

from __future__ import annotations

import math
import re

import pandas as pd
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from benchmark.metrics import CORE
from benchmark.leaderboard import ALL_DATASETS, board_columns, error_columns, is_pooled, leaderboards, suite_of
from benchmark.modalities.camera.modality import CAMERA
from benchmark.modalities.sonar.modality import SONAR
from benchmark.modality import Modality

ERRORS = ("err_d_px", "err_alpha_deg", "err_w_px", "err_beta_deg")
MODALITIES: dict[str, Modality] = {"camera": CAMERA, "sonar": SONAR}


class Cells:
    """Builds cells and frames tables shaped like the store's."""

    def __init__(self) -> None:
        self.cells: list[dict] = []
        self.frames: list[dict] = []

    def add(
        self,
        tracker: str,
        dataset: str,
        seed: int,
        outcomes: list[str | None],
        d_errors: list[float] | None = None,
        step_ms: float = 10.0,
        status: str = "ok",
        message: str = "",
        key: str | None = None,
        modality: str = "camera",
        dataset_key: str | None = None,
        deterministic: bool = False,
    ) -> None:
        cell_id = len(self.cells) + 1
        self.cells.append(
            {
                "id": cell_id,
                "tracker": tracker,
                "tracker_key": key or f"key-{tracker}",
                "dataset": dataset,
                "dataset_key": dataset_key or f"data-{dataset}",
                "modality": modality,
                "seed": seed,
                "init": "truth",
                "status": status,
                "message": message,
                "deterministic": deterministic,
            }
        )
        d_errors = d_errors or [math.nan] * len(outcomes)
        for index, (outcome, d_error) in enumerate(zip(outcomes, d_errors, strict=True)):
            self.frames.append(
                {
                    "cell_id": cell_id,
                    "frame": index,
                    "outcome": outcome,
                    "step_ms": step_ms,
                    "wall_ms": 2 * step_ms,
                    "err_d_px": d_error,
                    "err_alpha_deg": d_error / 10,
                    "err_w_px": 0.0 if outcome not in (None, "missed") else math.nan,
                    "err_beta_deg": math.nan,
                }
            )

    def boards(self, modalities: dict[str, Modality] = MODALITIES) -> dict[str, pd.DataFrame]:
        return leaderboards(pd.DataFrame(self.cells), pd.DataFrame(self.frames), modalities)


def rows(board: pd.DataFrame, dataset: str) -> pd.DataFrame:
    return board[board["dataset"] == dataset].set_index("tracker")


def test_camera_board_has_unit_named_columns() -> None:
    data = Cells()
    data.add("a", "s/1", 0, ["correct", "false"], [1.0, 2.0])
    board = data.boards()["camera"]
    for column in ("rank", "tracker", "dataset", "seeds", "frames", "correct_pct", "false_pct", "missed_pct",
                   "rmse_d_px", "rmse_alpha_deg", "rmse_w_px", "rmse_beta_deg", "cpu_fps", "wall_fps", "status"):
        assert column in board.columns
    numeric = [c for c in board.columns if pd.api.types.is_float_dtype(board[c])]
    assert numeric and all(re.search(r"(_pct|_px|_deg|_m|_fps)$", column) for column in numeric)


def test_seeds_pool_by_frames_not_by_mean_of_rates() -> None:
    data = Cells()
    data.add("a", "s/1", 0, ["correct", "correct", "correct", "missed"], [1.0, 1.0, 1.0, math.nan], step_ms=10.0)
    data.add("a", "s/1", 1, ["false"], [4.0], step_ms=30.0)
    row = rows(data.boards()["camera"], "s/1").loc["a"]
    assert row["seeds"] == 2 and row["frames"] == 5
    assert (row["correct_pct"], row["false_pct"], row["missed_pct"]) == pytest.approx((60.0, 20.0, 20.0))
    assert row["rmse_d_px"] == pytest.approx(math.sqrt((1 + 1 + 1 + 16) / 4))
    assert row["cpu_fps"] == pytest.approx(5 / 0.07)
    assert row["status"] == "ok"


def test_the_spread_over_seeds_is_the_standard_deviation_of_per_seed_correct_rates() -> None:
    data = Cells()
    data.add("a", "s/1", 0, ["correct", "false"])  # 50 %
    data.add("a", "s/1", 1, ["correct"] * 3 + ["missed"])  # 75 %
    data.add("a", "s/2", 0, ["correct"] * 2)  # seed 0 over both datasets: 3 of 4
    data.add("a", "s/2", 1, ["missed"] * 4)  # seed 1 over both datasets: 3 of 8
    data.add("b", "s/1", 0, ["correct"])
    board = data.boards()["camera"]
    assert rows(board, "s/1").loc["a", "correct_sd_pct"] == pytest.approx(pd.Series([50.0, 75.0]).std())
    assert rows(board, "s/2").loc["a", "correct_sd_pct"] == pytest.approx(pd.Series([100.0, 0.0]).std())
    assert rows(board, ALL_DATASETS).loc["a", "correct_sd_pct"] == pytest.approx(pd.Series([75.0, 37.5]).std())
    assert math.isnan(rows(board, "s/1").loc["b", "correct_sd_pct"])


@settings(max_examples=25, deadline=None)
@given(st.lists(st.lists(st.sampled_from(["correct", "false", "missed", None]), min_size=1, max_size=8),
                min_size=1, max_size=4))
def test_pooled_rates_are_frame_weighted_and_sum_to_100(seeds: list[list[str | None]]) -> None:
    data = Cells()
    for seed, outcomes in enumerate(seeds):
        data.add("a", "s/1", seed, outcomes)
    row = rows(data.boards()["camera"], "s/1").loc["a"]
    scored = [o for outcomes in seeds for o in outcomes if o is not None]
    assert row["frames"] == len(scored)
    if scored:
        assert row["correct_pct"] == pytest.approx(100 * scored.count("correct") / len(scored))
        assert row["correct_pct"] + row["false_pct"] + row["missed_pct"] == pytest.approx(100.0)
    else:
        assert math.isnan(row["correct_pct"])


def test_rank_by_correct_then_rmse_d_with_failures_last() -> None:
    data = Cells()
    data.add("worse", "s/1", 0, ["correct", "false"], [1.0, 9.0])
    data.add("tied-precise", "s/1", 0, ["correct", "correct", "missed", "missed"], [0.5, 0.5, math.nan, math.nan])
    data.add("tied-rough", "s/1", 0, ["correct", "correct", "false", "false"], [3.0, 3.0, 3.0, 3.0])
    data.add("best", "s/1", 0, ["correct", "correct", "correct", "false"], [2.0, 2.0, 2.0, 2.0])
    data.add("crashed", "s/1", 0, ["correct"], [0.0], status="error", message="RuntimeError: x (frame 1)")
    board = data.boards()["camera"]
    ranked = board[board["dataset"] == "s/1"]
    assert ranked["tracker"].tolist() == ["best", "tied-precise", "tied-rough", "worse", "crashed"]
    assert ranked["rank"].tolist() == [1, 2, 3, 4, 5]


def test_overall_rows_come_first_and_pool_all_datasets() -> None:
    data = Cells()
    data.add("a", "s/1", 0, ["correct"] * 3)
    data.add("a", "s/2", 0, ["missed"])
    data.add("b", "s/1", 0, ["false"] * 2)
    data.add("b", "s/2", 0, ["correct"] * 2)
    board = data.boards()["camera"]
    assert board["dataset"].tolist()[:2] == [ALL_DATASETS, ALL_DATASETS]
    overall = rows(board, ALL_DATASETS)
    assert overall.loc["a", "correct_pct"] == pytest.approx(75.0)
    assert overall.loc["b", "correct_pct"] == pytest.approx(50.0)
    assert overall.loc["a", "rank"] == 1
    assert board["dataset"].tolist()[2:] == ["s/1", "s/1", "s/2", "s/2"]


def test_status_counts_failed_cells_and_quotes_the_first_message() -> None:
    data = Cells()
    data.add("a", "s/1", 0, ["correct"])
    data.add("a", "s/1", 1, ["correct"], status="error", message="RuntimeError: boom (frame 1)")
    data.add("a", "s/1", 2, [], status="timeout", message="no result within the 5 s limit")
    data.add("t", "s/1", 0, [], status="timeout", message="no result within the 5 s limit")
    board = rows(data.boards()["camera"], "s/1")
    assert board.loc["a", "status"] == "error (2/3 cells): RuntimeError: boom (frame 1)"
    assert board.loc["t", "status"].startswith("timeout (1/1 cells)")
    assert board.loc["t", "frames"] == 0


def test_one_board_per_modality() -> None:
    data = Cells()
    data.add("a", "s/1", 0, ["correct"])
    data.add("sonar-thing", "sonar/1", 0, ["correct"], modality="sonar")
    boards = data.boards()
    assert list(boards) == ["camera", "sonar"]
    assert boards["sonar"]["tracker"].unique().tolist() == ["sonar-thing"]
    assert list(boards["sonar"].columns) == board_columns(CORE.for_board("sonar", SONAR.error_columns))
    assert "rmse_across_m" in boards["sonar"] and "rmse_d_px" not in boards["sonar"]
    assert list(boards["camera"].columns) == board_columns(CORE.for_board("camera", CAMERA.error_columns))


def test_one_name_with_two_parameter_sets_is_shown_twice() -> None:
    data = Cells()
    data.add("a", "s/1", 0, ["correct"], key="1111111111")
    data.add("a", "s/1", 0, ["false"], key="2222222222")
    trackers = set(rows(data.boards()["camera"], "s/1").index)
    assert trackers == {"a [11111111]", "a [22222222]"}


def test_one_dataset_name_standing_for_two_datasets_is_shown_twice() -> None:
    data = Cells()
    data.add("a", "seq.txt", 0, ["correct"], dataset_key="aaaaaaaaaaaa")
    data.add("a", "seq.txt", 0, ["false"], dataset_key="bbbbbbbbbbbb")
    data.add("a", "s/1", 0, ["false"])
    board = data.boards()["camera"]
    assert board["dataset"].tolist() == [ALL_DATASETS, "s/1", "seq.txt [aaaaaaaa]", "seq.txt [bbbbbbbb]"]
    assert rows(board, "seq.txt [aaaaaaaa]").loc["a", "correct_pct"] == 100.0
    assert rows(board, ALL_DATASETS).loc["a", "frames"] == 3


def test_cells_without_any_frame_still_get_a_row() -> None:
    data = Cells()
    data.add("killed", "s/1", 0, [], status="timeout", message="no result within the 5 s limit")
    board = leaderboards(pd.DataFrame(data.cells), pd.DataFrame(), MODALITIES)["camera"]
    row = rows(board, "s/1").loc["killed"]
    assert row["frames"] == 0 and math.isnan(row["correct_pct"]) and row["status"].startswith("timeout (1/1")


def test_a_modality_no_plugin_registers_is_boarded_by_name_with_the_error_columns_of_its_frames() -> None:
    data = Cells()
    data.add("a", "s/1", 0, ["correct", "false"], [1.0, 3.0])
    data.add("scanner", "lidar/1", 0, ["correct", "missed"], [2.0, math.nan], modality="lidar")
    frames = pd.DataFrame(data.frames)
    frames.loc[frames["cell_id"] == 2, ["err_alpha_deg", "err_w_px", "err_beta_deg"]] = math.nan
    boards = leaderboards(pd.DataFrame(data.cells), frames, {"camera": CAMERA})
    assert list(boards) == ["camera", "lidar"]
    lidar = rows(boards["lidar"], "lidar/1").loc["scanner"]
    assert lidar["correct_pct"] == 50.0 and lidar["rmse_d_px"] == pytest.approx(2.0)
    assert math.isnan(lidar["rmse_w_px"])
    assert rows(boards["camera"], "s/1").loc["a", "rmse_d_px"] == pytest.approx(math.sqrt(5.0))


def test_error_columns_come_from_the_modality_or_else_from_the_frames() -> None:
    frames = pd.DataFrame(columns=["cell_id", "frame", "outcome", "err_range_m", "step_ms", "wall_ms", "err_bearing_deg"])
    assert error_columns(SONAR, frames) == ("err_across_m",)
    assert error_columns(None, frames) == ("err_range_m", "err_bearing_deg")
    assert error_columns(None, pd.DataFrame()) == ()


def test_a_board_of_several_suites_pools_each_suite_after_the_whole() -> None:
    data = Cells()
    data.add("a", "dev/1", 0, ["correct", "correct"])
    data.add("a", "dev/2", 0, ["false", "correct"])
    data.add("a", "test/1", 0, ["missed", "missed"])
    data.add("a", "test/2", 0, ["correct", "missed"])
    data.add("a", "alone/1", 0, ["correct"])
    board = data.boards()["camera"]
    assert board["dataset"].tolist()[:3] == [ALL_DATASETS, "dev (all)", "test (all)"]
    assert rows(board, "dev (all)").loc["a", "correct_pct"] == 75.0
    assert rows(board, "test (all)").loc["a", "missed_pct"] == 75.0
    assert "alone (all)" not in set(board["dataset"])
    single = Cells()
    single.add("a", "dev/1", 0, ["correct"])
    single.add("a", "dev/2", 0, ["false"])
    assert single.boards()["camera"]["dataset"].tolist() == [ALL_DATASETS, "dev/1", "dev/2"]


def test_suites_and_pooled_rows_are_read_from_dataset_names() -> None:
    assert suite_of("camera-test/t01") == "camera-test"
    assert suite_of("/data/run/seq.txt") == "/data/run/seq.txt"
    assert is_pooled(ALL_DATASETS) and is_pooled("camera-test (all)") and not is_pooled("camera-test/t01")


@settings(max_examples=25, deadline=None)
@given(st.permutations(range(8)), st.lists(st.floats(0.01, 1e3), min_size=3, max_size=3))
def test_a_board_is_the_same_bit_for_bit_whatever_order_its_cells_finished_in(order: list[int], errors: list[float]) -> None:
    made = Cells()
    for tracker in ("a", "b"):
        for dataset in ("s/S1", "s/S2"):
            for seed in (0, 1):
                made.add(tracker, dataset, seed, ["correct", "false", "missed"], [e * (seed + 1) for e in errors])
    finished = Cells()  # the same cells, stored in another order, as a run with several workers may store them
    for position, index in enumerate(order):
        cell = dict(made.cells[index], id=100 + position)
        finished.cells.append(cell)
        finished.frames += [dict(frame, cell_id=cell["id"]) for frame in made.frames if frame["cell_id"] == index + 1]
    expected, got = made.boards()["camera"], finished.boards()["camera"]
    pd.testing.assert_frame_equal(got, expected, check_exact=True)


def test_seeds_that_agree_frame_for_frame_are_deterministic_whatever_order_their_datasets_finished_in() -> None:
    made = Cells()
    for tracker, declared in (("a", True), ("undeclared", False)):
        made.add(tracker, "s/S1", 0, ["correct", "false"], [1.0, 2.0], deterministic=declared)
        made.add(tracker, "s/S2", 0, ["missed", "correct"], [math.nan, 3.0], deterministic=declared)
        made.add(tracker, "s/S2", 1, ["missed", "correct"], [math.nan, 3.0], deterministic=declared)  # S2 first
        made.add(tracker, "s/S1", 1, ["correct", "false"], [1.0, 2.0], deterministic=declared)
    board = rows(made.boards()["camera"], ALL_DATASETS)
    assert bool(board.loc["a", "deterministic"])
    # Seeds that agree within a run say nothing of the next run: only a tracker that declares it is deterministic.
    assert not board.loc["undeclared", "deterministic"]
    assert board.loc["undeclared", "correct_lo_pct"] == board.loc["undeclared", "correct_hi_pct"]


def following_catalogue():
    from benchmark.metrics.closed_loop import METRICS

    catalogue = CORE
    for metric in METRICS:
        catalogue = catalogue.adding(metric)
    return catalogue


def closed_loop_run(data: Cells, tracker: str, dataset: str, seed: int, offsets: list[float], seen: list[bool],
                    route_m: float = 4.0) -> None:
    """A closed-loop cell of ``tracker``: a frame every 0.5 s, 1 m apart along the route, at ``offsets``."""
    from benchmark.results import LoopValues

    data.add(tracker, dataset, seed, ["correct" if s else "missed" for s in seen], [1.0 if s else math.nan for s in seen])
    for row, offset, in_view in zip(data.frames[-len(seen):], offsets, seen, strict=True):
        index = row["frame"]
        row |= LoopValues(offset, 0.0, float(index), 0.5 * index, in_view, route_m=route_m).columns()


def test_closed_loop_cells_get_a_board_per_suite_ranked_by_distance_followed_then_offset() -> None:
    data = Cells()
    data.add("a", "camera/S1", 0, ["correct", "correct"], [1.0, 1.0])
    lost = [True, False, False, False, False, False, False]  # out of view for over 2 s from frame 5 on
    closed_loop_run(data, "a", "routes/r1", 0, [0.0] * 7, lost, route_m=6.0)
    closed_loop_run(data, "b", "routes/r1", 0, [0.3] * 7, [True] * 7, route_m=6.0)
    closed_loop_run(data, "c", "routes/r1", 0, [0.1] * 7, [True] * 7, route_m=6.0)
    closed_loop_run(data, "c", "routes/r1", 1, [0.2] * 7, [True] * 7, route_m=6.0)
    closed_loop_run(data, "b", "other/r2", 0, [0.0] * 3, [True] * 3, route_m=2.0)
    boards = leaderboards(pd.DataFrame(data.cells), pd.DataFrame(data.frames), MODALITIES, following_catalogue())
    assert list(boards) == ["camera", "camera: other, closed loop", "camera: routes, closed loop"]
    assert "followed_m" not in boards["camera"] and boards["camera"]["dataset"].tolist() == ["(all)", "camera/S1"]
    board = boards["camera: routes, closed loop"]
    metric_columns = [c for c in board.columns if c not in ("rank", "tracker", "dataset", "init", "training", "seeds",
                                                            "frames")]
    assert metric_columns[:6] == ["followed_m", "followed_pct", "offset_mean_m", "offset_max_m", "heading_error_deg",
                                  "followed_sd_m"]
    assert metric_columns.index("correct_pct") > metric_columns.index("followed_sd_m")
    single = rows(board, "routes/r1")
    # b and c follow all 6 m; c is closer to the cable; a lost it after 0 m.
    assert single.index.tolist() == ["c", "b", "a"] and single["rank"].tolist() == [1, 2, 3]
    assert single.loc["c", "seeds"] == 2 and single.loc["c", "offset_mean_m"] == pytest.approx(0.15)
    assert single["followed_pct"].tolist() == pytest.approx([100.0, 100.0, 0.0])
    assert single.loc["c", "followed_sd_m"] == 0.0 and single.loc["c", "correct_pct"] == 100.0
    assert rows(boards["camera: other, closed loop"], "other/r2").loc["b", "followed_m"] == 2.0


def test_a_closed_loop_cell_that_kept_no_frame_stays_on_its_dataset_s_board() -> None:
    data = Cells()
    closed_loop_run(data, "a", "routes/r1", 0, [0.0] * 3, [True] * 3)
    data.add("a", "routes/r1", 1, [], status="error", message="died at once")
    board = leaderboards(pd.DataFrame(data.cells), pd.DataFrame(data.frames), MODALITIES, following_catalogue())
    assert list(board) == ["camera: routes, closed loop"]
    row = rows(board["camera: routes, closed loop"], "routes/r1").loc["a"]
    assert row["seeds"] == 2 and row["status"].startswith("error (1/2 cells)")
