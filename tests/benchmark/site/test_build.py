"""Tests of benchmark.site.build: the pages of a nightly history, their links, figures and escaping."""

from __future__ import annotations

import errno
import multiprocessing
import os
import re
from html.parser import HTMLParser
from pathlib import Path

import pytest

from benchmark.errors import DataError
from benchmark.history.database import History
from benchmark.registry import Registry
from benchmark.site import build_site
from benchmark.site.build import page_name

from .conftest import HOSTILE_MESSAGE, HOSTILE_NAME, Site, build


class Tags(HTMLParser):
    """The start tags of a page with their attributes, and its text."""

    def __init__(self, page: Path) -> None:
        super().__init__()
        self.tags: list[tuple[str, dict[str, str | None]]] = []
        self.text: list[str] = []
        self.feed(page.read_text(encoding="utf-8"))

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        self.tags.append((tag, dict(attrs)))

    def handle_data(self, data: str) -> None:
        self.text.append(data)

    def attributes(self, tag: str, name: str) -> list[str]:
        return [str(attrs[name]) for found, attrs in self.tags if found == tag and attrs.get(name)]


def section(page: Path, start: str, end: str) -> str:
    text = page.read_text(encoding="utf-8")
    return text[text.index(start) : text.index(end, text.index(start))]


def pages(site: Site) -> list[Path]:
    return sorted(site.root.rglob("*.html"))


def tracker_page(site: Site, tracker: str) -> Path:
    return site.root / "trackers" / f"{page_name(tracker)}.html"


def test_index_names_the_regression_of_the_night(nightly: Site) -> None:
    regressions = section(nightly.index, "Regressions of the night", "Improvements")
    rows = re.findall(r'<tr class="regression">(.*?)</tr>', regressions, flags=re.DOTALL)
    correct = next(row for row in rows if "correct_pct" in row)
    assert ">hough</a>" in correct and "S2.txt" in correct
    before, after = map(float, re.findall(r"([\d.]+) &rarr; <strong>([\d.]+)</strong>", correct)[0])
    assert before > after + 2.0
    assert re.search(r"<td>[^<]*(vote_fraction|parameters)[^<]*</td>", correct)
    assert 'href="cells/' in correct
    assert not [row for row in rows if ">condensation</a>" in row and "correct_pct" in row]


def test_index_header_names_the_run(nightly: Site) -> None:
    text = " ".join(Tags(nightly.index).text)
    assert "#4" in text and "2024-06-13 02:00 UTC" in text
    assert "0.1.0" in text and "0123456789ab" in text and "test cpu" in text


def test_index_has_one_interactive_board_per_modality(nightly: Site) -> None:
    html = nightly.index.read_text(encoding="utf-8")
    assert "<h3>camera</h3>" in html
    assert html.count('<table id="board-0"') == 1
    assert '<script src="assets/itables.js"></script>' in html
    assert (nightly.root / "assets" / "itables.js").stat().st_size > 100_000


def test_board_links_trackers_and_dataset_rows(nightly: Site) -> None:
    board = section(nightly.index, 'id="board-0_fallback"', "</table>")
    assert '<a href="trackers/hough.html">hough</a>' in board
    assert '<a href="trackers/condensation.html">condensation</a>' in board
    cells = {int(cell_id) for cell_id in re.findall(r'href="cells/(\d+).html"', board)}
    latest = nightly.history.cells([int(nightly.history.runs()["id"].iloc[-1])])
    assert cells == set(latest["id"])


def test_every_link_and_image_of_every_page_exists(nightly: Site) -> None:
    for page in pages(nightly):
        tags = Tags(page)
        targets = [*tags.attributes("a", "href"), *tags.attributes("img", "src"), *tags.attributes("script", "src")]
        for target in targets:
            if not target.startswith(("http://", "https://", "#")):
                assert (page.parent / target).is_file(), f"{page.name}: {target}"


def test_tracker_page_shows_trends_with_the_step(nightly: Site) -> None:
    page = tracker_page(nightly, "hough")
    (figure,) = Tags(page).attributes("img", "src")
    assert figure.endswith(".png") and (page.parent / figure).read_bytes().startswith(b"\x89PNG")
    steps = section(page, "Over the history", "</section>")
    assert re.search(r"<code>correct_pct</code></td><td>[^<]*S2.txt</td><td>2024-06-12</td>", steps)
    cells = section(page, "Cells of this run", "</section>")
    assert cells.count('href="../cells/') >= 2


def test_cell_page_shows_outcome_strip_errors_and_pictures(nightly: Site) -> None:
    latest = nightly.history.cells([int(nightly.history.runs()["id"].iloc[-1])])
    hough = latest[latest["tracker"] == "hough"].iloc[0]
    page = nightly.root / "cells" / f"{hough['id']}.html"
    tags = Tags(page)
    images = tags.attributes("img", "src")
    assert images[0] == f"{hough['id']}-frames.png"
    pictures = nightly.history.pictures(int(hough["id"]))
    assert pictures and len(images) == 1 + len(pictures)
    for source, picture in zip(images[1:], pictures):
        assert (page.parent / source).read_bytes() == picture.png
    text = " ".join(" ".join(tags.text).split())
    assert f"frame {pictures[0].frame} · {pictures[0].outcome}" in text
    assert "vote_fraction" in text and "missed" in text


def test_first_run_has_nothing_to_compare(first_night: Site) -> None:
    text = " ".join(" ".join(Tags(first_night.index).text).split())
    assert "nothing to compare it with yet" in text
    assert 'class="regression"' not in first_night.index.read_text(encoding="utf-8")


def test_plugin_strings_are_escaped_on_every_page(hostile: Site) -> None:
    for page in pages(hostile):
        html = page.read_text(encoding="utf-8")
        assert HOSTILE_NAME not in html and HOSTILE_MESSAGE not in html, page.name
    index = hostile.index.read_text(encoding="utf-8")
    assert "&lt;script&gt;alert(&#34;tracker&#34;)&lt;/script&gt;" in index
    assert tracker_page(hostile, HOSTILE_NAME).is_file()
    assert re.fullmatch(r"[A-Za-z0-9._-]+", page_name(HOSTILE_NAME))
    failed = hostile.history.cells()
    failed = failed[failed["status"] == "error"].iloc[0]
    cell = (hostile.root / "cells" / f"{failed['id']}.html").read_text(encoding="utf-8")
    assert "&lt;img src=x onerror=alert(1)&gt;" in cell


def test_rebuild_replaces_the_site_and_keeps_other_files(
    first_night: Site, registry: Registry, tmp_path: Path
) -> None:
    (tmp_path / "cells").mkdir()
    (tmp_path / "cells" / "999.html").write_text("stale")
    (tmp_path / "notes.txt").write_text("mine")
    site = build(first_night.history, tmp_path, registry)
    assert not (tmp_path / "cells" / "999.html").exists()
    assert (tmp_path / "notes.txt").read_text() == "mine"
    assert site.index == tmp_path / "index.html" and site.index.is_file()
    assert sorted(path.name for path in tmp_path.iterdir() if path.name.startswith(".")) == [".builds", ".current", ".lock"]
    assert [path.name for path in (tmp_path / ".builds").iterdir()] == [Path(os.readlink(tmp_path / ".current")).name]


def test_empty_history_is_an_error(registry: Registry, tmp_path: Path) -> None:
    with History(tmp_path / "history.sqlite") as history, pytest.raises(DataError, match="no runs"):
        build_site(history, tmp_path / "site", registry.modalities)
    assert not (tmp_path / "site" / "index.html").exists()



def site_state(site: Path) -> tuple[bytes, list[str]]:
    """What a reader of ``site`` sees: the index's bytes, and every page it links that is missing."""
    index = (site / "index.html").read_bytes()
    links = re.findall(r'href="((?:trackers|cells)/[^"#]+)"', index.decode())
    return index, [target for target in links if not (site / target).is_file()]


def test_a_build_that_fails_part_way_leaves_the_site_as_it_was_and_says_why(
    first_night: Site, registry: Registry, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    build(first_night.history, tmp_path, registry)
    before, missing = site_state(tmp_path)
    assert not missing

    def disk_full(*args: object, **kwargs: object) -> None:
        raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr("benchmark.site.build._cell", disk_full)
    with pytest.raises(DataError, match=f"site {tmp_path}: cannot write it: No space left on device"):
        build_site(first_night.history, tmp_path, registry.modalities)
    assert site_state(tmp_path) == (before, [])
    assert len(list((tmp_path / ".builds").iterdir())) == 1


def test_what_a_killed_build_left_is_removed_and_two_builds_are_kept(
    first_night: Site, registry: Registry, tmp_path: Path
) -> None:
    builds = tmp_path / ".builds"
    shown = []
    for _ in range(3):
        build(first_night.history, tmp_path, registry)
        shown.append(Path(os.readlink(tmp_path / ".current")).name)
        (builds / "staging-killed").mkdir()  # as a build killed while writing leaves it
    build(first_night.history, tmp_path, registry)
    newest = Path(os.readlink(tmp_path / ".current")).name
    assert sorted(path.name for path in builds.iterdir()) == sorted([shown[-1], newest])
    assert not site_state(tmp_path)[1]


def _build_in_a_process(history: Path, site: Path) -> None:
    from benchmark.plugins import load_registry

    with History(history) as database:
        build_site(database, site, load_registry().modalities)


def test_builds_of_one_site_at_once_take_turns_and_leave_it_whole(first_night: Site, tmp_path: Path) -> None:
    context = multiprocessing.get_context("fork")
    processes = [
        context.Process(target=_build_in_a_process, args=(first_night.history.location, tmp_path)) for _ in range(4)
    ]
    for process in processes:
        process.start()
    for process in processes:
        process.join()
    assert [process.exitcode for process in processes] == [0, 0, 0, 0]
    assert not site_state(tmp_path)[1]
    assert len(list((tmp_path / ".builds").iterdir())) == 2
