from __future__ import annotations

import json
import sqlite3
from pathlib import Path

import pandas as pd
import pytest

from benchmark.errors import DataError
from benchmark.history.database import RECORDED, CellReplay, History, database_url, shown_location
from benchmark.history.database import _pack as database_pack
from benchmark.leaderboard import load_leaderboards
from benchmark.modalities.camera.modality import CAMERA
from benchmark.results import Picture
from benchmark.store import ResultStore

from ..conftest import Invoke


def record(history: History, out: Path, **overrides: object) -> int:
    with ResultStore(out / "results.sqlite") as results:
        run = results.latest_run()
        assert run is not None
        fields = dict(started="2026-11-01T00:00:00+00:00", version="0.1", commit="abc", machine={"cpu": "x"},
                      machine_key="m1", argv=["trackbench", "nightly"], seeds=2)
        fields.update(overrides)
        return history.record(results, run, {"camera": CAMERA}, **fields)  # type: ignore[arg-type]


def test_a_recorded_run_keeps_cells_metrics_frames_and_pictures(invoke: Invoke, tmp_path: Path) -> None:
    out = tmp_path / "out"
    assert invoke("run", "--tracker", "noisy", "--seeds", "2", "--in-process", "--out", str(out)).exit_code == 0
    with History(tmp_path / "h" / "history.sqlite") as history:
        run_id = record(history, out)
        runs = history.runs()
        assert runs[["id", "commit", "machine_key", "seeds"]].values.tolist() == [[run_id, "abc", "m1", 2]]
        assert runs["machine"].iloc[0] == {"cpu": "x"}
        cells = history.cells([run_id])
        board = pd.read_csv(out / "leaderboard.csv")
        assert set(cells["seed"]) == {0, 1}
        assert {"correct_pct", "false_pct", "missed_pct", "rmse_d_px", "cpu_fps", "wall_fps"} <= set(cells.columns)
        with ResultStore(out / "results.sqlite") as results:
            stored = results.cells()
            first = int(stored["id"].iloc[0])
            expected = results.frame_tables([first]).drop(columns="cell_id")
            pictures = results.pictures([first]).get(first, [])
        same = (cells["dataset_key"] == stored["dataset_key"].iloc[0]) & (cells["seed"] == stored["seed"].iloc[0])
        mine = cells[same]
        frames = history.frames(int(mine["id"].iloc[0]))
        pd.testing.assert_frame_equal(frames, expected, check_dtype=False)
        assert mine["estimated_frames"].iloc[0] == expected["err_d_px"].notna().sum() > 0
        assert history.pictures(int(mine["id"].iloc[0])) == pictures
        pooled = board[(board["tracker"] == "noisy") & (board["dataset"] != "(all)")]
        assert len(pooled) == cells["dataset_key"].nunique()


def test_pictures_round_trip_as_bytes(invoke: Invoke, tmp_path: Path) -> None:
    out = tmp_path / "out"
    assert invoke("run", "--tracker", "blind", "--in-process", "--out", str(out)).exit_code == 0
    with History(tmp_path / "history.sqlite") as history:
        run_id = record(history, out)
        cell = int(history.cells([run_id])["id"].iloc[0])
        pictures = history.pictures(cell)
        assert pictures and all(isinstance(p, Picture) and p.png.startswith(b"\x89PNG") for p in pictures)
        assert {p.outcome for p in pictures} <= {"false", "missed"}


def test_a_runs_changes_are_kept_as_they_were_said_and_replaced_when_said_again(
    invoke: Invoke, tmp_path: Path
) -> None:
    out = tmp_path / "out"
    assert invoke("run", "--tracker", "blind", "--in-process", "--out", str(out)).exit_code == 0
    said = pd.DataFrame(
        {"tracker": ["t"], "metric": ["cpu_fps"], "change": [-12.5], "confirmed": [False], "note": [""]}
    )
    with History(tmp_path / "history.sqlite") as history:
        run_id = record(history, out)
        assert history.changes(run_id) is None
        history.record_changes(run_id, said)
        pd.testing.assert_frame_equal(history.changes(run_id), said)
        history.record_changes(run_id, said.iloc[0:0])
        kept = history.changes(run_id)
        assert kept is not None and kept.empty and list(kept.columns) == list(said.columns)


def test_a_runs_published_boards_are_kept_equal_to_what_was_published(invoke: Invoke, tmp_path: Path) -> None:
    out = tmp_path / "out"
    assert invoke("run", "--tracker", "noisy", "--seeds", "2", "--in-process", "--out", str(out)).exit_code == 0
    with ResultStore(out / "results.sqlite") as results:
        published = load_leaderboards(results, {"camera": CAMERA})
    with History(tmp_path / "history.sqlite") as history:
        without = record(history, out)
        assert history.boards(without) is None
        run_id = record(history, out, boards=published)
        kept = history.boards(run_id)
    assert kept is not None and list(kept) == list(published)
    for modality, board in published.items():
        pd.testing.assert_frame_equal(kept[modality], board)


def test_urls_and_paths() -> None:
    assert database_url("postgresql://u@h/db") == "postgresql://u@h/db"
    assert database_url("x.sqlite").startswith("sqlite:///") and database_url("x.sqlite").endswith("/x.sqlite")


@pytest.mark.parametrize(
    ("location", "shown"),
    [
        ("postgresql://ci:s3cret@db.example:5432/history", "postgresql://ci:***@db.example:5432/history"),
        ("postgresql+psycopg://ci:p%40ss@/h?host=/run/pg", "postgresql+psycopg://ci:***@/h?host=%2Frun%2Fpg"),
        ("postgresql://ci:s3cret@db.example:port/history", "postgresql://ci:***@db.example:port/history"),
        ("postgresql://ci@db.example/history", "postgresql://ci@db.example/history"),
        ("reports/history.sqlite", "reports/history.sqlite"),
    ],
    ids=["password", "encoded password and socket", "unparsable port", "no password", "a file"],
)
def test_a_location_is_shown_with_its_password_masked(location: str, shown: str) -> None:
    assert shown_location(location) == shown


def test_a_drivers_message_quoting_the_url_is_masked_and_on_one_line(monkeypatch: pytest.MonkeyPatch) -> None:
    import sqlalchemy as sa

    def quoting(url: sa.URL) -> sa.Engine:
        raise sa.exc.ArgumentError(f"cannot use\n{url.render_as_string(hide_password=False)} (password p@ss-word)")

    monkeypatch.setattr("benchmark.history.database.sa.create_engine", quoting)
    with pytest.raises(DataError) as caught:
        History("postgresql://ci:p%40ss-word@db.example/history")
    message = str(caught.value)
    assert "p@ss-word" not in message and "p%40ss-word" not in message and "\n" not in message
    assert message.startswith("history database postgresql://ci:***@db.example/history: ArgumentError: cannot use")


def test_the_command_line_is_kept_with_the_passwords_of_its_urls_masked(invoke: Invoke, tmp_path: Path) -> None:
    out = tmp_path / "out"
    assert invoke("run", "--tracker", "perfect", "--in-process", "--out", str(out)).exit_code == 0
    argv = ["trackbench", "nightly", "--history=postgresql://ci:s3cret@db/h", "--scheduler", "tcp://u:pw@host:8786"]
    with History(tmp_path / "history.sqlite") as history:
        record(history, out, argv=argv)
        kept = history.runs()["argv"].iloc[0]
    assert kept == [*argv[:2], "--history=postgresql://ci:***@db/h", "--scheduler", "tcp://u:***@host:8786"]


def test_a_history_whose_folder_cannot_be_made_is_a_data_error_naming_it(tmp_path: Path) -> None:
    (tmp_path / "file").write_text("")
    with pytest.raises(DataError, match="file/history.sqlite: cannot create its folder"):
        History(tmp_path / "file" / "history.sqlite")


def test_a_file_that_is_no_database_is_a_data_error_naming_it(tmp_path: Path) -> None:
    bad = tmp_path / "history.sqlite"
    bad.write_bytes(b"not a database at all" * 100)
    with pytest.raises(DataError, match="history.sqlite"):
        History(bad)


@pytest.mark.parametrize(
    ("table", "message"),
    [("runs (x TEXT)", "its table 'runs' is not a trackbench history's"), ("notes (x TEXT)", "holds other tables \\(notes\\)")],
    ids=["a table of our name", "tables of its own"],
)
def test_another_programs_database_is_refused_and_left_byte_for_byte_unchanged(
    tmp_path: Path, table: str, message: str
) -> None:
    other = tmp_path / "other.sqlite"
    connection = sqlite3.connect(other)
    with connection:
        connection.execute(f"CREATE TABLE {table}")
    connection.close()
    before = other.read_bytes()
    with pytest.raises(DataError, match=f"other.sqlite: {message}.*left unchanged"):
        History(other)
    assert other.read_bytes() == before


def replay_of(cell_id: int, page: bytes = b"<!DOCTYPE html><title>replay</title>") -> CellReplay:
    return CellReplay(cell_id, RECORDED, "", "0:3", "trackbench replay ...", len(page), "d", page)


def test_only_the_latest_runs_keep_frames_pictures_and_replays(
    invoke: Invoke, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setattr("benchmark.history.database.DETAILED_RUNS", 2)
    out = tmp_path / "out"
    assert invoke("run", "--tracker", "blind", "--in-process", "--out", str(out)).exit_code == 0
    with History(tmp_path / "history.sqlite") as history:
        runs = [record(history, out)]
        first = int(history.cells()["id"].iloc[0])
        history.record_replays([replay_of(first)])
        runs += [record(history, out) for _ in range(2)]
        cells = history.cells()
        last = int(cells[cells["run_id"] == runs[-1]]["id"].iloc[0])
        history.record_replays([replay_of(last)])
        assert history.pictures(first) == [] and history.pictures(last)
        with pytest.raises(DataError, match=f"cell {first} "):
            history.frames(first)
        with pytest.raises(DataError, match=f"no replay page of cell {first} "):
            history.replay_page(first)
        assert history.replays()["cell_id"].tolist() == [last]
        assert len(history.frames(last)) > 0 and len(cells) == 3 * len(cells[cells["run_id"] == runs[0]])


def test_a_cells_replay_is_kept_with_its_page_and_replaced_when_said_again(invoke: Invoke, tmp_path: Path) -> None:
    out = tmp_path / "out"
    assert invoke("run", "--tracker", "blind", "--in-process", "--out", str(out)).exit_code == 0
    with History(tmp_path / "history.sqlite") as history:
        record(history, out)
        first, second = (int(cell) for cell in history.cells()["id"].iloc[:2])
        page = bytes(range(256)) * 100
        history.record_replays([replay_of(first, page), CellReplay(second, "over budget", "beyond", "0:9", "c")])
        history.record_replays([replay_of(first, page[::-1])])
        kept = history.replays()
        assert history.replay_page(first) == page[::-1]
        with pytest.raises(DataError, match=f"no replay page of cell {second} "):
            history.replay_page(second)
    assert kept[["cell_id", "state", "why", "frames", "size"]].values.tolist() == [
        [first, RECORDED, "", "0:3", len(page)], [second, "over budget", "beyond", "0:9", 0]
    ]


def test_an_older_history_gets_the_declaration_column_and_keeps_its_cells(invoke: Invoke, tmp_path: Path) -> None:
    out = tmp_path / "out"
    assert invoke("run", "--tracker", "perfect", "--tracker", "noisy", "--in-process", "--out", str(out)).exit_code == 0
    path = tmp_path / "history.sqlite"
    with History(path) as history:
        first = record(history, out)
    connection = sqlite3.connect(path)
    connection.execute("ALTER TABLE cells DROP COLUMN deterministic")  # as a history of trackbench 0.5 has it
    connection.close()
    with History(path) as history:
        second = record(history, out)
        cells = history.cells()
    declared = cells.groupby(["run_id", "tracker"])["deterministic"].all()
    assert not declared[first, "perfect"] and not declared[first, "noisy"]  # cells of old declare nothing
    assert declared[second, "perfect"] and not declared[second, "noisy"]


def test_a_run_keeps_its_load_and_an_older_history_gains_the_column_empty(invoke: Invoke, tmp_path: Path) -> None:
    out = tmp_path / "out"
    assert invoke("run", "--tracker", "perfect", "--in-process", "--out", str(out)).exit_code == 0
    path = tmp_path / "history.sqlite"
    with History(path) as history:
        first = record(history, out)
    connection = sqlite3.connect(path)
    connection.execute("ALTER TABLE runs DROP COLUMN load")  # as a history of trackbench 0.6 has it
    connection.close()
    load = {"cores": 2, "busy_pct": 97.5, "others_pct": 48.0}
    with History(path) as history:
        second = record(history, out, load=load)
        runs = history.runs().set_index("id")
    assert runs.loc[first, "load"] == {} and runs.loc[second, "load"] == load


def test_a_run_recorded_before_the_cpu_timing_reads_its_fps_and_step_times_as_wall_times(
    invoke: Invoke, tmp_path: Path
) -> None:
    out = tmp_path / "out"
    assert invoke("run", "--tracker", "perfect", "--in-process", "--out", str(out)).exit_code == 0
    path = tmp_path / "history.sqlite"
    with History(path) as history:
        run = record(history, out)
        cell_id = int(history.cells([run])["id"].iloc[0])
        frames = history.frames(cell_id)
        fps = float(history.cells([run])["wall_fps"].iloc[0])
    # What an older trackbench wrote: its fps and step_ms timed the wall clock.
    old_frames = frames.drop(columns="step_ms").rename(columns={"wall_ms": "step_ms"})
    connection = sqlite3.connect(path)
    old_metrics = json.dumps({"correct_pct": 100.0, "fps": fps})
    connection.execute("UPDATE cells SET metrics = ? WHERE id = ?", (old_metrics, cell_id))
    connection.execute("UPDATE cell_frames SET frames = ? WHERE cell_id = ?", (database_pack(old_frames), cell_id))
    connection.commit()
    connection.close()
    with History(path) as history:
        cell = history.cells([run]).set_index("id").loc[cell_id]
        read = history.frames(cell_id)
    assert cell["wall_fps"] == fps and pd.isna(cell["cpu_fps"]) and "fps" not in cell.index
    assert read["wall_ms"].tolist() == frames["wall_ms"].tolist() and read["step_ms"].isna().all()
    assert list(read.columns) == list(frames.columns)
