"""The run sequence of the harness: select, resume, run, store and publish, without the command line."""

from __future__ import annotations

import sqlite3
import types
from pathlib import Path

import pytest

from benchmark.harness import describe_result, publish, run_benchmark
from benchmark.registry import Registry
from benchmark.runner import run_cell
from benchmark.selection import Selection, select_cells
from benchmark.store import DATABASE_NAME, ResultStore


@pytest.fixture
def registry(fakes: types.ModuleType) -> Registry:
    return fakes.make_registry()


def stored(out: Path) -> list[tuple]:
    with sqlite3.connect(out / DATABASE_NAME) as connection:
        return connection.execute("SELECT run_id, tracker, dataset, status FROM cells ORDER BY id").fetchall()


def test_a_run_stores_every_cell_and_publishes_one_board_per_modality(registry: Registry, tmp_path: Path) -> None:
    cells = select_cells(registry, Selection(trackers=("perfect", "blind", "raising"), suites=("fake",)))
    lines: list[str] = []
    publication = run_benchmark(cells, registry.modalities, tmp_path, jobs=0, argv=["test"], log=lines.append)
    assert len(stored(tmp_path)) == 6 and len(lines) == 6
    assert sorted(publication.boards) == ["camera"]
    board = publication.boards["camera"]
    overall = board[board["dataset"] == "(all)"].set_index("tracker")
    assert overall.loc["perfect", "correct_pct"] == 100.0 and overall.loc["blind", "missed_pct"] == 100.0
    assert overall.loc["raising", "status"].startswith("error (2/2 cells): RuntimeError: lost the cable")
    assert [path.name for path in publication.files] == ["leaderboard.csv", "leaderboard.md", "leaderboard.html"]
    assert all(path.is_file() for path in publication.files)
    assert publication.run_id == 1


def test_resume_takes_over_finished_cells_and_runs_only_the_rest(registry: Registry, tmp_path: Path) -> None:
    cells = select_cells(registry, Selection(trackers=("perfect", "raising"), suites=("fake",)))
    run_benchmark(cells, registry.modalities, tmp_path, jobs=0)
    lines: list[str] = []
    publication = run_benchmark(cells, registry.modalities, tmp_path, jobs=0, resume=True, log=lines.append)
    assert lines[0] == "resume: 2 cells already finished, 2 to run"
    assert [row[1] for row in stored(tmp_path) if row[0] == 2] == ["raising", "raising"]
    board = publication.boards["camera"]
    assert set(board["tracker"]) == {"perfect", "raising"}
    assert publication.run_id == 2


def test_publish_reranks_a_stored_run_or_every_run(registry: Registry, tmp_path: Path) -> None:
    run_benchmark(select_cells(registry, Selection(trackers=("perfect",))), registry.modalities, tmp_path, jobs=0)
    run_benchmark(select_cells(registry, Selection(trackers=("blind",))), registry.modalities, tmp_path, jobs=0)
    out = tmp_path / "again"
    with ResultStore(tmp_path / DATABASE_NAME) as store:
        latest = publish(store, registry.modalities, out)
        everything = publish(store, registry.modalities, out, all_runs=True)
    assert latest.run_id == 2 and set(latest.boards["camera"]["tracker"]) == {"blind"}
    assert everything.run_id is None and set(everything.boards["camera"]["tracker"]) == {"perfect", "blind"}
    assert "All runs of" in (out / "leaderboard.md").read_text()


def test_a_finished_cell_is_described_in_one_line(registry: Registry, fakes: types.ModuleType) -> None:
    (cell,) = select_cells(registry, Selection(trackers=("raising",), datasets=("fake/S2",)))
    line = describe_result(run_cell(cell))
    assert line.startswith("raising  fake/S2  seed 0  error  correct 100.0%")
    assert "(3 frames," in line and line.endswith("RuntimeError: lost the cable (frame 3)")
