"""``trackbench nightly``, ``compare`` and ``report`` through click's runner, with the fake registry."""

from __future__ import annotations

import contextlib
import dataclasses
import os
import signal
import subprocess
import sys
import types
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pandas as pd
import pytest

import benchmark.plugins
from benchmark.cli import EXIT_REGRESSION, EXIT_SPEED_REGRESSION
from benchmark.history.database import History
from benchmark.history.nightly import REPEAT_FOLDER
from benchmark.history.regressions import NOISE_RUNS
from benchmark.model import Frame

from ..conftest import ALL_TRACKERS, Invoke, Perfect


def nightly(invoke: Invoke, tmp_path: Path, *extra: str):  # noqa: ANN201
    return invoke(
        "nightly", "--tracker", "noisy", "--seeds", "2", "--in-process", "--out", str(tmp_path / "out"),
        "--history", str(tmp_path / "history.sqlite"), "--site", str(tmp_path / "site"), *extra,
    )


def test_a_worsened_parameter_is_a_regression_in_the_exit_status_the_output_and_the_site(
    invoke: Invoke, tmp_path: Path
) -> None:
    first = nightly(invoke, tmp_path)
    assert first.exit_code == 0, first.output
    assert "cells 4/4, 0 failed, elapsed " in first.stderr and "site pages " in first.stderr  # a log's progress
    assert "no change beyond the thresholds" in first.stdout
    second = nightly(invoke, tmp_path, "--param", "noisy.sigma_px=40")
    assert second.exit_code == EXIT_REGRESSION, second.output
    assert "regression" in second.stdout and "rmse_d_px" in second.stdout and "sigma_px" in second.stdout
    assert "1 by tracker and cause" in second.stdout, second.stdout  # one parameter, one row
    assert str(tmp_path / "out" / "changes.csv") in second.stdout
    written = pd.read_csv(tmp_path / "out" / "changes.csv", keep_default_na=False)
    with History(tmp_path / "history.sqlite") as history:
        assert history.runs()["id"].tolist() == [1, 2]
        kept = history.changes(2)
        assert kept is not None and len(kept) == len(written) > 1
        assert kept["metric"].tolist() == written["metric"].tolist()
    index = (tmp_path / "site" / "index.html").read_text()
    assert "regression" in index.lower() and "rmse_d_px" in index and "noisy" in index

    compared = invoke("compare", "1", "2", "--history", str(tmp_path / "history.sqlite"))
    assert compared.exit_code == 0, compared.output
    assert "regression" in compared.stdout and "rmse_d_px" in compared.stdout
    backwards = invoke("compare", "2", "1", "--history", str(tmp_path / "history.sqlite"))
    assert "improvement" in backwards.stdout and "regression" not in backwards.stdout

    (tmp_path / "site" / "index.html").unlink()
    rebuilt = invoke("report", "--history", str(tmp_path / "history.sqlite"), "--site", str(tmp_path / "site"))
    assert rebuilt.exit_code == 0, rebuilt.output
    assert "site pages " in rebuilt.stderr
    assert "rmse_d_px" in (tmp_path / "site" / "index.html").read_text()


def test_compare_and_report_name_a_missing_history_or_run(invoke: Invoke, tmp_path: Path) -> None:
    missing = invoke("compare", "1", "2", "--history", str(tmp_path / "none.sqlite"))
    assert missing.exit_code == 2 and "none.sqlite" in missing.output
    assert not (tmp_path / "none.sqlite").exists()
    assert nightly(invoke, tmp_path).exit_code == 0
    unknown = invoke("compare", "1", "7", "--history", str(tmp_path / "history.sqlite"))
    assert unknown.exit_code == 2 and "no run 7" in unknown.output
    bad = nightly(invoke, tmp_path, "--min-effect", "correct_pct")
    assert bad.exit_code == 2 and "METRIC=NUMBER" in bad.output


@dataclasses.dataclass(frozen=True)
class BusyParams:
    work: int = 1


class Busy(Perfect):
    """The true state after a fixed amount of arithmetic per step, ``work`` times over: CPU work and nothing else."""

    name = "busy"
    Params = BusyParams

    def step(self, frame: Frame) -> Any:
        total = 0
        for value in range(20_000 * self.params.work):
            total += value * value
        return frame.truth.cable if total >= 0 else None


@pytest.fixture
def invoke_busy(invoke: Invoke, fakes: types.ModuleType, monkeypatch: pytest.MonkeyPatch) -> Invoke:
    """``invoke`` with the fake registry and the tracker ``busy``."""
    monkeypatch.setattr(benchmark.plugins, "load_registry", lambda *a, **k: fakes.make_registry((*ALL_TRACKERS, Busy)))
    return invoke


@contextlib.contextmanager
def both_cores_busy() -> Iterator[None]:
    """Another process spinning on both cores while the block runs (a neighbour on a shared machine)."""
    spinner = subprocess.Popen(
        [sys.executable, "-c", "import os; os.fork(); exec('while True: pass')"], start_new_session=True
    )
    try:
        yield
    finally:
        os.killpg(spinner.pid, signal.SIGKILL)
        spinner.wait()


MIN_STEP_S = 0.005
"""Small enough that the tiny sequence's steps are judged (about 0.7 ms each here), large enough to mean something."""


def busy_nightly(invoke: Invoke, tmp_path: Path, *extra: str):  # noqa: ANN201
    return invoke(
        "nightly", "--tracker", "busy", "--dataset", "fake/S1", "--seeds", "2", "--in-process",
        "--min-step-time", str(MIN_STEP_S),
        "--out", str(tmp_path / "out"), "--history", str(tmp_path / "history.sqlite"), "--site", str(tmp_path / "site"),
        *extra,
    )


def test_nightlies_with_nothing_changed_stay_green_while_another_process_loads_both_cores_and_a_slower_tracker_does_not(
    invoke_busy: Invoke, tmp_path: Path
) -> None:
    with both_cores_busy():
        for night in range(5):  # with --fail-on-speed: a speed regression found on noise would exit 4
            kept = busy_nightly(invoke_busy, tmp_path, "--fail-on-speed")
            assert kept.exit_code == 0, (night, kept.output)
            assert "machine load during the run: cores:" in kept.output
        with History(tmp_path / "history.sqlite") as history:
            runs, cells = history.runs(), history.cells()
        assert len(runs) == 5 and all(0 <= run["others_pct"] <= run["busy_pct"] <= 100 for run in runs["load"])
        # Speed was judged: the last nights had the earlier runs a noise estimate needs, and enough step time.
        last = cells[cells["run_id"] == runs["id"].iloc[-1]]
        step_s = (last["frames"] / last["cpu_fps"]).groupby(last["dataset"]).sum()
        assert len(runs) - 1 >= NOISE_RUNS and step_s.min() >= MIN_STEP_S

        slower = busy_nightly(invoke_busy, tmp_path, "--param", "busy.work=3", "--fail-on-speed")
        reported = busy_nightly(invoke_busy, tmp_path, "--param", "busy.work=3")  # still slow against the window
    assert slower.exit_code == EXIT_SPEED_REGRESSION, slower.output
    assert "regression" in slower.stdout and "cpu_fps" in slower.stdout and "held" in slower.stdout
    assert (tmp_path / "out" / REPEAT_FOLDER / "results.sqlite").is_file()
    assert reported.exit_code == 0 and "regression" in reported.stdout and "held" in reported.stdout, reported.output


def test_a_speed_change_too_early_to_judge_is_on_the_site_as_unjudged(invoke_busy: Invoke, tmp_path: Path) -> None:
    assert busy_nightly(invoke_busy, tmp_path).exit_code == 0
    slower = busy_nightly(invoke_busy, tmp_path, "--param", "busy.work=3")  # one earlier run: no noise estimate
    assert slower.exit_code == 0, slower.output
    page = (tmp_path / "site" / "index.html").read_text()
    assert "Speed changes not judged" in page and "not judged: 1 earlier run on this machine" in page


def test_changes_are_described_one_entry_per_tracker_and_cause_within_the_width() -> None:
    from benchmark.history.nightly import describe_changes

    rows = [
        dict(tracker="hough", dataset=f"camera/S{i}", metric=metric, kind="accuracy", before=90.0, after=80.0,
             change=-10.0, verdict="regression", cause="vote_fraction 0.25 -> 0.5", effects=5.0 - i,
             note="frames with an estimate 300 -> 212" if metric.startswith("rmse") else "")
        for i in range(1, 4) for metric in ("correct_pct", "rmse_d_px")
    ]
    text = describe_changes(pd.DataFrame(rows), "Run 1 -> 2", width=60)
    lines = text.splitlines()
    assert lines[0] == "Run 1 -> 2: 6 changes, 1 by tracker and cause"
    assert all(len(line) <= 60 for line in lines)
    assert sum(line.startswith("  regression") for line in lines) == 1 and "correct_pct -10.0 on camera/S1" in text
    assert "cause: vote_fraction 0.25 -> 0.5" in text and "6 changes on 3 datasets, 2 metrics" in text
    assert "note: frames with an estimate 300 -> 212 (+2)" in text


def test_a_nightly_runs_the_routes_suite_when_named_and_its_site_draws_each_path(
    invoke: Invoke, fakes: types.ModuleType, monkeypatch: pytest.MonkeyPatch, tmp_path: Path
) -> None:
    from benchmark.selection import Selection, select_cells

    from ..site.conftest import route_registry

    unnamed = select_cells(route_registry(fakes), Selection(trackers=("perfect",)))  # as a nightly naming no suite
    assert {cell.dataset for cell in unnamed} == {"fake/S1", "fake/S2"}  # a closed-loop suite runs only when named
    monkeypatch.setattr(benchmark.plugins, "load_registry", lambda *a, **k: route_registry(fakes))
    named = invoke("nightly", "--tracker", "perfect", "--suite", "fake", "--suite", "routes", "--in-process",
                   "--out", str(tmp_path / "out"), "--history", str(tmp_path / "history.sqlite"),
                   "--site", str(tmp_path / "site"))
    assert named.exit_code == 0, named.output
    history = History(tmp_path / "history.sqlite")
    cells = history.cells()
    (route_cell,) = cells.loc[cells["dataset"] == "routes/short", "id"]
    assert list(history.boards(1) or {}) == ["camera", "camera: routes, closed loop"]
    assert cells.loc[cells["dataset"] == "routes/short", "followed_m"].iloc[0] > 1.0
    page = (tmp_path / "site" / "cells" / f"{route_cell}.html").read_text(encoding="utf-8")
    assert 'id="top-view"' in page and '"name":"vehicle"' in page
