"""The labeller in a real browser: drag borders on two key frames, reload, interpolate, save, read the file back.

Needs Python playwright and a Chromium at ``/usr/bin/chromium`` (the
``chromium`` fixture of ``tests/benchmark/conftest.py``); skipped without them.
"""

from __future__ import annotations

import math
import urllib.error
import urllib.request
from pathlib import Path

import pytest

from benchmark.modalities.camera.geometry import Line, cable_borders, cable_from_borders, pixel_to_model
from benchmark.modalities.camera.io.sequence_file import read_sequence_file
from benchmark.modalities.camera.labeller.document import open_document
from benchmark.modalities.camera.model import CableState

from .conftest import N_FRAMES, SIZE, served

sync_api = pytest.importorskip("playwright.sync_api", reason="the browser tests need Python playwright")

Point = tuple[float, float]
KEY_FRAMES: dict[int, dict[str, tuple[Point, Point]]] = {
    0: {"left": ((20.0, 0.0), (24.0, 47.0)), "right": ((40.0, 0.0), (37.0, 47.0))},
    N_FRAMES - 1: {"left": ((10.0, 0.0), (17.0, 47.0)), "right": ((29.0, 0.0), (33.0, 47.0))},
}
"""Where the ends of each border are dragged, top end first, in pixels: on the top and bottom rows."""


def settle(page: sync_api.Page) -> None:
    """Wait until the page has finished its last action and redrawn."""
    page.wait_for_selector('#labeller[data-pending="0"]')


def drag(page: sync_api.Page, border: str, end: int, target: Point) -> None:
    """Drag the handle at one end of a border to the pixel ``target`` of the frame."""
    box = page.locator(f'.handle[data-border="{border}"][data-end="{end}"]').bounding_box()
    assert box is not None
    x, y = page.evaluate(
        "([u, v]) => { const p = new DOMPoint(u, v).matrixTransform(document.getElementById('view').getScreenCTM());"
        " return [p.x, p.y]; }",
        list(target),
    )
    page.mouse.move(box["x"] + box["width"] / 2, box["y"] + box["height"] / 2)
    page.mouse.down()
    page.mouse.move(x, y, steps=4)
    page.mouse.up()
    settle(page)


def interpolate_and_save(page: sync_api.Page, between: int) -> None:
    """Press ``I`` and ``S``; the page must say it interpolated ``between`` frames, then that it saved."""
    page.keyboard.press("i")
    settle(page)
    assert page.inner_text("#message") == f"interpolated {between} frames"
    page.keyboard.press("s")
    settle(page)
    assert page.inner_text("#saved") == "saved"


def state_through(borders: dict[str, tuple[Point, Point]]) -> CableState:
    return cable_from_borders(*(Line.from_pixels(*borders[side], SIZE) for side in ("left", "right")))


def distance(line: Line, point: tuple[float, float]) -> float:
    """Distance of a model point from a line."""
    return abs((point[0] - line.x0) * line.dy - (point[1] - line.y0) * line.dx)


def test_drag_two_key_frames_interpolate_and_save(chromium: sync_api.Browser, image_folder: Path) -> None:
    document = open_document(image_folder)
    problems: list[str] = []
    with served(document) as url:
        page = chromium.new_page(viewport={"width": 1400, "height": 900})
        page.on("console", lambda message: message.type == "error" and problems.append(message.text))
        page.on("pageerror", lambda error: problems.append(f"page error: {error}"))
        page.goto(url)
        settle(page)
        for index, borders in KEY_FRAMES.items():
            page.keyboard.press("End" if index else "Home")
            settle(page)
            for border, ends in borders.items():
                for end, target in enumerate(ends):
                    drag(page, border, end, target)
            assert page.inner_text("#kind") == "key frame"
        page.reload()  # the unsaved key frames survive in the page's draft
        settle(page)
        assert page.inner_text("#saved") == "unsaved changes"
        interpolate_and_save(page, N_FRAMES - 2)
        assert problems == []
    first, last = (state_through(KEY_FRAMES[index]) for index in sorted(KEY_FRAMES))
    rows = read_sequence_file(document.output)
    assert [row.image for row in rows] == list(document.images)
    for index, row in enumerate(rows):
        t = index / (N_FRAMES - 1)
        expected = CableState.from_array(first.as_array() + t * (last.as_array() - first.as_array()))
        for saved, wanted in zip(cable_borders(row.cable), cable_borders(expected), strict=True):
            ends = [pixel_to_model(*end, SIZE) for end in _row_ends(wanted)]
            assert max(distance(saved, end) for end in ends) < 0.5, (index, row.cable, expected)


def _row_ends(line: Line) -> list[Point]:
    """The pixel points where a near-vertical line crosses the top and bottom rows of the frame."""
    ends = []
    for v in (0.0, SIZE[1] - 1.0):
        _, y = pixel_to_model(0.0, v, SIZE)
        s = (y - line.y0) / line.dy
        x = line.x0 + s * line.dx
        ends.append((x + (SIZE[0] - 1) / 2.0, v))
    return ends


def test_the_server_refuses_a_missing_token_and_a_path_traversal(
    chromium: sync_api.Browser, image_folder: Path
) -> None:
    document = open_document(image_folder)
    with served(document) as url:
        root = url.rsplit("/", 2)[0] + "/"
        page = chromium.new_page()
        response = page.goto(root + "frames/0")
        assert response is not None and response.status == 403
        assert page.request.get(url + "frames/..%2F..%2Fframes.txt").status == 404
        assert page.request.get(url + "frames/0").headers["content-type"] == "image/png"
        with pytest.raises(urllib.error.HTTPError) as refused:
            urllib.request.urlopen(root + "api/sequence")
        assert refused.value.code == 403


def test_typed_values_copy_no_cable_next_unlabelled_and_undo_by_keyboard(
    chromium: sync_api.Browser, image_folder: Path
) -> None:
    document = open_document(image_folder)
    typed = {"#d": "2", "#alpha": "5", "#w": "10", "#beta": "1"}
    with served(document) as url:
        page = chromium.new_page(viewport={"width": 1400, "height": 900})
        page.goto(url)
        settle(page)
        for selector, value in typed.items():
            page.fill(selector, value)
            page.press(selector, "Enter")
            settle(page)
        assert page.inner_text("#kind") == "key frame"
        for key, position, kind in [
            ("c", 2, "key frame"),
            ("ArrowRight", 3, "unlabelled"),
            ("x", 3, "no cable visible"),
            ("n", 4, "unlabelled"),
            ("z", 3, "unlabelled"),
            ("x", 3, "no cable visible"),
            ("ArrowLeft", 2, "key frame"),
        ]:
            page.keyboard.press(key)
            settle(page)
            assert page.inner_text("#position").startswith(f"frame {position} / {N_FRAMES}"), key
            assert page.inner_text("#kind") == kind, key
        page.keyboard.press("Control+s")
        settle(page)
        assert page.inner_text("#saved") == "saved"
    rows = read_sequence_file(document.output)
    expected = [2.0, math.radians(5.0), 10.0, math.radians(1.0)]
    for row in rows[:2]:
        assert row.cable.as_array().tolist() == pytest.approx(expected)
    assert [row.cable.is_known for row in rows] == [True, True] + [False] * (N_FRAMES - 2)
