"""Tests of benchmark.report.markdown: the Markdown page and the terminal view."""

from __future__ import annotations

import re

import pandas as pd
import pytest

from benchmark.report.markdown import escape_markdown, to_markdown, to_text

NASTY = {
    "html": "<img src=x onerror=alert(1)>",
    "emphasis": "**bold** _it_ ~~gone~~",
    "link": "[link](http://x) ![image](http://y)",
    "code": "`rm -rf` ```",
    "pipe": "a | b",
    "newline": "two\nlines",
}


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


@pytest.mark.parametrize(
    ("text", "markdown"),
    [
        ("<img src=x onerror=alert(1)>", "&lt;img src=x onerror=alert(1)&gt;"),
        ("**bold** _it_ ~~gone~~", r"\*\*bold\*\* \_it\_ \~\~gone\~\~"),
        ("[link](http://x)", r"\[link\](http://x)"),
        ("`x` $y$", r"\`x\` \$y\$"),
        ("a | b", r"a \| b"),
        ("a\\|b", r"a\\\|b"),
        ("two\nlines\r\n  here", "two lines here"),
        ("R&D &amp;", "R&amp;D &amp;amp;"),
        ("# heading", r"\# heading"),
        ("- item", r"\- item"),
        ("1. item", r"1\. item"),
        ("66.7", "66.7"),
        ("stereo/case1-slow", "stereo/case1-slow"),
    ],
)
def test_escape_markdown_makes_text_literal(text: str, markdown: str) -> None:
    assert escape_markdown(text) == markdown


def test_plugin_text_shows_as_literal_text_everywhere(boards: dict[str, pd.DataFrame]) -> None:
    board = boards["camera"].assign(tracker=NASTY["html"], dataset=NASTY["link"], status=NASTY["newline"])
    board["init"] = [NASTY["pipe"], NASTY["code"]]
    markdown = to_markdown(
        {f"camera {NASTY['emphasis']}": board}, caption=NASTY["html"], problems=list(NASTY.values())
    )
    assert "<" not in markdown and "&lt;img src=x onerror=alert(1)&gt;" in markdown
    assert "**" not in markdown and "## camera \\*\\*bold\\*\\* \\_it\\_ \\~\\~gone\\~\\~" in markdown
    assert "](" not in markdown.replace("\\](", "") and "\\[link\\](http://x)" in markdown
    assert re.search(r"(?<!\\)`", markdown) is None
    table = [line for line in markdown.splitlines() if line.startswith("|")]
    assert len(table) == 2 + len(board) and all("two lines" in line for line in table[2:])
    assert len({line.replace("\\|", "").count("|") for line in table}) == 1
    problems = markdown.split("## Problems\n\n", 1)[1].splitlines()
    assert problems[: len(NASTY)] == [f"- {escape_markdown(text)}" for text in NASTY.values()]


def test_problems_close_the_page_and_the_terminal_view(boards: dict[str, pd.DataFrame]) -> None:
    problem = "plugin 'acme' (acme-dist 1.0) failed to import: ImportError: No module named 'acme'"
    assert to_markdown(boards, problems=[problem]).endswith(f"## Problems\n\n- {escape_markdown(problem)}\n")
    assert "Problems" not in to_markdown(boards) and "Problems" not in to_text(boards)
    assert to_text(boards, problems=[problem, "two\nlines"]).endswith(f"Problems\n\n- {problem}\n- two lines")
    assert to_text({}, problems=[problem]) == f"No results.\n\nProblems\n\n- {problem}"
