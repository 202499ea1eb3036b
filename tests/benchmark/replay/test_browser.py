"""The replay page in Chromium from ``file://``: it plays, the strip jumps, overlays and belief are drawn, no errors.

The camera page is played with the fake filters; the sonar and stereo
pages of the first-party filters are opened and their marks checked.

Needs Python playwright and a Chromium at ``/usr/bin/chromium`` (skipped
without them).  ``TRACKBENCH_SCREENSHOTS=folder`` keeps the screenshot
(``replay-*.png``) there.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from benchmark.registry import Registry
from benchmark.replay.page import page_data, replay_html, write_replay
from benchmark.replay.record import record_cell

from benchmark.replay.record import Recording

from ..conftest import FakeSequence, make_cell
from ..site.test_browser import Browser, save_for_readme
from .conftest import REAL_CELLS, REAL_FRAMES

sync_api = pytest.importorskip("playwright.sync_api", reason="the browser tests need Python playwright")

FRAMES = 8


def pixel(page: sync_api.Page, canvas: str, u: float, v: float) -> list[int]:
    """The RGBA of a canvas's pixel at ``(u, v)`` in its own coordinates."""
    return page.evaluate(
        f"Array.from(document.getElementById('{canvas}').getContext('2d').getImageData({int(u)}, {int(v)}, 1, 1).data)"
    )


def painted(page: sync_api.Page, canvas: str, r: int, g: int, b: int) -> int:
    """How many pixels of a canvas are close to the colour ``(r, g, b)``."""
    return page.evaluate(
        f"""(() => {{
        const c = document.getElementById('{canvas}'), d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
        let n = 0;
        for (let k = 0; k < d.length; k += 4)
          if (Math.abs(d[k] - {r}) < 40 && Math.abs(d[k + 1] - {g}) < 40 && Math.abs(d[k + 2] - {b}) < 40 && d[k + 3] > 200) n++;
        return n; }})()"""
    )


@pytest.mark.parametrize("tracker", ["fake-particles", "fake-gaussian"])
def test_the_replay_plays_jumps_and_draws(chromium: sync_api.Browser, registry: Registry, tmp_path: Path, tracker: str) -> None:
    recording = record_cell(make_cell(registry.trackers[tracker], FakeSequence("fake/S1", FRAMES)))
    path = write_replay(recording, tmp_path / "replay.html")
    browser = Browser(chromium.new_page(viewport={"width": 1200, "height": 800}))
    page = browser.open(path)
    page.wait_for_function("document.getElementById('frame').dataset.frame === '0'")
    frame = page.evaluate("document.getElementById('frame').dataset")
    marks = page_data(recording)["frames"][0]["marks"]
    assert int(frame["overlays"]) == len(marks) >= 4  # two borders each of truth and estimate, and any particles'
    assert (tracker == "fake-particles") == any(role == "particle" for role, _, _ in marks)
    zoom = 480 / 64
    u1, v1, u2, v2 = recording.frames[0].truth_marks[0].points
    red, green, blue, _ = pixel(page, "frame", (u1 + u2) / 2 * zoom, (v1 + v2) / 2 * zoom)
    assert max(red, green) > 150 > blue  # a border lies where the truth's first chord is (the estimate's may cover it)
    assert painted(page, "frame", 27, 158, 27) > 100  # the truth's borders in green
    assert painted(page, "frame", 214, 39, 40) > 100  # and the estimate's in red
    assert painted(page, "belief", 31, 78, 158) > 20  # particles or the Gaussian's mean
    page.select_option("#speed", "25")
    page.click("#play")
    page.wait_for_function("Number(document.body.dataset.frame) >= 2")
    page.click("#play")  # pause
    box = page.locator("#strip").bounding_box()
    target = 5
    page.mouse.click(box["x"] + (target + 0.5) / FRAMES * box["width"], box["y"] + box["height"] / 2)
    page.wait_for_function(f"document.getElementById('frame').dataset.frame === '{target}'")
    assert page.evaluate("document.body.dataset.frame") == str(target)
    assert page.input_value("#slider") == str(target)
    page.click("#previous")
    assert page.evaluate("document.body.dataset.frame") == str(target - 1)
    save_for_readme(page, f"replay-{tracker}.png", tmp_path)
    assert browser.problems == []


def test_an_address_opens_a_frame_with_the_belief_zoomed_to_it(
    chromium: sync_api.Browser, registry: Registry, tmp_path: Path
) -> None:
    recording = record_cell(make_cell(registry.trackers["fake-particles"], FakeSequence("fake/S1", FRAMES)))
    path = tmp_path / "replay.html"
    path.write_text(replay_html(recording, start=4))
    browser = Browser(chromium.new_page(viewport={"width": 1200, "height": 800}))
    page = browser.open(path)
    page.wait_for_function("document.getElementById('belief').dataset.frame === '4'")  # the page's start
    page.goto(path.as_uri() + "#frame=6")
    page.reload()
    page.wait_for_function("document.getElementById('belief').dataset.frame === '6'")  # the address's frame
    whole = page.evaluate("document.getElementById('belief').toDataURL()")
    page.goto(path.as_uri() + "#frame=6&zoom")
    page.reload()
    page.wait_for_function("document.getElementById('belief').dataset.frame === '6'")
    assert page.is_checked("#zoom") and page.input_value("#slider") == "6"
    zoomed = page.evaluate("document.getElementById('belief').toDataURL()")
    page.uncheck("#zoom")
    assert page.evaluate("document.getElementById('belief').toDataURL()") != zoomed != whole
    assert browser.problems == []


COLOURS = {
    "truth": (27, 158, 27),
    "estimate": (214, 39, 40),
    "measurement": (224, 142, 0),
    "particle": (31, 78, 158),
}
"""The colours of the roles, as the page draws them."""

SEEN = {
    "sonar": ("truth", "estimate", "particle"),
    "stereo": ("estimate", "measurement"),
    "stereo-images": ("estimate",),
}
"""The roles whose colour shows on the last frame's picture (a truth under its estimate may be hidden)."""


@pytest.mark.parametrize("name", sorted(REAL_CELLS))
def test_the_sonar_and_stereo_replays_draw_their_marks(
    chromium: sync_api.Browser, real_recordings: dict[str, Recording], tmp_path: Path, name: str
) -> None:
    recording = real_recordings[name]
    path = write_replay(recording, tmp_path / "replay.html")
    browser = Browser(chromium.new_page(viewport={"width": 1200, "height": 900}))
    page = browser.open(path)
    last = REAL_FRAMES - 1
    page.wait_for_function("document.getElementById('frame').dataset.frame === '0'")
    for _ in range(last):
        page.click("#next")
    page.wait_for_function(f"document.getElementById('frame').dataset.frame === '{last}'")
    marks = page.evaluate(f"JSON.parse(document.getElementById('replay-data').textContent).frames[{last}].marks.length")
    assert int(page.evaluate("document.getElementById('frame').dataset.overlays")) == marks > 0
    width, height = page.evaluate("[document.getElementById('frame').width, document.getElementById('frame').height]")
    assert (width, height) == (recording.frames[last].picture.width, recording.frames[last].picture.height)
    for role in SEEN[name]:
        assert painted(page, "frame", *COLOURS[role]) > 5, role
    assert painted(page, "belief", 31, 78, 158) > 20  # particles or the Gaussian's mean
    shown = "Array.from(document.querySelectorAll('.legend [data-role]')).filter((s) => !s.hidden)"
    shown += ".map((s) => s.dataset.role)"
    roles = {role for frame in page_data(recording)["frames"] for role, _, _ in frame["marks"]}
    assert set(page.evaluate(shown)) == {"measurement", "particle", "covariance"} & roles
    save_for_readme(page, f"replay-{recording.tracker}-{name}.png", tmp_path)
    assert browser.problems == []
