"""The site in a real browser from ``file://``: no console errors, boards sort, plots draw, runs compare.

Needs Python playwright and a Chromium at ``/usr/bin/chromium``; skipped
without them.  ``TRACKBENCH_SCREENSHOT=path.png`` also saves the index's
screenshot there; ``TRACKBENCH_SCREENSHOTS=folder`` saves the index with
its grouped changes open (``nightly-index.png``) and the compare page
(``nightly-compare.png``) there, as the README shows them.
"""

from __future__ import annotations

import os
import shutil
from pathlib import Path

import pytest

from .conftest import HOSTILE_NAME, Site

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


def save_for_readme(page: sync_api.Page, name: str, tmp_path: Path) -> None:
    """A full-page screenshot, kept in ``$TRACKBENCH_SCREENSHOTS`` when that names a folder."""
    screenshot = tmp_path / name
    page.screenshot(path=str(screenshot), full_page=True)
    assert screenshot.stat().st_size > 10_000
    if os.environ.get("TRACKBENCH_SCREENSHOTS"):
        shutil.copyfile(screenshot, Path(os.environ["TRACKBENCH_SCREENSHOTS"]) / name)


def test_tracker_and_cell_pages_draw_their_plots(browser: Browser, nightly: Site) -> None:
    page = browser.open(nightly.root / "trackers" / "hough.html")
    page.wait_for_selector("#cells.dataTable")
    page.wait_for_selector("#trends .main-svg")
    points = page.locator("#trends .scatterlayer .trace").first.locator(".point")
    assert points.count() == 3
    ticks = [str(tick.text_content()) for tick in page.query_selector_all("#trends .xtick text")]
    assert ticks[0].startswith("#1 \u00b7 0123456 \u00b7 2024-06-10") and ticks[2].startswith("#3 ")
    box = points.nth(2).bounding_box()
    assert box is not None
    page.mouse.move(box["x"] + box["width"] / 2, box["y"] + box["height"] / 2)
    page.wait_for_selector("#trends .hovertext")
    assert "#3 \u00b7 0123456" in str(page.text_content("#trends .hovertext"))
    with page.expect_navigation(wait_until="load"):
        page.click("#cells tbody a")
    assert "/cells/" in page.url
    page.wait_for_selector("#frames .main-svg")
    assert page.evaluate("[...document.images].every(image => image.complete && image.naturalWidth > 0)")
    assert len(page.query_selector_all(".pictures img")) >= 1
    assert page.is_visible("tr.changed")
    assert browser.problems == []


def test_index_groups_the_changes_and_opens_each(browser: Browser, nightly: Site, tmp_path: Path) -> None:
    page = browser.open(nightly.index)
    page.wait_for_selector("#board-0.dataTable")
    groups = page.query_selector_all("table.groups > tbody > tr.regression")
    assert len(groups) == 1
    inner = "table.groups > tbody > tr.regression table.inner"
    assert page.is_hidden(inner)
    page.click("table.groups > tbody > tr.regression summary")
    assert page.is_visible(inner)
    assert "correct_pct" in page.inner_text(inner)
    save_for_readme(page, "nightly-index.png", tmp_path)
    assert browser.problems == []


def test_runs_page_leads_to_each_run_and_its_comparison(browser: Browser, nightly: Site, tmp_path: Path) -> None:
    page = browser.open(nightly.root / "runs.html")
    assert [link.inner_text() for link in page.query_selector_all("#runs tbody tr td:first-child a")] == [
        "#3", "#2", "#1"]
    with page.expect_navigation(wait_until="load"):
        page.click("#runs a[href='runs/2.html']")
    assert page.url.endswith("/runs/2.html")
    page.wait_for_selector("#board-0.dataTable")
    with page.expect_navigation(wait_until="load"):
        page.click("a[rel=next]")
    assert page.url.endswith("/runs/3.html")
    with page.expect_navigation(wait_until="load"):
        page.click("nav.neighbours a.compare")
    assert page.input_value("#run-a") == "2" and page.input_value("#run-b") == "3"
    worse = page.query_selector_all("#comparison tbody tr:has(td.worse)")
    assert any("hough" in row.inner_text() and "correct_pct" in row.inner_text() for row in worse)
    page.select_option("#run-b", "2")
    page.wait_for_function("document.querySelectorAll('#comparison tbody tr').length === 0")
    page.select_option("#run-a", "1")
    page.select_option("#run-b", "3")
    assert page.evaluate("location.hash") == "#a=1&b=3"
    rows = [row.inner_text().split("\t") for row in page.query_selector_all("#comparison tbody tr")]
    correct = next(row for row in rows if row[0] == "hough" and row[2] == "correct_pct")
    assert float(correct[3]) > float(correct[4]) and correct[5].startswith("-")
    page.fill("#filter", "condensation")
    assert all(row.inner_text().startswith("condensation") for row in page.query_selector_all("#comparison tbody tr"))
    page.fill("#filter", "")
    save_for_readme(page, "nightly-compare.png", tmp_path)
    assert browser.problems == []


def test_hostile_names_stay_text(browser: Browser, hostile: Site) -> None:
    page = browser.open(hostile.index)
    page.wait_for_selector("#board-0.dataTable")
    assert '<script>alert("tracker")</script>' in page.inner_text("#board-0")
    cells = [str(link.get_attribute("href")) for link in page.query_selector_all("#board-0 tbody a[href^='cells/']")]
    assert cells
    replays = 0
    for cell in cells:
        page = browser.open(hostile.root / cell)
        if page.query_selector("a.replay") is None:
            continue
        replays += 1
        with page.expect_navigation(wait_until="load"):
            page.click("a.replay")
        title = page.inner_text("h1")
        assert "/replays/1/" in page.url and (HOSTILE_NAME in title or "shouting" in title)
        page.wait_for_function("document.querySelector('#strip').width > 0")
        with page.expect_navigation(wait_until="load"):
            page.click("#back")
        assert page.url.endswith(cell)
    assert replays == len(cells)  # every cell failed on a frame (each tracker misses frames)
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


def test_a_closed_loop_cell_page_draws_the_path_over_the_route(browser: Browser, closed_loop_night: Site) -> None:
    cells = closed_loop_night.history.cells()
    (route_cell,) = cells.loc[cells["dataset"] == "routes/short", "id"]
    page = browser.open(closed_loop_night.root / "cells" / f"{route_cell}.html")
    page.wait_for_selector("#top-view .main-svg")
    lines = page.locator("#top-view .scatterlayer .trace path.js-line")
    assert lines.count() == 2  # the cable's route and the vehicle's path
    drawn = [lines.nth(i).get_attribute("d") or "" for i in range(2)]
    assert all(path.startswith("M") and path.count("L") >= 3 for path in drawn), drawn  # polylines, not empty
    boxes = [lines.nth(i).bounding_box() for i in range(2)]
    assert all(box is not None and box["height"] > 200 for box in boxes)  # each runs along the route, up the plot
    legend = [str(text.text_content()) for text in page.query_selector_all("#top-view .legendtext")]
    assert legend[:2] == ["cable", "vehicle"]  # (the out-of-view trace has no point here, so no legend entry)
    page.wait_for_selector("#frames .main-svg")
    index = browser.open(closed_loop_night.index)
    index.wait_for_selector("#board-1.dataTable")
    assert "followed_m" in index.locator("#board-1 thead").inner_text().replace("\u200b", "")
    assert browser.problems == []
