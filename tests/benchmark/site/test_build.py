"""Tests of benchmark.site.build: the pages of a nightly history, their links, figures and escaping."""

from __future__ import annotations

import errno
import json
import multiprocessing
import os
import re
import types
from html.parser import HTMLParser
from pathlib import Path

import pandas as pd
import pytest
from click.testing import CliRunner

from benchmark import cli

from benchmark.errors import DataError
from benchmark.history.database import History
from benchmark.history.regressions import Thresholds
from benchmark.leaderboard import leaderboards
from benchmark.registry import Registry
from benchmark.site import build_site
from benchmark.site import build as site_build
from benchmark.site.build import page_name

from benchmark.selection import Selection

from .conftest import HOSTILE_MESSAGE, HOSTILE_NAME, Site, build, record


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


def test_index_shows_the_regression_of_the_night_as_one_row_with_its_cause(nightly: Site) -> None:
    regressions = section(nightly.index, "Regressions of the night", "Improvements")
    groups = re.findall(r'<tr class="regression">(.*?)</details>', regressions, flags=re.DOTALL)
    assert len(groups) == 1
    (group,) = groups
    assert ">hough</a>" in group and "vote_fraction 0.25 -&gt; 0.5" in group
    headline = re.search(r"<strong>(\w+) ([+-][\d.]+) on [^<]*S2.txt</strong>", group)
    assert headline and headline.group(1) in {"correct_pct", "missed_pct", "rmse_d_px"}
    correct = re.search(r"<code>correct_pct</code>.*?([\d.]+) &rarr; <strong>([\d.]+)</strong>", group, re.DOTALL)
    assert correct and float(correct.group(1)) > float(correct.group(2)) + 2.0
    assert 'href="cells/' in group
    assert "condensation" not in regressions


def test_index_header_names_the_run(nightly: Site) -> None:
    text = " ".join(Tags(nightly.index).text)
    assert "#3" in text and "2024-06-12 02:00 UTC" in text
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
                assert (page.parent / target.split("#")[0]).is_file(), f"{page.name}: {target}"


def figures(page: Path) -> list[dict]:
    """The plotly figures drawn on a page, as the JSON its scripts hand to plotly.js."""
    specs = re.findall(r"const figure = (\{.*?\}); Plotly.newPlot", page.read_text(encoding="utf-8"))
    return [json.loads(spec.replace("<\\/", "</")) for spec in specs]


def test_tracker_page_shows_interactive_trends_by_run_with_the_step(nightly: Site) -> None:
    page = tracker_page(nightly, "hough")
    assert '<script src="../assets/plotly.js"></script>' in page.read_text(encoding="utf-8")
    assert (nightly.root / "assets" / "plotly.js").stat().st_size > 1_000_000
    (figure,) = figures(page)
    labels = figure["layout"]["xaxis"]["ticktext"]
    assert labels == [f"#{run} \u00b7 0123456 \u00b7 2024-06-{day} 02:00" for run, day in ((1, 10), (2, 11), (3, 12))]
    correct = next(trace for trace in figure["data"] if trace["yaxis"] == "y")
    assert correct["x"] == [0, 1, 2] and correct["y"][0] > correct["y"][2] + 2.0
    assert any(shape["x0"] == 1.5 for shape in figure["layout"]["shapes"])
    steps = section(page, "Over the runs", "</section>")
    assert re.search(r"<code>correct_pct</code></td><td>[^<]*S2.txt</td>\s*<td><a href=\"../runs/3.html\">#3", steps)
    cells = section(page, "Cells of the latest run", "</section>")
    assert cells.count('href="../cells/') >= 2


def test_tracker_page_marks_the_changed_parameter(nightly: Site) -> None:
    parameters = section(tracker_page(nightly, "hough"), "<h2>Parameters</h2>", "</section>")
    changed = re.findall(r'<tr class="changed"><th>(\w+)</th><td><del>([^<]*)</del> &rarr;\s*<code>([^<]*)</code>',
                         parameters)
    assert changed == [("vote_fraction", "0.25", "0.5")]
    assert 'href="../runs/2.html">run #2</a>' in parameters
    unchanged = section(tracker_page(nightly, "condensation"), "<h2>Parameters</h2>", "</section>")
    assert 'class="changed"' not in unchanged


def test_cell_page_shows_interactive_frames_pictures_and_changed_parameters(nightly: Site) -> None:
    latest = nightly.history.cells([3])
    hough = latest[latest["tracker"] == "hough"].iloc[0]
    page = nightly.root / "cells" / f"{hough['id']}.html"
    tags = Tags(page)
    images = tags.attributes("img", "src")
    pictures = nightly.history.pictures(int(hough["id"]))
    assert pictures and len(images) == len(pictures)
    for source, picture in zip(images, pictures):
        assert (page.parent / source).read_bytes() == picture.png
    (figure,) = figures(page)
    frames = nightly.history.frames(int(hough["id"]))
    strip = {trace["name"].split()[0]: trace["x"] for trace in figure["data"] if trace["yaxis"] == "y"}
    assert sorted(frame for shown in strip.values() for frame in shown) == sorted(frames["frame"])
    assert len(strip["missed"]) == int((frames["outcome"] == "missed").sum())
    text = " ".join(" ".join(tags.text).split())
    assert f"frame {pictures[0].frame} · {pictures[0].outcome}" in text
    assert "1 parameter changed since run #2" in text
    assert re.search(r'<tr class="changed"><th>vote_fraction</th>', page.read_text(encoding="utf-8"))
    earlier = nightly.history.cells([2])
    earlier = earlier[(earlier["tracker"] == "hough") & (earlier["seed"] == hough["seed"])].iloc[0]
    assert f'href="{earlier["id"]}.html"' in page.read_text(encoding="utf-8")


def test_runs_page_lists_every_run_with_its_counts(nightly: Site) -> None:
    page = nightly.root / "runs.html"
    rows = re.findall(r"<tr>\s*<td><a href=\"runs/(\d+).html\">.*?</tr>", page.read_text(encoding="utf-8"),
                      flags=re.DOTALL)
    assert rows == ["3", "2", "1"]
    body = section(page, '<tbody>', "</tbody>")
    latest = body[: body.index("</tr>")]
    cells = re.findall(r'<td class="num[^"]*">(\d+|–)</td>', latest)
    assert cells[:3] == ["4", "4", "0"] and int(cells[3]) >= 2
    first = body[body.rindex("<tr>"):]
    assert re.findall(r'<td class="num[^"]*">(\d+|–)</td>', first)[3:] == ["0", "0"]


def test_run_pages_link_their_neighbours_and_show_their_changes(nightly: Site) -> None:
    second = nightly.root / "runs" / "2.html"
    links = Tags(second).attributes("a", "href")
    assert "../runs/1.html" in links and "../runs/3.html" in links and "../compare.html#a=1&b=2" in links
    assert "No regressions against the 1 earlier run" in " ".join(" ".join(Tags(second).text).split())
    third = section(nightly.root / "runs" / "3.html", "Regressions", "Improvements")
    assert "vote_fraction 0.25 -&gt; 0.5" in third
    first = " ".join(" ".join(Tags(nightly.root / "runs" / "1.html").text).split())
    assert "nothing to compare it with yet" in first
    board = section(nightly.root / "runs" / "1.html", 'id="board-0_fallback"', "</table>")
    assert ">hough</a>" in board and ">condensation</a>" in board and "../cells/" in board


def test_compare_page_holds_every_runs_means(nightly: Site) -> None:
    html = (nightly.root / "compare.html").read_text(encoding="utf-8")
    data = json.loads(re.search(r'<script id="run-means" type="application/json">(.*?)</script>', html).group(1))
    assert sorted(data["values"]) == ["1", "2", "3"]
    row = next(i for i, (tracker, _) in enumerate(data["rows"]) if tracker == "hough")
    correct = data["metrics"].index("correct_pct")
    cells = nightly.history.cells()
    for run in (1, 3):
        of_run = cells[(cells["run_id"] == run) & (cells["tracker"] == "hough")]
        assert data["values"][str(run)][str(row)][correct] == pytest.approx(of_run["correct_pct"].mean())
    assert html.count("<option") == 6


def test_compare_writes_a_self_contained_page(nightly: Site, tmp_path: Path) -> None:
    page = tmp_path / "compare.html"
    result = CliRunner().invoke(
        cli.main, ["compare", "1", "3", "--history", nightly.history.location, "--html", str(page)]
    )
    assert result.exit_code == 0, result.output
    html = page.read_text(encoding="utf-8")
    tags = Tags(page)
    assert not tags.attributes("script", "src") and not tags.attributes("a", "href") and "<script" not in html
    regressions = section(page, "Regressions", "Improvements")
    assert "vote_fraction 0.25 -&gt; 0.5" in regressions and "correct_pct" in regressions
    every = section(page, "Every metric", "</table>")
    assert re.search(r"<td>hough</td><td>[^<]*S2.txt</td><td><code>correct_pct</code></td>", every)


def test_compare_html_names_a_file_it_cannot_write(nightly: Site, tmp_path: Path) -> None:
    page = tmp_path / "missing" / "compare.html"
    result = CliRunner().invoke(
        cli.main, ["compare", "1", "3", "--history", nightly.history.location, "--html", str(page)]
    )
    assert result.exit_code == 2 and f"comparison page {page}" in result.output


def test_first_run_has_nothing_to_compare(first_night: Site) -> None:
    text = " ".join(" ".join(Tags(first_night.index).text).split())
    assert "nothing to compare it with yet" in text
    assert 'class="regression"' not in first_night.index.read_text(encoding="utf-8")


def test_plugin_strings_are_escaped_on_every_page(hostile: Site) -> None:
    assert any(page.parts[-3] == "replays" for page in pages(hostile))
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

    monkeypatch.setitem(site_build.KINDS, "cell", disk_full)
    with pytest.raises(DataError, match=f"site {tmp_path}: cannot write it: No space left on device"):
        # Other thresholds: every page is drawn again, none is reused.
        build_site(first_night.history, tmp_path, registry.modalities, thresholds=Thresholds(window=4))
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


def fake_history(fakes: types.ModuleType, folder: Path, days: list[int]) -> tuple[Registry, History]:
    """A history of fake trackers on ``fake/S1``, one run recorded per day of ``days``."""
    registry = fakes.make_registry((fakes.Perfect, fakes.Noisy))
    history = History(folder / "history.sqlite")
    selection = Selection(trackers=("perfect", "noisy"), datasets=("fake/S1",), seeds=2)
    record(registry, history, selection, folder / "run", days)
    return registry, history


def html_files(site: Path) -> dict[str, bytes]:
    """Every page the site shows, by its path in the site."""
    shown = (site / ".current").resolve()
    return {path.relative_to(shown).as_posix(): path.read_bytes() for path in sorted(shown.rglob("*.html"))}


def test_pages_drawn_in_parallel_equal_those_drawn_one_by_one(fakes: types.ModuleType, tmp_path: Path) -> None:
    registry, history = fake_history(fakes, tmp_path, [10, 11])
    build_site(history, tmp_path / "one", registry.modalities, workers=1)
    build_site(history, tmp_path / "two", registry.modalities, workers=2)
    one, two = html_files(tmp_path / "one"), html_files(tmp_path / "two")
    assert len(one) >= site_build.POOL_FROM and one == two


def test_a_rebuild_reuses_the_pages_whose_inputs_did_not_change(fakes: types.ModuleType, tmp_path: Path) -> None:
    registry, history = fake_history(fakes, tmp_path, [10])
    site = tmp_path / "site"
    build_site(history, site, registry.modalities)
    before = {name: (site / name).stat().st_ino for name in html_files(site)}
    first_cells = [name for name in before if name.startswith("cells/")]
    record(registry, history, Selection(trackers=("perfect", "noisy"), datasets=("fake/S1",), seeds=2),
           tmp_path / "again", [11])
    progress: list[tuple[int, int]] = []
    build_site(history, site, registry.modalities, report=lambda done, total: progress.append((done, total)))
    after = {name: (site / name).stat().st_ino for name in html_files(site)}
    assert first_cells and all(after[name] == before[name] for name in first_cells)
    assert after["index.html"] != before["index.html"] and after["runs/1.html"] != before["runs/1.html"]
    new_cells = [name for name in after if name.startswith("cells/") and name not in before]
    assert len(new_cells) == len(first_cells)
    total = progress[-1][1]
    assert [done for done, _ in progress] == list(range(1, total + 1)) and {t for _, t in progress} == {total}
    assert total == len(after) + 1  # every page and the assets


def test_pages_show_the_changes_the_nightly_kept(fakes: types.ModuleType, tmp_path: Path) -> None:
    registry, history = fake_history(fakes, tmp_path, [10, 11])
    kept = pd.DataFrame([dict(
        tracker="noisy", dataset="fake/S1", metric="correct_pct", kind="accuracy", before=90.0, after=70.0,
        change=-20.0, low=-25.0, high=-15.0, verdict="regression", cause="sigma_px 1.0 -> 9.0", effects=10.0,
        note="frames with an estimate 300 -> 212",
    )])
    history.record_changes(2, kept)
    site = tmp_path / "site"
    build_site(history, site, registry.modalities)
    for page in (site / "index.html", site / "runs" / "2.html"):
        regressions = section(page, "Regressions", "Improvements")
        assert "sigma_px 1.0 -&gt; 9.0" in regressions and "correct_pct -20.0 on fake/S1" in regressions
        assert "frames with an estimate 300 -&gt; 212" in regressions
    runs = section(site / "runs.html", "<tbody>", "</tr>")
    assert re.findall(r'<td class="num[^"]*">(\d+|–)</td>', runs)[3:] == ["1", "0"]


def test_a_speed_change_a_repeat_did_not_hold_has_its_own_section(fakes: types.ModuleType, tmp_path: Path) -> None:
    registry, history = fake_history(fakes, tmp_path, [10, 11])
    kept = pd.DataFrame([dict(
        tracker="noisy", dataset="fake/S1", metric="cpu_fps", kind="speed", before=900.0, after=700.0,
        change=-200.0, low=-250.0, high=-150.0, verdict="unconfirmed", cause="", effects=2.0,
        note="repeat 880: within the noise, not held",
    )])
    history.record_changes(2, kept)
    site = tmp_path / "site"
    build_site(history, site, registry.modalities)
    page = site / "runs" / "2.html"
    held = section(page, "Speed changes a repeat did not hold", "Leaderboards")
    assert "cpu_fps -200" in held and "within the noise, not held" in held
    assert "cpu_fps" not in section(page, "Regressions", "Improvements")


def test_run_pages_show_the_boards_the_nightly_kept(
    fakes: types.ModuleType, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    registry, history = fake_history(fakes, tmp_path, [10, 11])
    build_site(history, tmp_path / "site", registry.modalities, workers=1)
    worked_out = (tmp_path / "site" / "index.html").read_text()
    assert "Each metric's mean over the seeds' summaries" in (tmp_path / "site" / "runs" / "1.html").read_text()
    cells = history.cells([2])
    frames = pd.concat([history.frames(int(cell)).assign(cell_id=int(cell)) for cell in cells["id"]])
    kept = {modality: board.assign(correct_pct=12.3456)
            for modality, board in leaderboards(cells, frames, registry.modalities).items()}
    monkeypatch.setattr(History, "boards", lambda self, run_id: kept)
    build_site(history, tmp_path / "again", registry.modalities, workers=1)
    index, first = (tmp_path / "again" / "index.html").read_text(), (tmp_path / "again" / "runs" / "1.html").read_text()
    assert ">12.3" not in worked_out and ">12.3" in index
    assert ">12.3" in first and "Each metric's mean over the seeds' summaries" not in first


def test_the_closed_loop_board_stands_apart_and_links_its_cells(closed_loop_night: Site) -> None:
    html = closed_loop_night.index.read_text(encoding="utf-8")
    assert "<h3>camera</h3>" in html and "<h3>camera: routes, closed loop</h3>" in html
    board = section(closed_loop_night.index, 'id="board-1_fallback"', "</table>")
    assert "followed_<wbr>m" in board and "routes/short" in board and "fake/S1" not in board
    cells = closed_loop_night.history.cells()
    (route_cell,) = cells.loc[cells["dataset"] == "routes/short", "id"]
    assert f'href="cells/{route_cell}.html"' in board
    assert "followed_<wbr>m" not in section(closed_loop_night.index, 'id="board-0_fallback"', "</table>")


def test_a_closed_loop_cell_page_draws_its_path_over_the_route_from_above(closed_loop_night: Site) -> None:
    from .conftest import SHORT_ROUTE

    cells = closed_loop_night.history.cells()
    (route_cell,) = cells.loc[cells["dataset"] == "routes/short", "id"]
    page = closed_loop_night.root / "cells" / f"{route_cell}.html"
    assert 'id="path"' in page.read_text(encoding="utf-8")
    top = next(figure for figure in figures(page) if figure["data"][0]["name"] == "cable")
    cable, vehicle, hidden = top["data"]
    length = sum(leg["length_m"] for leg in SHORT_ROUTE["legs"])
    assert cable["y"][-1] == pytest.approx(length, abs=0.01) and cable["x"][-1] > 0  # the route turns right
    frames = closed_loop_night.history.frames(int(route_cell))
    assert len(vehicle["x"]) == len(frames) and vehicle["x"][0] == pytest.approx(SHORT_ROUTE["start_offset_m"])
    assert abs(vehicle["x"][-1] - cable["x"][-1]) < abs(vehicle["x"][0])  # steered towards the cable
    assert hidden["name"].startswith("cable out of view") and "stretched" in page.read_text(encoding="utf-8")
    (open_cell,) = cells.loc[cells["dataset"] == "fake/S1", "id"]
    assert 'id="path"' not in (closed_loop_night.root / "cells" / f"{open_cell}.html").read_text(encoding="utf-8")


def test_a_closed_loop_cell_whose_route_the_build_does_not_know_says_so(
    closed_loop_night: Site, tmp_path: Path, fakes: types.ModuleType
) -> None:
    from benchmark.metrics.closed_loop import METRICS

    registry = fakes.make_registry((fakes.Perfect,))
    metrics = registry.metrics
    for metric in METRICS:
        metrics = metrics.adding(metric)
    index = build_site(closed_loop_night.history, tmp_path / "site", registry.modalities, metrics=metrics)
    cells = closed_loop_night.history.cells()
    (route_cell,) = cells.loc[cells["dataset"] == "routes/short", "id"]
    text = (index.parent / "cells" / f"{route_cell}.html").read_text(encoding="utf-8")
    assert 'id="path"' in text and "do not declare its route" in text and '"name":"cable"' not in text
