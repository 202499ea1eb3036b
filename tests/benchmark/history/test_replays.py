"""The nightly's replays of its failed cells: which cells, which frames, the budget, and failures that fail nothing."""

from __future__ import annotations

import json
import re
import shutil
from pathlib import Path

import pandas as pd
import pytest

import benchmark.history.replays as replays
import benchmark.replay.views as views
from benchmark.cli import EXIT_FAILED
from benchmark.history.database import RECORDED, History
from benchmark.history.replays import (
    FAILED_FRAMES,
    FRAMES_AFTER,
    FRAMES_BEFORE,
    NOT_OK,
    REGRESSION,
    replay_command,
    replay_order,
    replay_window,
)
from benchmark.replay.record import FrameRange

from ..conftest import Invoke

COMMAND = "trackbench replay --tracker raising --dataset fake/S1 --seed 0 --init truth --frames 0:3"
"""The command of the replay of ``raising`` on ``fake/S1``: it raises at frame 3, so the frames before it."""


def nightly(invoke: Invoke, tmp_path: Path, *extra: str):  # noqa: ANN201
    return invoke(
        "nightly", "--tracker", "raising", "--tracker", "perfect", "--dataset", "fake/S1", "--in-process",
        "--out", str(tmp_path / "out"), "--history", str(tmp_path / "history.sqlite"),
        "--site", str(tmp_path / "site"), *extra,
    )


def kept(tmp_path: Path) -> tuple[pd.DataFrame, pd.DataFrame]:
    """The history's cells and replays."""
    with History(tmp_path / "history.sqlite") as history:
        return history.cells(), history.replays()


def raising_cell(cells: pd.DataFrame, run_id: int = 1) -> int:
    return int(cells[(cells["tracker"] == "raising") & (cells["run_id"] == run_id)]["id"].iloc[0])


def test_a_failed_cell_gets_a_replay_linked_both_ways_and_kept_with_its_run(invoke: Invoke, tmp_path: Path) -> None:
    first = nightly(invoke, tmp_path)
    assert first.exit_code == EXIT_FAILED, first.output
    assert "replays: 1 page (" in first.stderr and "kB of the 50.0 MB budget" in first.stderr
    cells, rows = kept(tmp_path)
    cell_id = raising_cell(cells)
    assert rows[["cell_id", "state", "frames", "command"]].values.tolist() == [[cell_id, RECORDED, "0:3", COMMAND]]
    site = tmp_path / "site"
    page = (site / "cells" / f"{cell_id}.html").read_text()
    assert f'href="../replays/1/{cell_id}.html"' in page and COMMAND in page and "Watch frames 0\u20132" in page
    replay = site / "replays" / "1" / f"{cell_id}.html"
    html = replay.read_text()
    assert f'href="../../cells/{cell_id}.html"' in html
    data = json.loads(re.search(r'<script type="application/json"[^>]*>(.*?)</script>', html, re.S)[1])
    assert [frame["index"] for frame in data["frames"]] == [0, 1, 2] and data["tracker"] == "raising"
    assert int(rows["size"].iloc[0]) == len(html.encode())
    perfect = int(cells[cells["tracker"] == "perfect"]["id"].iloc[0])
    assert "Replay" not in (site / "cells" / f"{perfect}.html").read_text()  # nothing failed: nothing to watch

    inode = replay.stat().st_ino
    second = nightly(invoke, tmp_path)
    assert second.exit_code == EXIT_FAILED, second.output
    assert replay.read_text() == html and replay.stat().st_ino == inode  # the first run's page, linked as it was
    later = raising_cell(kept(tmp_path)[0], run_id=2)
    assert (site / "replays" / "2" / f"{later}.html").is_file()

    shutil.rmtree(site)  # the history alone makes the site again, replays included
    rebuilt = invoke("report", "--history", str(tmp_path / "history.sqlite"), "--site", str(site))
    assert rebuilt.exit_code == 0, rebuilt.output
    assert replay.read_text() == html and f'href="../replays/1/{cell_id}.html"' in page


def test_the_budget_stops_replays_and_the_page_shows_the_command_instead(invoke: Invoke, tmp_path: Path) -> None:
    result = nightly(invoke, tmp_path, "--replay-budget", "1kB")
    assert result.exit_code == EXIT_FAILED, result.output
    assert "replays: 0 pages (0 B of the 1 kB budget); without a page: 1 over budget" in result.stderr
    cells, rows = kept(tmp_path)
    assert rows["state"].tolist() == ["over budget"] and rows["size"].tolist() == [0]
    page = (tmp_path / "site" / "cells" / f"{raising_cell(cells)}.html").read_text()
    assert "beyond the night&#39;s replay budget" in page and COMMAND in page and "../replays/" not in page
    assert not (tmp_path / "site" / "replays").exists() or not any((tmp_path / "site" / "replays").rglob("*.html"))


def test_a_budget_of_zero_records_nothing(invoke: Invoke, tmp_path: Path) -> None:
    result = nightly(invoke, tmp_path, "--replay-budget", "0")
    assert result.exit_code == EXIT_FAILED, result.output
    assert "replays:" not in result.stderr and kept(tmp_path)[1].empty


def test_a_size_that_is_no_size_is_refused(invoke: Invoke, tmp_path: Path) -> None:
    result = nightly(invoke, tmp_path, "--replay-budget", "lots")
    assert result.exit_code == 2 and "'lots' is not a size" in result.output
    assert not (tmp_path / "out").exists()


def test_a_replay_that_raises_is_a_line_and_a_reason_and_the_exit_status_stays(
    invoke: Invoke, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    def broken(*args: object) -> bytes:
        raise MemoryError("no room for the frames")

    monkeypatch.setattr(replays, "_page", broken)
    result = nightly(invoke, tmp_path)
    assert result.exit_code == EXIT_FAILED, result.output
    cells, rows = kept(tmp_path)
    cell_id = raising_cell(cells)
    line = f"replay of raising on fake/S1, seed 0 (cell #{cell_id}) failed: MemoryError: no room for the frames"
    assert line in result.stderr
    assert rows["state"].tolist() == ["failed"]
    page = (tmp_path / "site" / "cells" / f"{cell_id}.html").read_text()
    assert "recording the replay failed: MemoryError: no room for the frames" in page and COMMAND in page


def test_a_modality_without_a_view_shows_why_and_the_command(
    invoke: Invoke, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setattr(views, "_views", lambda: {})
    result = nightly(invoke, tmp_path)
    assert result.exit_code == EXIT_FAILED, result.output
    assert "failed:" not in result.stderr  # not a failure: a view still to come
    cells, rows = kept(tmp_path)
    assert rows["state"].tolist() == ["no view"]
    page = (tmp_path / "site" / "cells" / f"{raising_cell(cells)}.html").read_text()
    assert "replay cannot show camera frames yet" in page and COMMAND in page


def test_a_cell_that_ran_out_of_time_is_replayed_up_to_the_frame_it_stopped_at(
    invoke: Invoke, tmp_path: Path
) -> None:
    result = invoke(
        "nightly", "--tracker", "sleepy", "--dataset", "fake/S2", "--param", "sleepy.from_frame=2",
        "--param", "sleepy.sleep_s=1", "--timeout", "0.5", "--in-process", "--out", str(tmp_path / "out"),
        "--history", str(tmp_path / "history.sqlite"), "--site", str(tmp_path / "site"),
    )
    assert result.exit_code == EXIT_FAILED, result.output
    cells, rows = kept(tmp_path)
    assert cells["status"].tolist() == ["timeout"] and 0 < cells["frames"].iloc[0] < 6
    assert rows[["state", "frames"]].values.tolist() == [[RECORDED, f"0:{cells['frames'].iloc[0]}"]]


class Frames:
    """A history of frame tables only, for :func:`replay_order`."""

    def __init__(self, outcomes: dict[int, str]) -> None:
        self.outcomes = outcomes

    def frames(self, cell_id: int) -> pd.DataFrame:
        outcomes = list(self.outcomes[cell_id])
        return pd.DataFrame({"frame": range(len(outcomes)),
                             "outcome": [{"c": "correct", "f": "false", "m": "missed"}[o] for o in outcomes]})


def test_the_order_is_not_ok_then_regressions_then_most_failed_frames() -> None:
    outcomes = {1: "ccff", 2: "cccc", 3: "cfmmc", 4: "cfcc", 5: "cc", 6: "mmmcc", 7: ""}
    cells = pd.DataFrame({
        "id": [1, 2, 3, 4, 5, 6, 7],
        "tracker": ["a", "a", "b", "c", "d", "c", "e"],
        "dataset": ["S1", "S2", "S1", "S1", "S1", "S2", "S1"],
        "status": ["ok", "ok", "ok", "ok", "error", "ok", "timeout"],
        "false_pct": [50.0, 0.0, 20.0, 25.0, 0.0, 0.0, float("nan")],
        "missed_pct": [0.0, 0.0, 40.0, 0.0, 0.0, 60.0, float("nan")],
    })
    changes = pd.DataFrame({"tracker": ["a", "a", "c"], "dataset": ["S2", "S1", "S1"],
                            "kind": ["accuracy", "accuracy", "speed"],
                            "verdict": ["regression", "improvement", "regression"]})
    order = replay_order(Frames(outcomes), cells, changes)  # type: ignore[arg-type]
    shown = [(int(c.cell["id"]), c.priority, c.failed_frames, c.frames) for c in order]
    assert shown == [
        (5, NOT_OK, 0, FrameRange(0, 2)),
        (7, NOT_OK, 0, None),  # stopped before its first frame
        (2, REGRESSION, 0, FrameRange(0, 4)),  # no frame failed: from the first, within the frames it ran
        (3, FAILED_FRAMES, 3, FrameRange(0, 5)),
        (6, FAILED_FRAMES, 3, FrameRange(0, 5)),
        (1, FAILED_FRAMES, 2, FrameRange(0, 4)),
        (4, FAILED_FRAMES, 1, FrameRange(0, 4)),
    ]


def test_the_window_is_around_the_first_failed_frame_or_before_the_fault() -> None:
    frames = pd.DataFrame({"frame": range(200), "outcome": ["correct"] * 100 + ["missed"] * 100})
    assert replay_window(frames, "ok") == FrameRange(100 - FRAMES_BEFORE, 100 + FRAMES_AFTER + 1)
    assert replay_window(frames, "error") == FrameRange(200 - FRAMES_BEFORE, 200)
    assert replay_window(frames.iloc[:100], "ok") == FrameRange(0, FRAMES_BEFORE + FRAMES_AFTER + 1)
    assert replay_window(frames.iloc[:130], "ok") == FrameRange(100 - FRAMES_BEFORE, 130)
    assert replay_window(frames.iloc[:0], "timeout") is None


def test_the_command_is_quoted_for_a_shell() -> None:
    cell = {"tracker": "a b", "dataset": "my files/seq.txt", "seed": 2, "init": "none"}
    assert replay_command(cell, FrameRange(3, 9)) == (
        "trackbench replay --tracker 'a b' --dataset 'my files/seq.txt' --seed 2 --init none --frames 3:9"
    )
