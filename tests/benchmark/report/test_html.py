"""Tests of benchmark.report.html: the self-contained page."""

from __future__ import annotations

import pandas as pd

from benchmark.report.html import to_html


def test_html_page_holds_a_rounded_table_per_modality(boards: dict[str, pd.DataFrame]) -> None:
    page = to_html(boards, caption="Run 1.")
    assert page.startswith("<!DOCTYPE html>") and page.rstrip().endswith("</html>")
    assert "<h2>camera</h2>" in page and "<p>Run 1.</p>" in page
    assert "<table" in page and "<td>66.7</td>" in page


def test_text_is_escaped_and_empty_results_say_so(boards: dict[str, pd.DataFrame]) -> None:
    board = boards["camera"].assign(status="error: <script>")
    page = to_html({"a<b": board}, caption="R&D")
    assert "<script>" not in page and "&lt;script&gt;" in page
    assert "<h2>a&lt;b</h2>" in page and "R&amp;D" in page
    assert "No results." in to_html({})


def test_problems_get_an_escaped_section(boards: dict[str, pd.DataFrame]) -> None:
    page = to_html(boards, problems=["plugin 'acme' failed to import: <script>", "second"])
    assert "<h2>Problems</h2>" in page and "<script>" not in page
    assert "<ul><li>plugin &#x27;acme&#x27; failed to import: &lt;script&gt;</li><li>second</li></ul>" in page
    assert "Problems" not in to_html(boards)
