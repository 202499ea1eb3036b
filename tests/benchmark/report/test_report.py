"""Tests of benchmark.report: the three files a run publishes."""

from __future__ import annotations

import os
import re
from pathlib import Path

import pandas as pd
import pytest

from benchmark.errors import DataError
from benchmark.report import FILE_NAMES, write_leaderboards


def test_write_leaderboards_writes_csv_markdown_and_html(boards: dict[str, pd.DataFrame], tmp_path: Path) -> None:
    written = write_leaderboards(boards, tmp_path / "out", caption="Run 1.")
    assert [p.name for p in written] == ["leaderboard.csv", "leaderboard.md", "leaderboard.html"]
    assert [p.name for p in written] == list(FILE_NAMES.values())
    markdown = (tmp_path / "out" / "leaderboard.md").read_text()
    assert "## camera" in markdown and re.search(r"\|\s+66\.7 \|", markdown) and "Run 1." in markdown
    page = (tmp_path / "out" / "leaderboard.html").read_text()
    assert "<table" in page and "<td>66.7</td>" in page
    assert (tmp_path / "out" / "leaderboard.csv").read_text().startswith("modality,rank,tracker,")


def test_empty_results_export_cleanly(tmp_path: Path) -> None:
    written = write_leaderboards({}, tmp_path)
    assert all(path.exists() for path in written)
    assert "No results." in (tmp_path / "leaderboard.md").read_text()


def test_problems_go_to_the_pages_not_to_the_csv(boards: dict[str, pd.DataFrame], tmp_path: Path) -> None:
    problem = "plugin 'acme' (acme-dist 1.0) failed to import: ImportError: No module named 'acme'"
    csv, markdown, page = (path.read_text() for path in write_leaderboards(boards, tmp_path, problems=[problem]))
    assert "## Problems" in markdown and "acme-dist 1.0" in markdown
    assert "<h2>Problems</h2>" in page and "acme-dist 1.0" in page
    assert "acme" not in csv and "Problems" not in csv


def test_boards_replace_the_old_files_instead_of_rewriting_them(
    boards: dict[str, pd.DataFrame], tmp_path: Path
) -> None:
    for name in FILE_NAMES.values():
        (tmp_path / f"published-{name}").write_text("old board")
        os.link(tmp_path / f"published-{name}", tmp_path / name)  # a reader's handle on the old file
    written = write_leaderboards(boards, tmp_path)
    for path in written:
        assert (tmp_path / f"published-{path.name}").read_text() == "old board"
        assert "old board" not in path.read_text()
    assert len(list(tmp_path.iterdir())) == 2 * len(FILE_NAMES)  # no temporary file left behind


def test_a_board_that_cannot_be_written_is_a_data_error_naming_it(
    boards: dict[str, pd.DataFrame], tmp_path: Path
) -> None:
    (tmp_path / "leaderboard.html").mkdir()
    with pytest.raises(DataError, match=r"leaderboard\.html: cannot write leaderboard"):
        write_leaderboards(boards, tmp_path)
