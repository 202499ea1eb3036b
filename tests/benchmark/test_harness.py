"""The run sequence of the harness: select, resume, run, store and publish, without the command line."""

from __future__ import annotations

import dataclasses
import io
import sqlite3
import types
from pathlib import Path

import pandas as pd
import pytest

from benchmark import harness
from benchmark.errors import DataError
from benchmark.harness import describe_result, publish, record_conditions, run_benchmark
from benchmark.progress import Meter, TerminalProgress
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
    shown = io.StringIO()
    progress = TerminalProgress(Meter("cells", stream=shown, enabled=False))
    summary = run_benchmark(cells, registry.modalities, tmp_path, jobs=0, argv=["test"], progress=progress)
    publication = summary.publication
    assert len(stored(tmp_path)) == 6
    lines = shown.getvalue().splitlines()  # a line for each failed cell, and the count at the end
    failed = [["raising", f"fake/{name}", "seed 0", "error"] for name in ("S1", "S2")]
    assert [line.split("  ")[:4] for line in lines[:2]] == failed
    assert lines[2].startswith("cells 6/6, 2 failed, elapsed ") and len(lines) == 3
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
    summary = run_benchmark(cells, registry.modalities, tmp_path, jobs=0, resume=True, log=lines.append)
    publication = summary.publication
    assert summary.statuses == {"ok": 2, "error": 2} and not summary.clean
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


def write_sequence_file(folder: Path, make_image, n_frames: int = 3) -> Path:
    for index in range(n_frames):
        make_image(folder / "frames" / f"f{index}.png")
    rows = "".join(f"{index}.0 0.0 6.0 0.0 # frames/f{index}.png\n" for index in range(n_frames))
    (folder / "seq.txt").write_text(rows)
    return folder / "seq.txt"


def test_resume_matches_a_dataset_by_identity_not_by_the_path_typed(
    registry: Registry, tmp_path: Path, make_image, monkeypatch: pytest.MonkeyPatch
) -> None:
    sequence_file = write_sequence_file(tmp_path / "data", make_image)
    out = tmp_path / "out"

    def run(path: str) -> list[str]:
        lines: list[str] = []
        cells = select_cells(registry, Selection(trackers=("perfect",), datasets=(path,)))
        run_benchmark(cells, registry.modalities, out, jobs=0, resume=True, log=lines.append)
        return lines

    assert run(str(sequence_file))[0] == "resume: 0 cells already finished, 1 to run"
    monkeypatch.chdir(tmp_path / "data" / "frames")
    assert run("../seq.txt")[0] == "resume: 1 cells already finished, 0 to run"
    sequence_file.write_text(sequence_file.read_text().replace("0.0 6.0", "0.1 6.0", 1))
    assert run("../seq.txt")[0] == "resume: 0 cells already finished, 1 to run"
    make_image(tmp_path / "data" / "frames" / "f2.png", width=13)
    assert run("../seq.txt")[0] == "resume: 0 cells already finished, 1 to run"


def test_the_user_s_ctrl_c_keeps_and_publishes_the_finished_cells(
    registry: Registry, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    def interrupted_after_one(cells, **options):
        yield run_cell(list(cells)[0])
        raise KeyboardInterrupt

    monkeypatch.setattr(harness, "run_cells", interrupted_after_one)
    cells = select_cells(registry, Selection(trackers=("perfect", "blind"), suites=("fake",)))
    lines: list[str] = []
    summary = run_benchmark(cells, registry.modalities, tmp_path, log=lines.append)
    assert summary.interrupted and not summary.clean
    assert lines[-1] == "interrupted: 1 cells finished and kept, 3 not run"
    assert [row[1:] for row in stored(tmp_path)] == [("perfect", "fake/S1", "ok")]
    assert "perfect" in (tmp_path / "leaderboard.md").read_text()
    with ResultStore(tmp_path / DATABASE_NAME) as store:
        assert store.runs()["finished"].isna().all()


def test_an_output_folder_that_cannot_be_made_is_an_error_naming_it(registry: Registry, tmp_path: Path) -> None:
    (tmp_path / "file").write_text("not a folder")
    cells = select_cells(registry, Selection(trackers=("perfect",), suites=("fake",)))
    with pytest.raises(DataError, match=r"file/sub: cannot create folder"):
        run_benchmark(cells, registry.modalities, tmp_path / "file" / "sub")


def test_a_run_keeps_conditions_and_publishes_the_board_by_condition(
    fakes: types.ModuleType, tmp_path: Path
) -> None:
    @dataclasses.dataclass(frozen=True)
    class Drawn(fakes.FakeSequence):
        water: str = "I"

        def conditions(self) -> dict[str, object]:
            if self.water == "broken":
                raise RuntimeError("no frame to measure")
            return {"water": self.water}

    registry = fakes.make_registry()
    cells = select_cells(registry, Selection(trackers=("perfect", "blind"), suites=("fake",)))
    sequences = {"fake/S1": Drawn("world/A", 4, water="9C"), "fake/S2": Drawn("world/B", 4, water="broken")}
    cells = [dataclasses.replace(cell, sequence=sequences[cell.sequence.info.name]) for cell in cells]
    lines: list[str] = []
    publication = run_benchmark(cells, registry.modalities, tmp_path, in_process=True, log=lines.append).publication
    assert [path.name for path in publication.files][-2:] == ["conditions.csv", "conditions.md"]
    board = publication.by_condition.set_index("tracker")
    assert board.loc["perfect", "bin"] == "9C" and board.loc["perfect", "correct_pct"] == 100.0
    assert board.loc["blind", "missed_pct"] == 100.0 and set(board["sequences"]) == {1}
    assert any(line.startswith("world/B: its conditions could not be measured (RuntimeError") for line in lines)
    assert "### water" in (tmp_path / "conditions.md").read_text()
    run_benchmark(cells[:0], registry.modalities, tmp_path, in_process=True)
    assert not (tmp_path / "conditions.md").exists()


def test_conditions_the_store_holds_are_not_measured_again(fakes: types.ModuleType, tmp_path: Path) -> None:
    asked: list[str] = []

    @dataclasses.dataclass(frozen=True)
    class Measured(fakes.FakeSequence):
        def conditions(self) -> dict[str, object]:
            asked.append(self.info.name)
            return {"contrast_grey": 40.0}

    registry = fakes.make_registry()
    cells = select_cells(registry, Selection(trackers=("perfect", "blind"), suites=("fake",)))
    sequences = {"fake/S1": Measured("world/A", 4), "fake/S2": Measured("world/B", 4)}
    cells = [dataclasses.replace(cell, sequence=sequences[cell.sequence.info.name]) for cell in cells]
    first = run_benchmark(cells, registry.modalities, tmp_path, in_process=True).publication.by_condition
    assert sorted(asked) == ["world/A", "world/B"]  # once per sequence, not per cell
    second = run_benchmark(cells, registry.modalities, tmp_path, in_process=True).publication.by_condition
    assert sorted(asked) == ["world/A", "world/B"]  # the second run into the folder asks nobody
    assert not first.empty
    pd.testing.assert_frame_equal(first.reset_index(drop=True), second.reset_index(drop=True))


def test_a_tracker_that_needs_what_a_sequence_lacks_is_reported_before_the_run_and_not_run(
    fakes: types.ModuleType, tmp_path: Path
) -> None:
    class Calibrated(fakes.Perfect):
        name = "calibrated"
        needs = ("calibration", "frame_interval_s")

    registry = fakes.make_registry((fakes.Perfect, Calibrated))
    cells = select_cells(registry, Selection(suites=("fake",), seeds=2))
    lines: list[str] = []
    summary = run_benchmark(cells, registry.modalities, tmp_path, jobs=0, log=lines.append)
    expected = [f"calibrated cannot run on fake/{name}: it needs calibration" for name in ("S1", "S2")]
    assert lines[:2] == expected and len(lines) == 2
    assert {row[1] for row in stored(tmp_path)} == {"perfect"}
    assert summary.publication.problems == expected and not summary.clean
    assert summary.statuses == {"ok": 4}
    assert "calibrated cannot run on fake/S1: it needs calibration" in (tmp_path / "leaderboard.md").read_text()


def test_a_cell_on_frames_without_truth_is_described_as_such(registry: Registry, fakes: types.ModuleType) -> None:
    @dataclasses.dataclass(frozen=True)
    class Unlabelled(fakes.FakeSequence):
        def frames(self):
            return (dataclasses.replace(frame, truth=None) for frame in super().frames())

    cell = fakes.make_cell(registry.trackers["blind"], Unlabelled("video", 3))
    line = describe_result(run_cell(cell))
    assert line.startswith("blind  video  seed 0  ok  no truth  ") and "(3 frames," in line


def test_the_sequences_whose_conditions_are_measured_are_counted(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    class Sequence:
        def __init__(self, key: str) -> None:
            self.identity = types.SimpleNamespace(key=key, name=key)
            self.sequence = types.SimpleNamespace(conditions=lambda: {"contrast": 1.0})

    with ResultStore(tmp_path / "results.sqlite") as store:
        record_conditions(store, [Sequence("a"), Sequence("b"), Sequence("a")], lambda line: None)  # type: ignore[list-item]
        assert set(store.conditions(["a", "b"])) == {"a", "b"}
        record_conditions(store, [Sequence("a")], lambda line: None)  # type: ignore[list-item]
    lines = capsys.readouterr().err.splitlines()
    assert len(lines) == 1 and lines[0].startswith("sequences' conditions 2/2")
