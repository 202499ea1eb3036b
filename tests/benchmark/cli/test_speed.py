"""``trackbench speed``: the ratio table printed and written, bounds through the hook, bad names refused."""

from __future__ import annotations

import csv
from collections.abc import Callable
from pathlib import Path

import pytest
from click.testing import CliRunner, Result

import benchmark.plugins
import benchmark.speed.bounds
from benchmark.cli import main
from benchmark.registry import Registry

from ..conftest import make_registry
from ..speed.fakes import Fast, Slow, bounds_of


Run = Callable[..., Result]


@pytest.fixture
def speed(monkeypatch: pytest.MonkeyPatch) -> Run:
    """Run ``trackbench speed`` on the fake registry and the fake plugin's bounds."""

    def load_registry(disable: tuple[str, ...] = (), strict: bool = False) -> Registry:
        return make_registry((Fast, Slow))

    monkeypatch.setattr(benchmark.plugins, "load_registry", load_registry)
    monkeypatch.setattr(benchmark.speed.bounds, "load_bounds", lambda disable=(), strict=False: bounds_of())

    def run(*args: str) -> Result:
        return CliRunner().invoke(main, ["speed", "--rounds", "2", "--frames", "3", *args], env={"COLUMNS": "200"})

    return run


def test_the_table_has_a_row_per_bound_and_is_written_as_csv_and_markdown(speed: Run, tmp_path: Path) -> None:
    result = speed("--out", str(tmp_path / "t.csv"), "--out", str(tmp_path / "t.md"))
    assert result.exit_code == 0, result.output
    lines = result.stdout.splitlines()
    assert lines[0].split()[:2] == ["subject", "bound"]
    assert any(line.startswith("fast") and "a peer not installed" in line and "acme-peer" in line for line in lines)
    assert any(line.startswith("slow") and "not met" in line for line in lines)
    with open(tmp_path / "t.csv", newline="") as handle:
        rows = list(csv.DictReader(handle))
    assert [(row["subject"], row["bound"]) for row in rows] == [
        ("core step", "the same work"),
        ("fast", "the same work"),
        ("fast", "a peer not installed"),
        ("slow", "the same work"),
    ]
    _, fast, _, slow = rows
    assert float(slow["ratio"]) > float(fast["ratio"])
    assert (fast["frames"], fast["rounds"], fast["met"], slow["met"]) == ("3", "2", "True", "False")
    markdown = (tmp_path / "t.md").read_text()
    assert markdown.startswith("| subject | bound or peer |") and "| slow | the same work |" in markdown
    assert "fake/S1: 3 frames x 2 rounds" in markdown


def test_the_table_fits_a_narrow_terminal(speed: Run) -> None:
    arguments = ["speed", "--rounds", "1", "--frames", "2", "--tracker", "slow"]
    result = CliRunner().invoke(main, arguments, env={"COLUMNS": "60"})
    assert result.exit_code == 0, result.output
    assert all(len(line) <= 60 for line in result.stdout.splitlines())
    assert "not met" in result.stdout and "too narrow for" in result.stdout


def test_an_unknown_tracker_is_an_error_naming_it(speed: Run) -> None:
    result = speed("--tracker", "fast", "--tracker", "nope")
    assert result.exit_code == 2
    assert "Error: no speed bound is declared for 'nope'; subjects with a bound: core step, fast, slow" in result.output


def test_out_must_be_csv_or_markdown(speed: Run, tmp_path: Path) -> None:
    result = speed("--out", str(tmp_path / "t.txt"))
    assert result.exit_code == 2 and "written as .csv or .md, not .txt" in result.output
