"""Tests of benchmark.report.markdown: the Markdown page and the terminal view."""

from __future__ import annotations

import re

import pandas as pd

from benchmark.report.markdown import to_markdown, to_text


def test_markdown_has_a_section_per_modality_rounded_and_captioned(boards: dict[str, pd.DataFrame]) -> None:
    markdown = to_markdown(boards, caption="Run 1.")
    assert "## camera" in markdown and re.search(r"\|\s+66\.7 \|", markdown) and "Run 1." in markdown


def test_empty_results_say_so() -> None:
    assert "No results." in to_markdown({})
    assert to_text({}) == "No results."


def test_pipes_in_a_status_do_not_break_the_table(boards: dict[str, pd.DataFrame]) -> None:
    board = boards["camera"].assign(status="error (1/1 cells): a | b")
    lines = [line for line in to_markdown({"camera": board}).splitlines() if line.startswith("|")]
    assert len(lines) == 4 and all("a \\| b" in line for line in lines[2:])
    assert len({line.replace("\\|", "").count("|") for line in lines}) == 1


def test_the_terminal_view_shortens_long_statuses(boards: dict[str, pd.DataFrame]) -> None:
    board = boards["camera"].assign(status="error (1/1 cells): " + "x" * 100)
    text = to_text({"camera": board}, status_width=30)
    assert text.startswith("camera\n")
    assert "error (1/1 cells): xxxxxxxx..." in text and "x" * 31 not in text
