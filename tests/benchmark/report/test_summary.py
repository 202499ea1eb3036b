"""Tests of benchmark.report.summary: one row per tracker and board, as wide as the terminal."""

from __future__ import annotations

from pathlib import Path

import pandas as pd
import pytest

from benchmark.metrics import CORE, Effect, Metric
from benchmark.report.summary import board_summary, summary_metrics, summary_text


def camera_board() -> pd.DataFrame:
    """A ranked board of two trackers over two datasets and two seeds; one cell of ``b`` failed."""
    rows = []
    for tracker, correct, status in (("a-rather-long-tracker-name", 91.25, "ok"), ("b", 40.0, "error (1/4 cells): x")):
        for dataset in ("(all)", "fake/S1", "fake/S2"):
            rows.append(
                {"rank": 1, "tracker": tracker, "dataset": dataset, "init": "truth", "seeds": 2,
                 "correct_pct": correct, "false_pct": 1.0, "rmse_d_px": 3.14159, "rmse_w_px": 2.0, "cpu_fps": 1234.4, "wall_fps": 987.6,
                 "status": status if dataset != "fake/S1" else "ok"}
            )
    return pd.DataFrame(rows)


def test_a_row_per_tracker_with_the_headline_metrics_the_speed_and_the_failed_cells() -> None:
    lines = board_summary(camera_board(), "camera", 120)
    assert lines[0] == "camera: 2 trackers over 2 datasets"
    assert lines[1].split() == ["tracker", "correct_pct", "rmse_d_px", "cpu_fps", "wall_fps", "failed_cells"]
    assert lines[2].split() == ["a-rather-long-tracker-name", "91.2", "3.14", "1234", "988", "0/4"]
    assert lines[3].split() == ["b", "40.0", "3.14", "1234", "988", "1/4"]
    assert len(lines) == 4  # one row per tracker: the per-dataset rows are in the full board


def test_a_narrow_terminal_shortens_names_then_leaves_out_columns_from_the_right() -> None:
    for width in (60, 40, 30):
        lines = board_summary(camera_board(), "camera", width)
        assert max(map(len, lines)) <= width
    narrow = board_summary(camera_board(), "camera", 40)
    assert narrow[2].startswith("a-rather-long-t… ") and narrow[-1] == "(too narrow for cpu_fps, wall_fps, fail…"
    assert narrow[1].split()[:3] == ["tracker", "correct_pct", "rmse_d_px"]


def test_the_columns_come_from_the_catalogue_so_an_added_headline_metric_shows_by_itself() -> None:
    steadiness = Metric(
        name="steadiness_pct", better="higher", kind="robustness", columns=("outcome",),
        sums=lambda frames, scale: None, value=lambda sums, scale: None, digits=0,
        minimum_effect=Effect(1.0), headline=True,
    )
    metrics = CORE.adding(steadiness)
    board = camera_board().assign(steadiness_pct=99.6)
    assert [metric.name for metric in summary_metrics(board, "camera", metrics)] == [
        "correct_pct", "rmse_d_px", "cpu_fps", "wall_fps", "steadiness_pct"
    ]
    assert board_summary(board, "camera", 120, metrics)[3].split()[-2:] == ["1/4", "100"]
    assert "steadiness_pct" not in board_summary(board, "camera", 120)[1]  # not in the core catalogue


def test_the_text_names_the_files_of_the_full_boards_and_the_problems() -> None:
    files = [Path("reports/latest/leaderboard.md"), Path("reports/latest/leaderboard.csv")]
    text = summary_text({"camera": camera_board()}, files, ["plugin 'x' left out\nbecause"], width=80)
    assert "  reports/latest/leaderboard.md\n  reports/latest/leaderboard.csv" in text
    assert "- plugin 'x' left out because" in text
    assert summary_text({}, width=80) == "No results."


@pytest.mark.parametrize("columns", ["80", "100"])
def test_the_width_is_the_terminal_s(monkeypatch: pytest.MonkeyPatch, columns: str) -> None:
    monkeypatch.setenv("COLUMNS", columns)
    text = summary_text({"camera": camera_board()})
    assert max(map(len, text.splitlines())) <= int(columns)
