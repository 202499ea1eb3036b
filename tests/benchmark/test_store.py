"""Tests of benchmark.store: one transaction per cell, nothing finished is lost, damage is reported."""

from __future__ import annotations

import dataclasses
import math
import os
import sqlite3
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from benchmark import schema
from benchmark.errors import DataError
from benchmark.model import Outcome
from benchmark.results import LOOP_PREFIX, CellKey, CellResult, FrameScore, LoopValues, Picture
from benchmark.store import CELL_COLUMNS, SCHEMA_VERSION, ResultStore

ERRORS = ("err_d_px", "err_alpha_deg", "err_w_px", "err_beta_deg")
DATASET_KEY = "0123456789abcdef0123456789abcdef"


def make_result(
    tracker: str,
    outcomes: list[Outcome | None],
    status: str = "ok",
    message: str = "",
    dataset: str = "fake/S1",
    dataset_key: str = DATASET_KEY,
    seed: int = 1,
) -> CellResult:
    """A camera cell whose frame ``i`` has errors ``i + 1`` (``nan`` where the frame was missed)."""
    scores = tuple(
        FrameScore(
            index,
            outcome,
            {name: math.nan if outcome is Outcome.MISSED else (index + 1) / (position + 1)
             for position, name in enumerate(ERRORS)},
            0.002 * (index + 1),
        )
        for index, outcome in enumerate(outcomes)
    )
    return CellResult(
        tracker=tracker,
        tracker_version="1.0",
        tracker_key=f"key-{tracker}",
        params={"sigma_px": 4.0},
        dataset=dataset,
        dataset_key=dataset_key,
        modality="camera",
        seed=seed,
        init="truth",
        status=status,  # type: ignore[arg-type]
        message=message,
        scores=scores,
        elapsed_s=0.5,
        error_columns=ERRORS,
    )


@pytest.fixture
def results() -> dict[str, CellResult]:
    """A noisy (ok), a raising (error) and a blind (ok, nothing detected) cell."""
    correct, false, missed = Outcome.CORRECT, Outcome.FALSE, Outcome.MISSED
    return {
        "noisy": make_result("noisy", [correct, false, missed, correct, None, correct, correct, missed, false, false]),
        "raising": make_result(
            "raising", [correct, correct, correct], status="error", message="RuntimeError: lost the cable (frame 3)"
        ),
        "blind": make_result("blind", [missed] * 10),
    }


def test_a_cell_round_trips_with_its_frames(tmp_path: Path, results: dict[str, CellResult]) -> None:
    noisy = results["noisy"]
    with ResultStore(tmp_path / "r.sqlite") as store:
        run = store.start_run(["trackbench", "run"], {"seeds": 1})
        cell_id = store.add_cell(run, noisy)
        cells = store.cells(run)
        frames = store.frame_tables([cell_id])
    assert list(cells.columns) == list(CELL_COLUMNS)
    row = cells.iloc[0]
    assert (row["tracker"], row["dataset"], row["dataset_key"], row["seed"], row["status"]) == (
        "noisy", "fake/S1", DATASET_KEY, 1, "ok"
    )
    assert row["tracker_key"] == noisy.tracker_key and row["frames"] == len(noisy.scores)
    expected = noisy.frames
    assert frames["frame"].tolist() == expected["frame"].tolist()
    assert frames["outcome"].tolist() == expected["outcome"].tolist()
    for column in (*ERRORS, "step_ms", "wall_ms"):
        np.testing.assert_allclose(frames[column].to_numpy(float), expected[column].to_numpy(float), equal_nan=True)


def test_the_loop_values_of_a_closed_loop_cell_round_trip_and_open_loop_cells_get_no_loop_columns(
    tmp_path: Path, results: dict[str, CellResult]
) -> None:
    noisy = results["noisy"]
    loops = [LoopValues(0.01 * i - 0.03, 2.0 - i, 0.018 * i, 0.04 * i, i % 3 != 0) for i in range(len(noisy.scores))]
    steered = dataclasses.replace(
        noisy, scores=tuple(dataclasses.replace(s, loop=v) for s, v in zip(noisy.scores, loops, strict=True))
    )
    with ResultStore(tmp_path / "r.sqlite") as store:
        run = store.start_run([], {})
        steered_id, open_id = store.add_cell(run, steered), store.add_cell(run, noisy)
        frames = store.frame_tables([steered_id])
        open_frames = store.frame_tables([open_id])
        both = store.frame_tables([steered_id, open_id])
    expected = steered.frames
    loop_columns = [column for column in expected.columns if column.startswith(LOOP_PREFIX)]
    assert loop_columns == ["loop_offset_m", "loop_heading_error_deg", "loop_along_m", "loop_time_s", "loop_in_view"]
    assert sorted(frames.columns) == sorted(["cell_id", *expected.columns])
    for column in (*ERRORS, *loop_columns):
        np.testing.assert_array_equal(frames[column].to_numpy(float), expected[column].to_numpy(float))
    assert frames["loop_in_view"].tolist() == [float(v.in_view) for v in loops]
    assert not [column for column in open_frames.columns if column.startswith(LOOP_PREFIX)]
    assert both[both["cell_id"] == open_id][loop_columns].isna().all().all()


def test_nan_errors_come_back_as_nan(tmp_path: Path, results: dict[str, CellResult]) -> None:
    with ResultStore(tmp_path / "r.sqlite") as store:
        run = store.start_run([], {})
        frames = store.frame_tables([store.add_cell(run, results["blind"])])
    assert frames["outcome"].tolist() == ["missed"] * 10
    assert "err_d_px" not in frames or frames["err_d_px"].isna().all()


def test_cells_of_an_interrupted_run_survive_reopening(tmp_path: Path, results: dict[str, CellResult]) -> None:
    path = tmp_path / "r.sqlite"
    store = ResultStore(path)
    run = store.start_run(["trackbench", "run"], {})
    ids = [store.add_cell(run, results["noisy"]), store.add_cell(run, results["raising"])]
    store.close()  # killed: finish_run never called

    with ResultStore(path) as reopened:
        assert reopened.latest_run() == run
        assert reopened.runs()["finished"].isna().tolist() == [True]
        assert reopened.cells()["id"].tolist() == ids
        assert len(reopened.frame_tables(ids)) == len(results["noisy"].scores) + len(results["raising"].scores)
        found = reopened.find_ok_cells([results["noisy"].key, results["raising"].key])
    assert found == {results["noisy"].key: ids[0]}


def test_a_failing_write_leaves_no_partial_cell(tmp_path: Path, results: dict[str, CellResult]) -> None:
    good = results["noisy"]
    broken_scores = (*good.scores[:3], FrameScore("not an int", Outcome.CORRECT, {}, 0.0))  # type: ignore[arg-type]
    broken = dataclasses.replace(good, scores=broken_scores)
    with ResultStore(tmp_path / "r.sqlite") as store:
        run = store.start_run([], {})
        with pytest.raises(ValueError):
            store.add_cell(run, broken)
        assert store.cells(all_runs=True).empty
        assert store.frame_tables(range(1, 10)).empty
        store.add_cell(run, good)
        assert len(store.cells(run)) == 1


PICTURES = (Picture(1, "false", b"\x89PNG first"), Picture(2, "missed", b"\x89PNG second\x00\xff"))


def test_pictures_round_trip_with_their_cell_in_frame_order(tmp_path: Path, results: dict[str, CellResult]) -> None:
    pictured = dataclasses.replace(results["noisy"], pictures=PICTURES[::-1])
    with ResultStore(tmp_path / "r.sqlite") as store:
        run = store.start_run([], {})
        pictured_id = store.add_cell(run, pictured)
        bare_id = store.add_cell(run, results["blind"])
        assert store.pictures([pictured_id, bare_id, 999]) == {pictured_id: list(PICTURES)}
    with ResultStore(tmp_path / "r.sqlite") as reopened:
        (stored,) = reopened.pictures(range(1, 3)).values()
    assert [type(picture.png) for picture in stored] == [bytes, bytes] and stored == list(PICTURES)


def test_a_failing_write_leaves_no_pictures_behind(tmp_path: Path, results: dict[str, CellResult]) -> None:
    good = dataclasses.replace(results["noisy"], pictures=PICTURES)
    broken = dataclasses.replace(good, pictures=(*PICTURES, Picture("not an int", "false", b"")))  # type: ignore[arg-type]
    with ResultStore(tmp_path / "r.sqlite") as store:
        run = store.start_run([], {})
        with pytest.raises(ValueError):
            store.add_cell(run, broken)
        assert store.cells(all_runs=True).empty and store.pictures(range(1, 10)) == {}
        cell_id = store.add_cell(run, good)
        assert store.pictures([cell_id]) == {cell_id: list(PICTURES)}


def test_a_run_shows_its_own_and_its_resumed_cells_latest_per_key(
    tmp_path: Path, results: dict[str, CellResult]
) -> None:
    noisy, raising, blind = results["noisy"], results["raising"], results["blind"]
    with ResultStore(tmp_path / "r.sqlite") as store:
        first = store.start_run([], {})
        noisy_id = store.add_cell(first, noisy)
        store.add_cell(first, raising)
        store.add_cell(first, blind)
        second = store.start_run([], {})
        store.reuse_cells(second, [noisy_id])
        redo_id = store.add_cell(second, raising)
        assert sorted(store.cells(second)["id"]) == sorted([noisy_id, redo_id])
        assert store.cells()["id"].tolist() == store.cells(second)["id"].tolist()
        everything = store.cells(all_runs=True)
        assert len(everything) == 3 and redo_id in everything["id"].tolist()
        assert store.runs()["cells"].tolist() == [3, 2]


def test_resume_lookup_prefers_the_latest_ok_cell_and_ignores_failures(
    tmp_path: Path, results: dict[str, CellResult]
) -> None:
    with ResultStore(tmp_path / "r.sqlite") as store:
        run = store.start_run([], {})
        store.add_cell(run, results["noisy"])
        latest = store.add_cell(run, results["noisy"])
        store.add_cell(run, results["raising"])
        other_seed = results["noisy"].key._replace(seed=99)
        found = store.find_ok_cells([results["noisy"].key, results["raising"].key, other_seed])
    assert found == {results["noisy"].key: latest}


def test_cells_are_matched_and_kept_by_the_datasets_key_not_its_name(
    tmp_path: Path, results: dict[str, CellResult]
) -> None:
    noisy = results["noisy"]
    edited = dataclasses.replace(noisy, dataset_key="f" * 32)
    elsewhere = dataclasses.replace(noisy, dataset="../fake/S1")
    with ResultStore(tmp_path / "r.sqlite") as store:
        run = store.start_run([], {})
        original_id = store.add_cell(run, noisy)
        edited_id = store.add_cell(run, edited)
        assert store.find_ok_cells([elsewhere.key, edited.key._replace(dataset_key="e" * 32)]) == {
            elsewhere.key: original_id
        }
        assert store.cells(run)["id"].tolist() == [original_id, edited_id]
        elsewhere_id = store.add_cell(run, elsewhere)
        kept = store.cells(run)
    assert kept["id"].tolist() == [edited_id, elsewhere_id]
    assert kept["dataset"].tolist() == ["fake/S1", "../fake/S1"]


def test_run_problems_are_stored_with_their_run(tmp_path: Path, results: dict[str, CellResult]) -> None:
    problem = "plugin 'acme' (acme-dist 1.0) failed to import: ImportError: No module named 'acme'"
    with ResultStore(tmp_path / "r.sqlite") as store:
        assert store.run_problems() == []
        troubled = store.start_run([], {}, problems=[problem])
        store.add_cell(troubled, results["noisy"])
        killed = store.start_run([], {})  # no cell yet: not the latest run with cells
        assert store.run_problems() == [problem]
        assert store.run_problems(troubled) == [problem]
        assert store.run_problems(killed) == []
        assert store.runs()["problems"].tolist() == [f'["{problem}"]', "[]"]


def test_a_foreign_file_or_schema_is_a_clear_error(tmp_path: Path) -> None:
    junk = tmp_path / "junk.sqlite"
    junk.write_bytes(b"this is not a database at all" * 100)
    with pytest.raises(DataError, match="junk.sqlite: the results database is damaged"):
        ResultStore(junk)
    future = tmp_path / "future.sqlite"
    with sqlite3.connect(future) as connection:
        connection.execute("PRAGMA user_version = 99")
    with pytest.raises(DataError, match="schema version 99"):
        ResultStore(future)


def test_another_programs_database_is_refused_and_left_untouched(tmp_path: Path) -> None:
    foreign = tmp_path / "notes.sqlite"
    connection = sqlite3.connect(foreign)
    with connection:
        connection.execute("CREATE TABLE notes (id INTEGER PRIMARY KEY, text TEXT)")
        connection.execute("INSERT INTO notes (text) VALUES ('keep me')")
    connection.close()
    before = foreign.read_bytes()
    refused = r"notes\.sqlite: not a trackbench results database \(it holds the tables notes\) and was left unchanged"
    with pytest.raises(DataError, match=refused):
        ResultStore(foreign)
    assert foreign.read_bytes() == before
    assert sorted(path.name for path in tmp_path.iterdir()) == ["notes.sqlite"]


def test_an_empty_file_becomes_a_new_database(tmp_path: Path, results: dict[str, CellResult]) -> None:
    path = tmp_path / "r.sqlite"
    path.touch()
    with ResultStore(path) as store:
        assert store.cells().empty
        store.add_cell(store.start_run([], {}), results["noisy"])
    with ResultStore(path) as store:
        assert len(store.cells()) == 1


V1_SCHEMA = """
CREATE TABLE runs (
    id INTEGER PRIMARY KEY, started TEXT NOT NULL, finished TEXT, argv TEXT NOT NULL, options TEXT NOT NULL,
    version TEXT NOT NULL
);
CREATE TABLE cells (
    id INTEGER PRIMARY KEY,
    run_id INTEGER NOT NULL REFERENCES runs(id),
    tracker TEXT NOT NULL, tracker_version TEXT NOT NULL, tracker_key TEXT NOT NULL, params TEXT NOT NULL,
    dataset TEXT NOT NULL, modality TEXT NOT NULL, seed INTEGER NOT NULL, init TEXT NOT NULL,
    status TEXT NOT NULL CHECK (status IN ('ok', 'error', 'timeout')),
    message TEXT NOT NULL, detail TEXT NOT NULL, frames INTEGER NOT NULL, elapsed_s REAL NOT NULL,
    finished TEXT NOT NULL
);
CREATE INDEX cells_by_key ON cells (tracker_key, dataset, seed, init);
CREATE TABLE run_cells (
    run_id INTEGER NOT NULL REFERENCES runs(id),
    cell_id INTEGER NOT NULL REFERENCES cells(id),
    PRIMARY KEY (run_id, cell_id)
);
CREATE TABLE frames (
    cell_id INTEGER NOT NULL REFERENCES cells(id), position INTEGER NOT NULL, frame INTEGER NOT NULL,
    outcome TEXT, step_ms REAL NOT NULL,
    PRIMARY KEY (cell_id, position)
);
CREATE TABLE frame_errors (
    cell_id INTEGER NOT NULL, position INTEGER NOT NULL, name TEXT NOT NULL, value REAL NOT NULL,
    PRIMARY KEY (cell_id, position, name),
    FOREIGN KEY (cell_id, position) REFERENCES frames(cell_id, position)
);
INSERT INTO runs VALUES (1, '2024-01-01T00:00:00+00:00', '2024-01-01T00:01:00+00:00', '[]', '{}', '0.1.0');
INSERT INTO cells VALUES (7, 1, 'noisy', '1.0', 'key-noisy', '{}', 'fake/S1', 'camera', 1, 'truth', 'ok', '', '',
                          1, 0.5, '2024-01-01T00:00:30+00:00');
INSERT INTO run_cells VALUES (1, 7);
INSERT INTO frames VALUES (7, 0, 0, 'correct', 2.0);
INSERT INTO frame_errors VALUES (7, 0, 'err_d_px', 1.5);
PRAGMA user_version = 1;
"""
"""A database as trackbench wrote it at schema version 1: one run with one cell of one frame."""


def test_a_version_1_database_is_upgraded_in_place(tmp_path: Path, results: dict[str, CellResult]) -> None:
    path = tmp_path / "r.sqlite"
    connection = sqlite3.connect(path)
    connection.executescript(V1_SCHEMA)
    connection.close()
    old_key = CellKey("key-noisy", "fake/S1", 1, "truth")

    with ResultStore(path) as store:
        old = store.cells(1)
        assert old[["id", "dataset", "dataset_key", "training"]].values.tolist() == [[7, "fake/S1", "fake/S1", ""]]
        assert store.frame_tables([7])["err_d_px"].tolist() == [1.5]
        # Version 1 timed the wall clock in step_ms: it is the wall time now, and the CPU time is unknown.
        assert store.frame_tables([7])["wall_ms"].tolist() == [2.0]
        assert store.frame_tables([7])["step_ms"].isna().all()
        assert store.run_problems(1) == []
        assert store.find_ok_cells([results["noisy"].key, old_key]) == {old_key: 7}
        assert store.pictures([7]) == {}
        run = store.start_run([], {}, problems=["a problem"])
        new_id = store.add_cell(run, dataclasses.replace(results["noisy"], pictures=PICTURES))
    with ResultStore(path) as reopened:
        assert reopened.cells(all_runs=True)["id"].tolist() == [7, new_id]
        assert reopened.pictures([7, new_id]) == {new_id: list(PICTURES)}
        assert reopened.find_ok_cells([results["noisy"].key]) == {results["noisy"].key: new_id}
        assert reopened.run_problems() == ["a problem"]
    connection = sqlite3.connect(path)
    assert connection.execute("PRAGMA user_version").fetchone()[0] == SCHEMA_VERSION
    index = [row[2] for row in connection.execute("PRAGMA index_info(cells_by_key)")]
    connection.close()
    assert index == ["tracker_key", "dataset_key", "seed", "init"]


def older_database(tmp_path: Path, result: CellResult, version: int, downgrade: str) -> tuple[Path, int]:
    """A database holding one cell, made as schema ``version`` had it by the SQL ``downgrade``; path and cell id."""
    path = tmp_path / "r.sqlite"
    with ResultStore(path) as store:
        cell_id = store.add_cell(store.start_run([], {}), result)
    connection = sqlite3.connect(path)
    if version < 7 and TO_VERSION_6 not in downgrade:
        downgrade = f"{TO_VERSION_6} {downgrade}"
    connection.executescript(f"{downgrade} PRAGMA user_version = {version};")
    connection.close()
    return path, cell_id


def test_a_version_2_database_gets_an_empty_training_column(tmp_path: Path, results: dict[str, CellResult]) -> None:
    path, _ = older_database(tmp_path, results["noisy"], 2, "ALTER TABLE cells DROP COLUMN training; ALTER TABLE cells DROP COLUMN deterministic;")
    trained = dataclasses.replace(results["noisy"], tracker_key="key+trained", training="camera-train")
    with ResultStore(path) as store:
        assert store.cells(all_runs=True)["training"].tolist() == [""]
        store.add_cell(store.start_run([], {}), trained)
        assert store.cells(all_runs=True)["training"].tolist() == ["", "camera-train"]
    connection = sqlite3.connect(path)
    assert connection.execute("PRAGMA user_version").fetchone()[0] == SCHEMA_VERSION
    connection.close()


def test_a_version_7_database_gets_an_empty_real_time_column(tmp_path: Path, results: dict[str, CellResult]) -> None:
    path, _ = older_database(tmp_path, results["noisy"], 7, "ALTER TABLE cells DROP COLUMN real_time;")
    paced = dataclasses.replace(results["noisy"], tracker_key="key+real-time:measured-median", real_time="measured")
    with ResultStore(path) as store:
        assert store.cells(all_runs=True)["real_time"].tolist() == [""]
        store.add_cell(store.start_run([], {}), paced)
        assert store.cells(all_runs=True)["real_time"].tolist() == ["", "measured"]
    connection = sqlite3.connect(path)
    assert connection.execute("PRAGMA user_version").fetchone()[0] == SCHEMA_VERSION == 8
    connection.close()


def test_a_version_3_database_gets_an_empty_pictures_table(tmp_path: Path, results: dict[str, CellResult]) -> None:
    path, old_id = older_database(tmp_path, results["noisy"], 3, "DROP TABLE pictures; ALTER TABLE cells DROP COLUMN deterministic;")
    with ResultStore(path) as store:
        assert store.cells(all_runs=True)["id"].tolist() == [old_id]
        assert len(store.frame_tables([old_id])) == len(results["noisy"].scores)
        assert store.pictures([old_id]) == {}
        new_id = store.add_cell(store.start_run([], {}), dataclasses.replace(results["noisy"], pictures=PICTURES))
        assert store.pictures([old_id, new_id]) == {new_id: list(PICTURES)}
    connection = sqlite3.connect(path)
    assert connection.execute("PRAGMA user_version").fetchone()[0] == SCHEMA_VERSION == 8
    columns = [(row[1], row[2], row[5]) for row in connection.execute("PRAGMA table_info(pictures)")]
    connection.close()
    assert columns == [("cell_id", "INTEGER", 1), ("frame", "INTEGER", 2), ("outcome", "VARCHAR(16)", 0), ("png", "BLOB", 0)]


def test_a_database_damaged_mid_file_is_a_data_error_naming_it(tmp_path: Path) -> None:
    path = tmp_path / "results.sqlite"
    with ResultStore(path) as store:
        run = store.start_run([], {})
        for seed in range(40):
            store.add_cell(run, make_result("noisy", [Outcome.CORRECT, Outcome.FALSE] * 100, seed=seed))
    assert not (tmp_path / "results.sqlite-wal").exists()  # all of it is in the file
    connection = sqlite3.connect(path)
    cells_page = connection.execute("SELECT rootpage FROM sqlite_master WHERE name = 'cells'").fetchone()[0]
    connection.close()
    original = path.read_bytes()
    page_size = int.from_bytes(original[16:18], "big")
    n_pages = len(original) // page_size
    assert n_pages > 50
    expected = (
        f"{path}: the results database is damaged (database disk image is malformed); "
        "move it aside to start a new one"
    )

    def damage(page: int) -> None:
        """Overwrite page ``page`` (numbered from 1, as SQLite does) of the original file."""
        damaged = bytearray(original)
        damaged[(page - 1) * page_size : page * page_size] = b"\xa5" * page_size
        path.write_bytes(damaged)

    damage(cells_page)
    with ResultStore(path) as store, pytest.raises(DataError) as raised:
        store.cells()
    assert str(raised.value) == expected and isinstance(raised.value.__cause__, sqlite3.DatabaseError)

    # Frames fill the middle of the file: damage a page after another until reading them meets one.
    for page in range(n_pages // 2, n_pages + 1):
        damage(page)
        with ResultStore(path) as store:
            ids = store.cells()["id"]
            try:
                store.frame_tables(ids)
            except DataError as exc:
                assert str(exc) == expected
                break
    else:
        pytest.fail("no damaged page was noticed")


def test_a_database_that_cannot_be_opened_or_used_is_a_data_error(tmp_path: Path) -> None:
    missing = tmp_path / "no such folder" / "r.sqlite"
    with pytest.raises(DataError, match=r"no such folder/r\.sqlite: cannot open the results database \(unable to open"):
        ResultStore(missing)
    store = ResultStore(tmp_path / "r.sqlite")
    store.close()
    with pytest.raises(DataError, match=r"r\.sqlite: cannot use the results database \(This Connection is closed\)"):
        store.start_run([], {})


@pytest.mark.skipif(not hasattr(os, "geteuid") or os.geteuid() == 0, reason="needs a user whom permissions bind")
def test_an_unwritable_folder_is_a_data_error(tmp_path: Path) -> None:
    folder = tmp_path / "locked"
    folder.mkdir(mode=0o500)
    try:
        with pytest.raises(DataError, match=r"locked/r\.sqlite: cannot open the results database"):
            ResultStore(folder / "r.sqlite")
    finally:
        folder.chmod(0o700)


def test_run_options_are_stored_as_json(tmp_path: Path) -> None:
    with ResultStore(tmp_path / "r.sqlite") as store:
        store.start_run(["trackbench", "run", "--seeds", "2"], {"seeds": 2, "out": Path("x")})
        runs = store.runs()
    assert runs.loc[0, "argv"] == '["trackbench", "run", "--seeds", "2"]'
    assert '"seeds": 2' in runs.loc[0, "options"]
    assert isinstance(runs.loc[0, "started"], str) and pd.isna(runs.loc[0, "finished"])


def test_conditions_are_kept_per_dataset_and_replaced_by_name(tmp_path: Path) -> None:
    with ResultStore(tmp_path / "r.sqlite") as store:
        store.add_conditions({"k1": {"water": "9C", "contrast_grey": 21.5}, "k2": {"frame_size": [640, 480]}})
        store.add_conditions({"k1": {"contrast_grey": 22.0}, "k3": {}})
        assert store.conditions(["k1", "k2", "k3", "k4"]) == {
            "k1": {"water": "9C", "contrast_grey": 22.0},
            "k2": {"frame_size": [640, 480]},
        }
        assert store.conditions([]) == {}
        with pytest.raises(ValueError, match="JSON"):
            store.add_conditions({"k5": {"contrast_grey": math.nan}})


def test_a_version_4_database_gets_an_empty_conditions_table(tmp_path: Path, results: dict[str, CellResult]) -> None:
    path, old_id = older_database(tmp_path, results["noisy"], 4, "DROP TABLE conditions; ALTER TABLE cells DROP COLUMN deterministic;")
    with ResultStore(path) as store:
        assert store.cells(all_runs=True)["id"].tolist() == [old_id]
        assert store.conditions([results["noisy"].key.dataset_key]) == {}
        store.add_conditions({"k": {"water": "I"}})
        assert store.conditions(["k"]) == {"k": {"water": "I"}}


def test_a_version_5_database_s_cells_declare_nothing_and_new_cells_keep_their_declaration(
    tmp_path: Path, results: dict[str, CellResult]
) -> None:
    path, _ = older_database(tmp_path, results["noisy"], 5, "ALTER TABLE cells DROP COLUMN deterministic;")
    declared = dataclasses.replace(results["noisy"], tracker_key="key+declared", deterministic=True)
    with ResultStore(path) as store:
        assert store.cells(all_runs=True)["deterministic"].tolist() == [False]
        store.add_cell(store.start_run([], {}), declared)
        assert store.cells(all_runs=True)["deterministic"].tolist() == [False, True]


TO_VERSION_6 = "ALTER TABLE frames DROP COLUMN step_ms; ALTER TABLE frames RENAME COLUMN wall_ms TO step_ms;"
"""Versions up to 6 timed a step by the wall clock only, in ``step_ms``."""

DOWNGRADES = {
    6: TO_VERSION_6,
    5: f"{TO_VERSION_6} ALTER TABLE cells DROP COLUMN deterministic;",
    4: f"{TO_VERSION_6} DROP TABLE conditions; ALTER TABLE cells DROP COLUMN deterministic;",
    3: f"{TO_VERSION_6} DROP TABLE conditions; DROP TABLE pictures; ALTER TABLE cells DROP COLUMN deterministic;",
    2: f"{TO_VERSION_6} DROP TABLE conditions; DROP TABLE pictures; ALTER TABLE cells DROP COLUMN deterministic; "
    "ALTER TABLE cells DROP COLUMN training;",
}
"""SQL that turns a database of this schema into one as schema version ``N`` had it (see the module docstring)."""


def contents(store: ResultStore, keys: list[CellKey]) -> dict[str, object]:
    """Everything a store reads back, for runs, cells, frames, pictures and the resume lookup."""
    cells = store.cells(all_runs=True)
    return {
        "runs": store.runs(),
        "latest": store.latest_run(),
        "problems": [store.run_problems(run) for run in store.runs()["id"]],
        "cells": [store.cells(run) for run in store.runs()["id"]],
        "all cells": cells,
        "frames": store.frame_tables(cells["id"]),
        "pictures": store.pictures(cells["id"]),
        "resumable": store.find_ok_cells(keys),
    }


@pytest.mark.parametrize("version", sorted(DOWNGRADES, reverse=True))
def test_an_older_database_is_upgraded_in_place_with_its_data_intact(
    tmp_path: Path, results: dict[str, CellResult], version: int
) -> None:
    noisy = dataclasses.replace(results["noisy"], pictures=PICTURES, training="camera-train", deterministic=True)
    cells = [noisy, results["raising"], results["blind"]]
    path = tmp_path / "results.sqlite"
    with ResultStore(path) as store:
        first = store.start_run(["trackbench", "run"], {"seeds": 1}, problems=["plugin 'acme' failed to import"])
        ids = [store.add_cell(first, cell) for cell in cells]
        store.finish_run(first)
        second = store.start_run(["trackbench", "run", "--resume"], {})
        store.reuse_cells(second, [ids[0], ids[2]])
        store.add_cell(second, results["raising"])
        before = contents(store, [cell.key for cell in cells])
    connection = sqlite3.connect(path)
    connection.executescript(f"{DOWNGRADES[version]} PRAGMA user_version = {version};")
    connection.close()
    # What the older schema could not keep comes back as its default: no pictures, no training, nothing declared;
    # its step times were wall times, and the CPU time is unknown.
    expected = dict(before, pictures={} if version <= 3 else before["pictures"])
    expected["frames"] = before["frames"].assign(step_ms=np.nan)
    for table in (expected["all cells"], *expected["cells"]):
        if version <= 5:
            table["deterministic"] = False
        if version == 2:
            table["training"] = ""

    with ResultStore(path) as store:
        after = contents(store, [cell.key for cell in cells])
        new_id = store.add_cell(store.start_run([], {}), noisy)
        store.add_conditions({DATASET_KEY: {"water": "I"}})
        grown = store.cells(all_runs=True)
        assert store.pictures([new_id]) == {new_id: list(PICTURES)}
        assert store.conditions([DATASET_KEY]) == {DATASET_KEY: {"water": "I"}}

    for name, value in expected.items():
        if isinstance(value, pd.DataFrame):
            pd.testing.assert_frame_equal(after[name], value, check_exact=True)
        elif name == "cells":
            for found, wanted in zip(after[name], value, strict=True):
                pd.testing.assert_frame_equal(found, wanted, check_exact=True)
        else:
            assert after[name] == value, name
    assert grown["id"].tolist()[-1] == new_id and bool(grown["deterministic"].iloc[-1])
    assert grown["training"].tolist()[-1] == "camera-train"
    connection = sqlite3.connect(path)
    assert connection.execute("PRAGMA user_version").fetchone()[0] == SCHEMA_VERSION
    assert connection.execute("PRAGMA integrity_check").fetchall() == [("ok",)]
    assert connection.execute("PRAGMA foreign_key_check").fetchall() == []
    connection.close()


def test_an_upgrade_that_fails_leaves_the_older_schema_as_it_was(
    tmp_path: Path, results: dict[str, CellResult], monkeypatch: pytest.MonkeyPatch
) -> None:
    path, old_id = older_database(tmp_path, results["noisy"], 4, DOWNGRADES[4])

    def interrupted(*args: object, **kwargs: object) -> None:
        raise RuntimeError("interrupted")

    monkeypatch.setattr(schema.RESULTS, "create_all", interrupted)  # after the new columns were added
    with pytest.raises(RuntimeError, match="interrupted"):
        ResultStore(path)
    connection = sqlite3.connect(path)
    assert connection.execute("PRAGMA user_version").fetchone()[0] == 4
    assert "deterministic" not in [row[1] for row in connection.execute("PRAGMA table_info(cells)")]
    connection.close()
    monkeypatch.undo()
    with ResultStore(path) as store:
        assert store.cells(all_runs=True)["id"].tolist() == [old_id]
        assert store.conditions([DATASET_KEY]) == {}


def test_a_status_the_store_does_not_know_is_refused_naming_the_file(
    tmp_path: Path, results: dict[str, CellResult]
) -> None:
    with ResultStore(tmp_path / "r.sqlite") as store:
        run = store.start_run([], {})
        with pytest.raises(DataError, match=r"r\.sqlite: cannot use the results database \(CHECK constraint failed"):
            store.add_cell(run, dataclasses.replace(results["noisy"], status="crashed"))  # type: ignore[arg-type]
        assert store.cells(all_runs=True).empty
