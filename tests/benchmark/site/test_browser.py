"""The site in a real browser from ``file://``: no console errors, boards sort, and a screenshot to look at.

Needs Python playwright and a Chromium at ``/usr/bin/chromium``; skipped
without them.  ``TRACKBENCH_SCREENSHOT=path.png`` also saves the index's
screenshot there.
"""

from __future__ import annotations

import os
import shutil
from pathlib import Path

import pytest

from .conftest import Site

sync_api = pytest.importorskip("playwright.sync_api", reason="the browser tests need Python playwright")


class Browser:
    """A Chromium page that keeps every console error, page error and dialog it meets."""

    def __init__(self, page: sync_api.Page) -> None:
        self.page = page
        self.problems: list[str] = []
        page.on("console", lambda message: message.type == "error" and self.problems.append(message.text))
        page.on("pageerror", lambda error: self.problems.append(f"page error: {error}"))
        page.on("dialog", lambda dialog: (self.problems.append(f"dialog: {dialog.message}"), dialog.dismiss()))

    def open(self, path: Path) -> sync_api.Page:
        self.page.goto(path.resolve().as_uri())
        self.page.wait_for_load_state("load")
        return self.page


@pytest.fixture(scope="module")
def browser(chromium: sync_api.Browser) -> Browser:
    return Browser(chromium.new_page(viewport={"width": 1400, "height": 900}))


def column(page: sync_api.Page, table: str, index: int) -> list[str]:
    return [cell.inner_text() for cell in page.query_selector_all(f"{table} tbody tr td:nth-child({index})")]


def test_index_board_is_a_sortable_datatable(browser: Browser, nightly: Site, tmp_path: Path) -> None:
    page = browser.open(nightly.index)
    board = "#board-0"
    page.wait_for_selector(f"{board}.dataTable")
    headers = [header.inner_text().strip() for header in page.query_selector_all(f"{board} thead th")]
    index = headers.index("correct_pct") + 1
    before = column(page, board, index)
    header = f"{board} thead th:nth-child({index})"
    page.click(header)
    page.wait_for_selector(f"{header}.dt-ordering-asc")
    ascending = column(page, board, index)
    assert ascending == sorted(before, key=float) != before
    page.click(header)
    page.wait_for_selector(f"{header}.dt-ordering-desc")
    assert column(page, board, index) == ascending[::-1]
    page.fill("div.dt-search input", "condensation")
    page.wait_for_function(f"document.querySelectorAll('{board} tbody tr').length === 2")
    page.fill("div.dt-search input", "")
    assert page.is_hidden(f"#{board[1:]}_fallback")
    screenshot = tmp_path / "index.png"
    page.screenshot(path=str(screenshot), full_page=True)
    if os.environ.get("TRACKBENCH_SCREENSHOT"):
        shutil.copyfile(screenshot, os.environ["TRACKBENCH_SCREENSHOT"])
    assert browser.problems == []


def test_tracker_and_cell_pages_load_cleanly(browser: Browser, nightly: Site) -> None:
    page = browser.open(nightly.root / "trackers" / "hough.html")
    page.wait_for_selector("#cells.dataTable")
    assert page.evaluate("[...document.images].every(image => image.complete && image.naturalWidth > 0)")
    with page.expect_navigation(wait_until="load"):
        page.click("#cells tbody a")
    assert "/cells/" in page.url
    assert page.evaluate("[...document.images].every(image => image.complete && image.naturalWidth > 0)")
    assert len(page.query_selector_all(".pictures img")) >= 1
    assert browser.problems == []


def test_hostile_names_stay_text(browser: Browser, hostile: Site) -> None:
    page = browser.open(hostile.index)
    page.wait_for_selector("#board-0.dataTable")
    assert '<script>alert("tracker")</script>' in page.inner_text("#board-0")
    cells = [str(link.get_attribute("href")) for link in page.query_selector_all("#board-0 tbody a[href^='cells/']")]
    assert cells
    for cell in cells:
        browser.open(hostile.root / cell)
    assert browser.problems == []


def test_without_javascript_the_boards_are_plain_tables(chromium: sync_api.Browser, nightly: Site) -> None:
    context = chromium.new_context(java_script_enabled=False)
    try:
        page = context.new_page()
        page.goto(nightly.index.resolve().as_uri())
        assert page.is_hidden("#board-0") and page.is_visible("#board-0_fallback")
        rows = page.query_selector_all("#board-0_fallback tbody tr")
        assert len(rows) == 4
        assert page.is_visible("#board-0_fallback a[href='trackers/hough.html']")
    finally:
        context.close()
