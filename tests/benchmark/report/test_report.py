"""Tests of benchmark.report: the three files a run publishes."""

from __future__ import annotations

import re
from pathlib import Path

import pandas as pd

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
