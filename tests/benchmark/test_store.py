"""Tests of benchmark.store: one transaction per cell, nothing finished is lost."""

from __future__ import annotations

import dataclasses
import sqlite3
import types
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from benchmark.errors import DataError
from benchmark.model import Outcome
from benchmark.registry import Registry
from benchmark.results import CellResult, FrameScore
from benchmark.runner import run_cell
from benchmark.store import ResultStore


@pytest.fixture
def results(fakes: types.ModuleType, fake_registry: Registry) -> dict[str, CellResult]:
    """Results of a noisy (ok), a raising (error) and a blind (ok) cell."""
    sequence = fakes.FakeSequence()
    return {
        name: run_cell(fakes.make_cell(fake_registry.trackers[name], sequence, 1))
        for name in ("noisy", "raising", "blind")
    }


def test_a_cell_round_trips_with_its_frames(tmp_path: Path, results: dict[str, CellResult]) -> None:
    noisy = results["noisy"]
    with ResultStore(tmp_path / "r.sqlite") as store:
        run = store.start_run(["trackbench", "run"], {"seeds": 1})
        cell_id = store.add_cell(run, noisy)
        cells = store.cells(run)
        frames = store.frame_tables([cell_id])
    row = cells.iloc[0]
    assert (row["tracker"], row["dataset"], row["seed"], row["status"]) == ("noisy", "fake/S1", 1, "ok")
    assert row["tracker_key"] == noisy.tracker_key and row["frames"] == len(noisy.scores)
    expected = noisy.frames
    assert frames["frame"].tolist() == expected["frame"].tolist()
    assert frames["outcome"].tolist() == expected["outcome"].tolist()
    for column in ("err_d_px", "err_alpha_deg", "err_w_px", "err_beta_deg", "step_ms"):
        np.testing.assert_allclose(frames[column].to_numpy(float), expected[column].to_numpy(float), equal_nan=True)


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


def test_a_foreign_file_or_schema_is_a_clear_error(tmp_path: Path) -> None:
    junk = tmp_path / "junk.sqlite"
    junk.write_bytes(b"this is not a database at all" * 100)
    with pytest.raises(DataError, match="junk.sqlite"):
        ResultStore(junk)
    future = tmp_path / "future.sqlite"
    with sqlite3.connect(future) as connection:
        connection.execute("PRAGMA user_version = 99")
    with pytest.raises(DataError, match="schema version 99"):
        ResultStore(future)


def test_run_options_are_stored_as_json(tmp_path: Path) -> None:
    with ResultStore(tmp_path / "r.sqlite") as store:
        store.start_run(["trackbench", "run", "--seeds", "2"], {"seeds": 2, "out": Path("x")})
        runs = store.runs()
    assert runs.loc[0, "argv"] == '["trackbench", "run", "--seeds", "2"]'
    assert '"seeds": 2' in runs.loc[0, "options"]
    assert isinstance(runs.loc[0, "started"], str) and pd.isna(runs.loc[0, "finished"])
