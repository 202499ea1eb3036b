"""The speed table: fitted to the terminal, written as CSV and markdown, unmeasured rows said so."""

from __future__ import annotations

import csv
import math
from pathlib import Path

from benchmark.speed.measure import Row
from benchmark.speed.table import DROPPED_FIRST, HEADERS, markdown_table, met_text, terminal_table, write_csv

MEASURED = Row("condensation", "its kernel", "camera/S1", 40, 7, 0.0015, 0.0002, 7.5, 7.0, 8.0, ">= 3000 fps", False)
MISSING = Row(
    "sonar_pf", "Stone | Soup", "sonar/x", 40, 1, 0.002, math.nan, math.nan, math.nan, math.nan, ">= 2x faster", None,
    "Stone Soup is not installed",
)


def test_cells_show_milliseconds_fps_ratio_spread_and_the_verdict() -> None:
    text = terminal_table([MEASURED], width=200).splitlines()
    assert text[0].split("  ")[0] == "subject" and len(text) == 2
    for value in ("1.5", "667", "0.2", "7.50x", "7.00-8.00", ">= 3000 fps", "not met"):
        assert value in text[1]


def test_a_row_without_a_bound_says_why_instead_of_a_verdict() -> None:
    assert met_text(MISSING) == "Stone Soup is not installed"
    line = terminal_table([MISSING], width=200).splitlines()[1]
    assert "Stone Soup is not installed" in line and line.count(" - ") >= 2


def test_a_narrow_terminal_shortens_the_words_then_leaves_out_columns_in_order() -> None:
    for width in (40, 60, 80, 100):
        lines = terminal_table([MEASURED, MISSING], width=width).splitlines()
        assert all(len(line) <= width for line in lines)
    lines = terminal_table([MEASURED], width=60).splitlines()
    assert lines[-1].startswith("(too narrow for")
    left_out = lines[-1].removeprefix("(too narrow for ").rstrip(")").split(", ")
    assert left_out == [title for title in HEADERS if title in DROPPED_FIRST[: len(left_out)]]
    assert "met" in lines[0]


def test_markdown_escapes_pipes_and_says_how_it_was_measured() -> None:
    text = markdown_table([MEASURED, MISSING])
    assert "| Stone \\| Soup |" in text
    assert "camera/S1: 40 frames x 7 rounds; sonar/x: 40 frames x 1 round." in text


def test_csv_keeps_full_precision(tmp_path: Path) -> None:
    path = tmp_path / "deep" / "speed.csv"
    write_csv([MEASURED, MISSING], path)
    with open(path, newline="") as handle:
        rows = list(csv.DictReader(handle))
    assert float(rows[0]["ours_s"]) == MEASURED.ours_s and float(rows[0]["ours_fps"]) == 1 / MEASURED.ours_s
    assert rows[1]["met"] == "" and rows[1]["note"] == "Stone Soup is not installed"
