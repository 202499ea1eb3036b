"""Tests of benchmark.cli through click's test runner, with a fake plugin registry."""

from __future__ import annotations

import sqlite3
import types
from pathlib import Path

import click
import cv2
import pandas as pd
import pytest
from click.testing import CliRunner

import benchmark.plugins
from benchmark.cli import main
from benchmark.errors import PluginError
from benchmark.metrics import SPEED, WALL_SPEED, derived_column
from benchmark.registry import Registry

from .conftest import Invoke

SPEEDS = [SPEED.name, WALL_SPEED.name]
"""The board columns that time the machine, which two runs of the same cells do not share."""


def board(out: Path) -> pd.DataFrame:
    return pd.read_csv(out / "leaderboard.csv")


def cell_rows(out: Path) -> list[tuple]:
    with sqlite3.connect(out / "results.sqlite") as connection:
        return connection.execute("SELECT id, run_id, tracker, dataset, seed, status FROM cells ORDER BY id").fetchall()


def test_list_shows_trackers_with_origin_and_parameters(invoke: Invoke) -> None:
    result = invoke("list")
    assert result.exit_code == 0, result.output
    lines = result.stdout.splitlines()
    raising = next(line for line in lines if line.startswith("raising "))
    assert "1.0" in raising and "camera" in raising and "fake-trackers 9.9" in raising and "plugin fakes" in raising
    assert "    fail_at = 3" in lines and "    sleep_s = 60.0" in lines
    assert any(line.startswith("sonar-only ") and "sonar" in line for line in lines)


def test_datasets_lists_suites_and_sequences(invoke: Invoke) -> None:
    result = invoke("datasets")
    assert result.exit_code == 0, result.output
    assert "fake  from fake-trackers 9.9" in result.stdout
    line = next(line for line in result.stdout.splitlines() if "fake/S2" in line)
    assert "camera" in line and "6 frames" in line and "shorter" in line


def test_disable_reaches_the_plugin_loader(invoke: Invoke, loads: list[tuple[str, ...]]) -> None:
    assert invoke("--disable", "hough", "--disable", "suites", "list").exit_code == 0
    assert loads == [("hough", "suites")]


def test_a_broken_plugin_is_a_one_line_error(monkeypatch: pytest.MonkeyPatch) -> None:
    def broken(disable: tuple[str, ...] = (), strict: bool = False) -> Registry:
        raise PluginError("plugin 'bad' (bad-dist 1.0) failed to import 'bad': ImportError: nope")

    monkeypatch.setattr(benchmark.plugins, "load_registry", broken)
    result = CliRunner().invoke(main, ["list"])
    assert result.exit_code == 2
    assert result.stderr.strip() == "Error: plugin 'bad' (bad-dist 1.0) failed to import 'bad': ImportError: nope"


def test_run_writes_the_three_files_and_prints_the_board(invoke: Invoke, tmp_path: Path) -> None:
    out = tmp_path / "out"
    result = invoke("run", "--tracker", "perfect", "--tracker", "blind", "--seeds", "2", "--in-process",
                    "--out", str(out))
    assert result.exit_code == 0, result.output
    for name in ("leaderboard.csv", "leaderboard.md", "leaderboard.html", "results.sqlite"):
        assert (out / name).is_file()
    table = board(out)
    per_dataset = table[table["dataset"] != "(all)"].set_index(["tracker", "dataset"])
    assert set(per_dataset.index) == {(t, d) for t in ("perfect", "blind") for d in ("fake/S1", "fake/S2")}
    assert per_dataset.loc[("perfect", "fake/S1"), "correct_pct"] == 100.0
    assert per_dataset.loc[("blind", "fake/S2"), "missed_pct"] == 100.0
    assert (per_dataset["seeds"] == 2).all() and (per_dataset["status"] == "ok").all()
    summary = result.stdout.splitlines()
    assert summary[0] == "camera: 2 trackers over 2 datasets" and summary[1].split()[:2] == ["tracker", "correct_pct"]
    assert [line.split()[0] for line in summary[2:4]] == ["perfect", "blind"] and "(all)" not in result.stdout
    assert f"  {out / 'leaderboard.md'}" in summary and max(map(len, summary)) <= 80 + len(str(out))
    assert not [line for line in result.stderr.splitlines() if " seed " in line]  # no line per ok cell without -v
    assert "cells 8/8, 0 failed, elapsed " in result.stderr


def test_run_verbose_writes_a_line_per_cell(invoke: Invoke, tmp_path: Path) -> None:
    result = invoke("run", "--tracker", "perfect", "--tracker", "blind", "--seeds", "2", "--in-process",
                    "--out", str(tmp_path / "out"), "-v")
    assert result.exit_code == 0, result.output
    progress = [line for line in result.stderr.splitlines() if " seed " in line]
    assert len(progress) == 8
    assert any(line.startswith("perfect  fake/S1  seed 1  ok  correct 100.0%") for line in progress)


def test_run_selects_suites_datasets_and_matching_modalities(invoke: Invoke, tmp_path: Path) -> None:
    out = tmp_path / "out"
    result = invoke("run", "--dataset", "fake/S2", "--tracker", "perfect", "--tracker", "sonar-only",
                    "--in-process", "--out", str(out))
    assert result.exit_code == 0, result.output
    assert [(row[2], row[3]) for row in cell_rows(out)] == [("perfect", "fake/S2")]


def test_run_reports_failures_as_rows_and_finishes_the_rest(invoke: Invoke, tmp_path: Path) -> None:
    out = tmp_path / "out"
    result = invoke("run", "--tracker", "raising", "--tracker", "garbage", "--tracker", "perfect",
                    "--dataset", "fake/S1", "--in-process", "--out", str(out))
    assert result.exit_code == 1, result.output
    assert "2 of 3 cells did not end ok." in result.stderr
    table = board(out).set_index(["tracker", "dataset"])
    assert table.loc[("raising", "fake/S1"), "status"] == "error (1/1 cells): RuntimeError: lost the cable (frame 3)"
    assert table.loc[("garbage", "fake/S1"), "status"].startswith("error (1/1 cells): EstimateError")
    assert table.loc[("perfect", "fake/S1"), "status"] == "ok"
    assert table.loc[("perfect", "fake/S1"), "rank"] == 1
    assert table.loc[("raising", "fake/S1"), "frames"] == 3


def test_param_overrides_reach_the_tracker(invoke: Invoke, tmp_path: Path) -> None:
    out = tmp_path / "out"
    result = invoke("run", "--tracker", "raising", "--dataset", "fake/S1", "--param", "raising.fail_at=7",
                    "--in-process", "--out", str(out))
    assert result.exit_code == 1, result.output
    assert "(frame 7)" in board(out).set_index("dataset").loc["fake/S1", "status"]


@pytest.mark.parametrize(
    ("args", "words"),
    [
        (["--tracker", "nope"], ["unknown tracker 'nope'", "perfect", "raising"]),
        (["--suite", "nope"], ["unknown suite 'nope'", "fake"]),
        (["--dataset", "nope/S9"], ["unknown dataset 'nope/S9'", "fake/S1"]),
        (["--tracker", "raising", "--param", "raising.speed=3"], ["'raising'", "'speed'", "fail_at"]),
        (["--tracker", "raising", "--param", "raising.fail_at=soon"], ["'raising'", "'fail_at'", "soon"]),
        (["--tracker", "raising", "--param", "perfect.x=1"], ["'perfect'", "not selected"]),
        (["--param", "no-equals-sign"], ["TRACKER.KEY=VALUE"]),
        (["--tracker", "sonar-only"], ["nothing to run", "sonar-only (sonar)"]),
        (["--seeds", "100000000"], ["x 100,000,000 seeds", "more cells than one run holds (1,000,000)"]),
    ],
)
def test_bad_selections_exit_2_with_a_clear_message(
    invoke: Invoke, tmp_path: Path, args: list[str], words: list[str]
) -> None:
    result = invoke("run", *args, "--in-process", "--out", str(tmp_path / "out"))
    assert result.exit_code == 2
    message = result.stderr.strip()
    assert message.startswith("Error: ") and "\n" not in message and "Traceback" not in result.output
    for word in words:
        assert word in message


@pytest.mark.parametrize("value", ["nan", "inf", "-inf", "0"])
@pytest.mark.parametrize(("command", "option"), [(["run"], "--timeout"), (["check", "perfect"], "--time-limit")])
def test_a_time_limit_must_be_a_positive_finite_number_of_seconds(
    invoke: Invoke, command: list[str], option: str, value: str
) -> None:
    result = invoke(*command, option, value)
    assert result.exit_code == 2
    assert f"Invalid value for '{option}'" in result.stderr and value in result.stderr


def test_resume_skips_ok_cells_and_redoes_failed_ones(
    invoke: Invoke, fakes: types.ModuleType, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    out = tmp_path / "out"
    args = ["run", "--tracker", "counting", "--tracker", "raising", "--dataset", "fake/S1", "--seeds", "2",
            "--in-process", "--out", str(out)]
    monkeypatch.setattr(fakes.Counting, "created", 0)
    assert invoke(*args).exit_code == 1
    assert fakes.Counting.created == 2
    first = cell_rows(out)
    first_board = board(out)

    result = invoke(*args, "--resume")
    assert result.exit_code == 1, result.output
    assert fakes.Counting.created == 2
    assert "resume: 2 cells already finished, 2 to run" in result.stderr
    second = cell_rows(out)
    added = second[len(first):]
    assert [(row[1], row[2], row[5]) for row in added] == [(2, "raising", "error"), (2, "raising", "error")]
    pd.testing.assert_frame_equal(board(out).drop(columns=SPEEDS), first_board.drop(columns=SPEEDS))

    assert invoke(*args).exit_code == 1
    assert fakes.Counting.created == 4


def test_an_interrupted_run_keeps_its_cells_for_resume(
    invoke: Invoke, fakes: types.ModuleType, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    import benchmark.executors.local

    out = tmp_path / "out"
    real = benchmark.executors.local.run_cell
    finished: list[str] = []

    def stop_after_two(cell, timeout_s=None):  # noqa: ANN001, ANN202
        if len(finished) == 2:
            raise KeyboardInterrupt
        finished.append(cell.label())
        return real(cell, timeout_s)

    monkeypatch.setattr(benchmark.executors.local, "run_cell", stop_after_two)
    monkeypatch.setattr(fakes.Counting, "created", 0)
    args = ["run", "--tracker", "counting", "--seeds", "3", "--in-process", "--out", str(out)]
    assert invoke(*args).exit_code != 0
    assert len(cell_rows(out)) == 2

    monkeypatch.setattr(benchmark.executors.local, "run_cell", real)
    result = invoke(*args, "--resume")
    assert result.exit_code == 0, result.output
    assert fakes.Counting.created == 2 + 4
    assert board(out).query("dataset != '(all)'")["seeds"].tolist() == [3, 3]


def test_leaderboard_command_republishes_the_latest_run(invoke: Invoke, tmp_path: Path) -> None:
    out = tmp_path / "out"
    assert invoke("run", "--tracker", "noisy", "--seeds", "2", "--in-process", "--out", str(out)).exit_code == 0
    expected = board(out)
    for name in ("leaderboard.csv", "leaderboard.md", "leaderboard.html"):
        (out / name).unlink()
    result = invoke("leaderboard", "--out", str(out))
    assert result.exit_code == 0, result.output
    pd.testing.assert_frame_equal(board(out), expected)
    assert (out / "leaderboard.md").is_file() and (out / "leaderboard.html").is_file()
    assert "noisy" in result.stdout


def test_leaderboard_without_a_database_is_a_clear_error(invoke: Invoke, tmp_path: Path) -> None:
    result = invoke("leaderboard", "--out", str(tmp_path / "missing"))
    assert result.exit_code == 2
    assert "no results database" in result.stderr


def test_run_in_a_pool(invoke: Invoke, tmp_path: Path) -> None:
    out = tmp_path / "out"
    result = invoke("run", "--tracker", "perfect", "--tracker", "raising", "--jobs", "2", "--out", str(out))
    assert result.exit_code == 1, result.output
    statuses = {(row[2], row[3]): row[5] for row in cell_rows(out)}
    assert statuses == {
        ("perfect", "fake/S1"): "ok",
        ("perfect", "fake/S2"): "ok",
        ("raising", "fake/S1"): "error",
        ("raising", "fake/S2"): "error",
    }


def test_dataset_path_runs_a_sequence_file(invoke: Invoke, fakes: types.ModuleType, tmp_path: Path) -> None:
    pytest.importorskip("benchmark.io")
    folder = tmp_path / "mine"
    (folder / "img").mkdir(parents=True)
    lines = ["# CableDistance CableAngle CableWidth CableSkew # Filename"]
    for index in range(4):
        cable = fakes.truth_at(index).cable
        image = fakes.FakeSequence().frames().__next__().observation
        assert cv2.imwrite(str(folder / "img" / f"{index:03d}.png"), image)
        lines.append(f"{cable.d} {cable.alpha} {cable.w} {cable.beta} # img/{index:03d}.png")
    (folder / "seq.txt").write_text("\n".join(lines) + "\n")
    path = str(folder / "seq.txt")
    out = tmp_path / "out"

    result = invoke("run", "--tracker", "perfect", "--dataset", path, "--in-process", "--out", str(out))
    assert result.exit_code == 0, result.output
    row = board(out).set_index("dataset").loc[path]
    assert row["frames"] == 4 and row["correct_pct"] == 100.0


def test_make_dataset_exports_every_sequence_of_a_suite(invoke: Invoke, tmp_path: Path) -> None:
    pytest.importorskip("benchmark.io")
    out = tmp_path / "export"
    result = invoke("make-dataset", "fake", "--out", str(out))
    assert result.exit_code == 0, result.output
    written = [Path(line) for line in result.stdout.splitlines()]
    assert len(written) == 2 and all(path.is_file() for path in written)
    assert "sequences 2/2, elapsed " in result.stderr
    assert len(list(out.rglob("*.png"))) == 10 + 6
    assert invoke("make-dataset", "nope", "--out", str(out)).exit_code == 2


def test_tables_lays_out_a_suite_per_case(fakes: types.ModuleType, monkeypatch: pytest.MonkeyPatch, tmp_path: Path):
    def load_registry(disable: tuple[str, ...] = (), strict: bool = False) -> Registry:
        registry = fakes.make_registry((fakes.Perfect, fakes.Blind))
        names = ["grid/a-slow", "grid/a-fast", "grid/b-slow", "grid/b-fast"]
        registry.add_suite("grid", [fakes.FakeSequence(name, 5) for name in names])
        return registry

    monkeypatch.setattr(benchmark.plugins, "load_registry", load_registry)
    out = str(tmp_path)
    assert CliRunner().invoke(main, ["run", "--suite", "grid", "--in-process", "--out", out]).exit_code == 0
    result = CliRunner().invoke(main, ["tables", "grid", "--out", out, "--metric", "correct_pct"])
    assert result.exit_code == 0, result.output
    text = (tmp_path / "tables_grid.md").read_text()
    assert "## a" in text and "## b" in text
    header = next(line for line in text.splitlines() if "slow" in line)
    assert header.index("slow") < header.index("fast")  # the suite's order, not alphabetical
    assert "correct_pct perfect" in text and "100.00" in text
    bad = CliRunner().invoke(main, ["tables", "grid", "--out", out, "--metric", "nope"])
    assert bad.exit_code == 2 and "no column nope" in bad.output
    assert CliRunner().invoke(main, ["tables", "fake", "--out", out]).exit_code == 2


@pytest.mark.parametrize(
    ("param", "words"),
    [
        ("bounded.windw=2", ["tracker 'bounded' has no parameter 'windw'", "known: window"]),
        ("bounded.window=0", ["tracker 'bounded'", "parameter 'window'", "greater than or equal to 1", "got 0"]),
        ("bounded.window=wide", ["tracker 'bounded'", "parameter 'window'", "wide"]),
    ],
)
def test_a_bad_param_exits_2_before_any_cell_runs(
    fakes: types.ModuleType, monkeypatch: pytest.MonkeyPatch, tmp_path: Path, param: str, words: list[str]
) -> None:
    bounded_only = fakes.make_registry((fakes.Bounded,))
    monkeypatch.setattr(benchmark.plugins, "load_registry", lambda disable=(), strict=False: bounded_only)
    monkeypatch.setattr(fakes.Bounded, "created", 0)
    out = tmp_path / "out"
    args = ["run", "--tracker", "bounded", "--in-process", "--out", str(out)]
    assert CliRunner().invoke(main, [*args, "--param", "bounded.window=2"]).exit_code == 0
    before, created = cell_rows(out), fakes.Bounded.created
    assert len(before) == 2 and created == 2

    result = CliRunner().invoke(main, [*args, "--param", param])
    assert result.exit_code == 2
    message = result.stderr.strip()
    assert message.startswith("Error: ") and "\n" not in message and "Traceback" not in result.output
    for word in words:
        assert word in message
    assert cell_rows(out) == before and fakes.Bounded.created == created
    with sqlite3.connect(out / "results.sqlite") as connection:
        assert connection.execute("SELECT COUNT(*) FROM runs").fetchone() == (1,)


def test_leaderboard_boards_a_modality_whose_plugin_is_gone_by_its_name(
    invoke: Invoke, monkeypatch: pytest.MonkeyPatch, tmp_path: Path
) -> None:
    out = tmp_path / "out"
    assert invoke("run", "--tracker", "noisy", "--in-process", "--out", str(out)).exit_code == 0
    expected = board(out)
    monkeypatch.setattr(benchmark.plugins, "load_registry", lambda disable=(), strict=False: Registry())
    result = invoke("leaderboard", "--out", str(out))
    assert result.exit_code == 0, result.output
    assert result.stdout.startswith("camera\n")
    # Without the scorer the error columns come from what the store holds: the same board, less the
    # columns no frame had a value for (the pose errors of a tracker that reports no pose).
    again = board(out)
    pose = {"rmse_cx_m", "rmse_cy_m", "rmse_theta_deg", "rmse_phi_deg"}
    ends = {derived_column(metric, end) for metric in pose for end in ("lo", "hi")}
    assert set(expected.columns) - set(again.columns) == pose | ends
    assert expected.drop(columns=again.columns).isna().all().all()
    pd.testing.assert_frame_equal(again, expected[again.columns])


def test_the_package_s_list_of_commands_is_the_command_line_s() -> None:
    import re

    import benchmark.cli

    block = benchmark.cli.__doc__.split("::", 1)[1].split("\n\n")[2]  # after the usage line
    listed = re.findall(r"^    ([a-z][a-z-]*) {2,}\S", block, flags=re.MULTILINE)
    assert len(listed) == len(block.splitlines())
    real = main.list_commands(click.Context(main))  # the built-in commands and those of installed plugins
    assert {"run", "diagnose"} <= set(real)
    assert sorted(listed) == real
