"""Tests of benchmark.report.display: boards rounded for reading, columns aligned by type."""

from __future__ import annotations

import math

import pandas as pd
import pytest

from benchmark.report.display import alignment, display_table, format_value


def test_display_rounds_rates_rmses_and_speeds(boards: dict[str, pd.DataFrame]) -> None:
    board = boards["camera"]
    shown = display_table(board).iloc[0]
    assert shown["correct_pct"] == "66.7" and shown["rmse_d_px"] == f"{math.sqrt(14 / 3):.2f}"
    assert shown["cpu_fps"] == "333" and shown["rmse_beta_deg"] == ""
    assert board["correct_pct"].iloc[0] == pytest.approx(200 / 3)  # the board itself keeps full precision


@pytest.mark.parametrize(
    ("column", "value", "text"),
    [
        ("missed_pct", 12.345, "12.3"),
        ("rmse_across_m", 0.125001, "0.13"),
        ("cpu_fps", 1234.5678, "1235"),
        ("wall_fps", 1234.5678, "1235"),
        ("frames", 17, "17"),
        ("status", "error (1/2 cells): x", "error (1/2 cells): x"),
        ("rmse_d_px", math.nan, ""),
        ("tracker", None, ""),
    ],
)
def test_each_kind_of_column_is_rounded_its_way(column: str, value: object, text: str) -> None:
    assert format_value(column, value) == text


def test_numbers_align_right_and_text_left() -> None:
    board = pd.DataFrame({"tracker": ["a"], "rank": [1], "correct_pct": [50.0], "status": ["ok"]})
    assert alignment(board) == ["left", "right", "right", "left"]
    assert display_table(board).dtypes.tolist() == [object] * 4


def _cells_and_frames(outcomes: dict[tuple[str, str], list[object]]) -> tuple[pd.DataFrame, pd.DataFrame]:
    """Cells of tracker ``a`` by (dataset, status), with frames of the given outcomes (None: no truth), 2 ms a step."""
    cells, frames = [], []
    for cell_id, ((dataset, status), frame_outcomes) in enumerate(outcomes.items(), start=1):
        cells.append(
            {"id": cell_id, "tracker": "a", "tracker_key": "k", "dataset": dataset, "dataset_key": dataset,
             "modality": "camera", "seed": 0, "init": "truth", "status": status, "message": ""}
        )
        frames += [
            {"cell_id": cell_id, "frame": index, "outcome": outcome, "step_ms": 2.0, "wall_ms": 4.0,
             "err_d_px": math.nan, "err_alpha_deg": math.nan, "err_w_px": math.nan, "err_beta_deg": math.nan}
            for index, outcome in enumerate(frame_outcomes)
        ]
    return pd.DataFrame(cells), pd.DataFrame(frames)


def test_a_row_without_truth_says_so_where_its_rates_would_be_and_keeps_its_speed() -> None:
    from benchmark.leaderboard import leaderboards
    from benchmark.modalities.camera.modality import CAMERA

    cells, frames = _cells_and_frames(
        {("video", "ok"): [None, None], ("labelled", "ok"): ["correct", "false"], ("broken", "error"): []}
    )
    board = leaderboards(cells, frames, {"camera": CAMERA})["camera"]
    shown = display_table(board).set_index(board["dataset"])
    assert shown.loc["video", ["correct_pct", "false_pct", "missed_pct"]].tolist() == ["no truth"] * 3
    assert shown.loc["video", ["cpu_fps", "wall_fps", "frames"]].tolist() == ["500", "250", "0"]
    assert shown.loc["labelled", ["correct_pct", "false_pct"]].tolist() == ["50.0", "50.0"]
    assert shown.loc["broken", "correct_pct"] == ""  # a cell that failed before any frame is not a row without truth
    assert shown.loc["(all)", "correct_pct"] == "50.0"
    assert math.isnan(board.set_index("dataset").loc["video", "correct_pct"])  # the board keeps NaN
