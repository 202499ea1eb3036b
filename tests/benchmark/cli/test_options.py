"""``--history`` is opened and checked before a command runs anything (benchmark.cli.options.HistoryDatabase)."""

from __future__ import annotations

import sqlite3
import sys
from pathlib import Path

import pytest

from ..conftest import Invoke

PASSWORD = "s3cret-Word-42"


def nightly(invoke: Invoke, tmp_path: Path, history: str):  # noqa: ANN201
    return invoke(
        "nightly", "--tracker", "noisy", "--in-process", "--out", str(tmp_path / "out"),
        "--history", history, "--site", str(tmp_path / "site"),
    )


def assert_refused_before_any_cell(result, tmp_path: Path, *named: str) -> None:  # noqa: ANN001
    """One line ``Error: ...`` naming ``named``, exit status 2, no traceback, no password, and no cell run."""
    assert result.exit_code == 2, result.output
    lines = result.output.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("Error: history database "), result.output
    assert all(text in lines[0] for text in named), lines[0]
    assert PASSWORD not in result.output and "Traceback" not in result.output
    assert not (tmp_path / "out").exists() and not (tmp_path / "site").exists()


def test_a_missing_driver_is_named_with_how_to_install_it_before_any_cell_runs(
    invoke: Invoke, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setitem(sys.modules, "psycopg", None)  # as if not installed
    result = nightly(invoke, tmp_path, f"postgresql://ci:{PASSWORD}@db.invalid/history")
    assert_refused_before_any_cell(
        result,
        tmp_path,
        "postgresql://ci:***@db.invalid/history",
        "psycopg",
        'pip install "subsea-trackbench[postgres]"',
    )


def test_a_driver_without_an_extra_is_named(invoke: Invoke, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setitem(sys.modules, "pg8000", None)
    result = nightly(invoke, tmp_path, f"postgresql+pg8000://ci:{PASSWORD}@db.invalid/history")
    assert_refused_before_any_cell(result, tmp_path, "its driver pg8000", "install the Python package")


def test_an_unreachable_server_is_refused_before_any_cell_runs(invoke: Invoke, tmp_path: Path) -> None:
    pytest.importorskip("psycopg", reason="the driver psycopg is not installed (pip install -e '.[test]')")
    result = nightly(invoke, tmp_path, f"postgresql://ci:{PASSWORD}@127.0.0.1:1/history")
    assert_refused_before_any_cell(result, tmp_path, "postgresql://ci:***@127.0.0.1:1/history", "OperationalError")


@pytest.mark.parametrize(
    "history",
    [f"nosuchdb://ci:{PASSWORD}@host/history", f"postgresql://ci:{PASSWORD}@host:port/history"],
    ids=["unknown database", "malformed URL"],
)
def test_a_url_that_names_no_database_is_refused(invoke: Invoke, tmp_path: Path, history: str) -> None:
    assert_refused_before_any_cell(nightly(invoke, tmp_path, history), tmp_path, "ci:***@host")


def test_another_programs_sqlite_database_is_refused_before_any_cell_runs(invoke: Invoke, tmp_path: Path) -> None:
    other = tmp_path / "other.sqlite"
    with sqlite3.connect(other) as connection:
        connection.execute("CREATE TABLE notes (x TEXT)")
    connection.close()
    result = nightly(invoke, tmp_path, str(other))
    assert_refused_before_any_cell(result, tmp_path, "other.sqlite", "holds other tables")


def test_compare_and_report_refuse_a_history_that_does_not_exist_without_creating_it(
    invoke: Invoke, tmp_path: Path
) -> None:
    missing = tmp_path / "none.sqlite"
    for command in (["compare", "1", "2"], ["report", "--site", str(tmp_path / "site")]):
        result = invoke(*command, "--history", str(missing))
        assert_refused_before_any_cell(result, tmp_path, "none.sqlite: no such file")
    assert not missing.exists()


def test_help_opens_no_history(invoke: Invoke, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.chdir(tmp_path)
    for command in ("nightly", "compare", "report"):
        result = invoke(command, "--help")
        assert result.exit_code == 0 and "--history FILE|URL" in result.output
    assert not (tmp_path / "reports").exists()
