"""The nightly site: every run of a history, its latest run first, page by page.

:func:`build_site` writes::

    index.html             the latest run: its changes grouped by cause, one full board per modality
    runs.html              every run: when, commit, machine, load, cells, regressions
    runs/<id>.html         one run: its changes against the runs before it, its boards as the nightly kept them
    compare.html           any two runs side by side, picked in the browser
    trackers/<name>.html   a tracker's headline metrics over the runs (interactive), its cells, changed parameters
    cells/<id>.html        one cell of a run that keeps its details: frames (interactive), pictures, parameters,
                           its replay or why there is none; a closed-loop cell's path over its route from above
    replays/<run>/<id>.html  a cell's replay page as its nightly recorded it (:mod:`benchmark.history.replays`)
    assets/itables.js      the table library (:mod:`benchmark.site.tables`)
    assets/plotly.js       the plotting library (:mod:`benchmark.site.figures`)

The site changes in one step.  A build writes its pages into a folder of
their own, ``site/.builds/run-N-XXXX``; when all are written, the link
``site/.current`` is pointed at it by one rename, and the names above are
links through ``.current``.  So a reader (a browser, a web server, a copy)
sees the previous site or the new one, never a mixture, and a build that
is killed or fails (a full or read-only disk is a
:class:`~benchmark.errors.DataError` naming the site) leaves the previous
site as it was.  Builds take turns (a lock, ``site/.lock``): each removes
what killed builds left, and every build but the new one and the one
before it, which a reader may still be browsing.

A build draws only what changed.  Each page has a hash of its inputs
(:func:`_plan`): the code and templates of trackbench, the thresholds and
metrics, and what of the history the page shows.  A history only grows:
a run and its cells never change once recorded, only the details of old
runs are dropped, so a run's page is named by the runs up to it, its
successor and whether it keeps details, and a cell's page by its row and
the cell it is compared with (and what its nightly did about its replay).
A replay page is named by the hash of the page kept in the history, so
it is written once and linked from build to build after.  The build's ``manifest.json`` keeps each
page's hash and files; a page whose hash equals the shown build's is
hard-linked from it (copied where links fail) instead of drawn.  The
pages to draw are drawn by worker processes, forked with the history
loaded (:data:`WORKERS`), each connecting to the database on its own.
"""

from __future__ import annotations

import hashlib
import json
import math
import multiprocessing
import os
import shutil
import tempfile
import uuid
from collections.abc import Callable, Iterator, Mapping
from concurrent.futures import ProcessPoolExecutor, as_completed
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import filelock
import pandas as pd

import benchmark
from benchmark.closedloop.route import Route
from benchmark.errors import DataError
from benchmark.files import make_folder
from benchmark.history.database import RECORDED, History
from benchmark.history.regressions import Thresholds
from benchmark.metrics import CORE, Metrics
from benchmark.modality import Modality
from benchmark.site.compare import compare_page
from benchmark.site.figures import PLOTLY_ASSET, write_plotly
from benchmark.site.pages import PAGE_KINDS, Drawn, Night, PageKind, page_name
from benchmark.site.tables import ASSET as ITABLES_ASSET
from benchmark.site.tables import write_bundle

OWNED = ("index.html", "runs.html", "compare.html", "assets", "runs", "trackers", "cells", "replays")
"""What the site shows at its top, each a link through :data:`CURRENT`; nothing else there is touched."""
BUILDS = ".builds"
"""The site's folder of builds, each a complete site."""
CURRENT = ".current"
"""The link to the build the site shows."""
LOCK = ".lock"
MANIFEST = "manifest.json"
"""Each page of a build with the hash of its inputs and its files, for the next build to reuse."""
WORKERS = 2
"""Processes drawing pages at most (never more than the machine's cores)."""
POOL_FROM = 8
"""Fewer pages to draw than this are drawn in the building process: starting workers would cost more."""


def assets_page(night: Night, key: None, site: Path) -> Drawn:
    """The shared scripts: the table and the plotting library."""
    return Drawn([write_bundle(site).relative_to(site).as_posix(), write_plotly(site).relative_to(site).as_posix()])


KINDS: dict[str, PageKind] = {"assets": assets_page, **PAGE_KINDS, "compare": compare_page}
"""Every kind of page by name."""
LAST = ("index", "runs")
"""Pages drawn in the building process after all others: the index's boards read the frames the latest run's
cell pages read, and the runs page shows what each run page found."""


@dataclass(frozen=True)
class Page:
    """One page to have: its kind, key, and the hash of its inputs."""

    kind: str
    key: Any
    inputs: str

    @property
    def name(self) -> str:
        return self.kind if self.key is None else f"{self.kind}/{self.key}"


def _digest(*parts: object) -> str:
    return hashlib.sha256(json.dumps(parts, default=str, sort_keys=True).encode()).hexdigest()[:20]


def _code_digest() -> str:
    """A hash of trackbench's code and the site's templates: pages drawn by other code are drawn again."""
    root = Path(benchmark.__file__).parent
    digest = hashlib.sha256()
    for path in sorted([*root.rglob("*.py"), *root.joinpath("site", "templates").iterdir()]):
        digest.update(path.relative_to(root).as_posix().encode())
        digest.update(path.read_bytes())
    from importlib.metadata import version

    digest.update(f"{version('plotly')} {version('itables')}".encode())
    return digest.hexdigest()[:20]


def _plan(night: Night) -> list[Page]:
    """Every page of the site with the hash of its inputs, in drawing order."""
    code = _code_digest()
    shared = (code, repr(night.thresholds), [(metric.name, scope) for metric, scope in night.metrics.added], sorted(night.modalities))
    ids = [int(run) for run in night.runs["id"]]
    everything = _digest(shared, ids, len(night.cells))
    detailed = night.detailed
    pages = [Page("assets", None, _digest(code)), Page("index", None, everything)]
    for position, run_id in enumerate(ids):
        following = ids[position + 1] if position + 1 < len(ids) else None
        kept = night.kept.get(run_id)
        pages.append(Page("run", run_id, _digest(shared, ids[: position + 1], following, run_id in detailed,
                                                 None if kept is None else kept.to_json(orient="split"))))
    pages += [Page("tracker", str(tracker), everything) for tracker in sorted(night.latest["tracker"].unique())]
    by_id = night.cells.set_index("id", drop=False)
    for cell in night.cells[night.cells["run_id"].isin(detailed)].to_dict("records"):
        earlier = night.previous.get(int(cell["id"]))
        compared = None
        if earlier is not None:
            row = by_id.loc[earlier]
            compared = (earlier, int(row["run_id"]) in detailed, row["tracker_version"], row["params"])
        # Empty values left out: a column added to the history later (a new metric) leaves old cells' pages as they are.
        known = {name: value for name, value in cell.items() if not (isinstance(value, float) and math.isnan(value))}
        replay = night.replay_rows.get(int(cell["id"]))
        route = night.routes.get(str(cell["dataset_key"]))
        drawn_route = None if route is None else [leg.__dict__ for leg in route.spec.legs]
        pages.append(Page("cell", int(cell["id"]), _digest(shared, known, compared, replay, drawn_route)))
        if replay is not None and replay["state"] == RECORDED:
            pages.append(Page("replay", int(cell["id"]), _digest(int(cell["run_id"]), replay["digest"])))
    pages += [Page("compare", None, everything), Page("runs", None, everything)]
    return pages


def _load(
    history: History,
    modalities: Mapping[str, Modality],
    metrics: Metrics,
    thresholds: Thresholds,
    routes: Mapping[str, Route],
) -> Night:
    runs = history.runs()
    if runs.empty:
        raise DataError(f"history database {history.location}: no runs yet, so no site to build")
    kept = {int(run_id): history.changes(int(run_id)) for run_id in runs["id"]}
    return Night(history, modalities, metrics, thresholds, runs, history.cells(), {},
                 {run_id: changes for run_id, changes in kept.items() if changes is not None},
                 replays=history.replays(), routes=routes)


_night: Night | None = None
"""The night a worker process draws from: set before the workers are forked, so they share it unpickled."""


def _open_own_history() -> None:
    """In a worker: connections of its own to the history (a forked connection is the parent's)."""
    assert _night is not None
    _night.history.after_fork()


def _draw(kind: str, key: Any, out: Path) -> Drawn:
    assert _night is not None
    return KINDS[kind](_night, key, out)


def _drawn_in_parallel(pages: list[Page], out: Path, workers: int) -> Iterator[tuple[Page, Drawn]]:
    """Draw ``pages`` in ``workers`` forked processes; yield each with what it left as it is done."""
    context = multiprocessing.get_context("fork")
    with ProcessPoolExecutor(workers, mp_context=context, initializer=_open_own_history) as pool:
        futures = {pool.submit(_draw, page.kind, page.key, out): page for page in pages}
        for future in as_completed(futures):
            yield futures[future], future.result()


def _reuse(page: Page, shown: Path, before: Mapping[str, Any], out: Path) -> Drawn | None:
    """The shown build's files of ``page`` linked into ``out`` when its inputs are unchanged, else None."""
    entry = before.get(page.name)
    if not entry or entry["inputs"] != page.inputs or not all((shown / f).is_file() for f in entry["files"]):
        return None
    for name in entry["files"]:
        target = out / name
        target.parent.mkdir(parents=True, exist_ok=True)
        try:
            os.link(shown / name, target)
        except OSError:
            shutil.copy2(shown / name, target)
    return Drawn(list(entry["files"]), dict(entry.get("facts", {})))


def _write(night: Night, out: Path, shown: Path | None, report: Callable[[int, int], None], workers: int) -> None:
    """Write every page into ``out``, reusing the shown build's pages whose inputs are unchanged."""
    global _night
    pages = _plan(night)
    before: dict[str, Any] = {}
    if shown is not None and (shown / MANIFEST).is_file():
        before = json.loads((shown / MANIFEST).read_text(encoding="utf-8"))
    manifest: dict[str, Any] = {}
    done = 0

    def record(page: Page, drawn: Drawn) -> None:
        nonlocal done
        if drawn.frames is not None:
            night.frames[int(page.key)] = drawn.frames
        manifest[page.name] = {"inputs": page.inputs, "files": drawn.files, "facts": drawn.facts}
        if page.kind == "run":
            night.run_facts[int(page.key)] = drawn.facts
        done += 1
        report(done, len(pages))

    to_draw, last = [], []
    for page in pages:
        reused = _reuse(page, shown, before, out) if shown is not None else None
        if reused is not None:
            record(page, reused)
        elif page.kind in LAST:
            last.append(page)
        else:
            to_draw.append(page)
    last.sort(key=lambda page: LAST.index(page.kind))
    # Workers are forked so that they share the loaded history; where there is no fork, pages are drawn here.
    workers = min(workers, os.cpu_count() or 1) if "fork" in multiprocessing.get_all_start_methods() else 1
    if any(page.kind == "tracker" for page in to_draw):
        night.changes  # found once here, not in each worker
    _night = night
    try:
        if workers > 1 and len(to_draw) >= POOL_FROM:
            for page, drawn in _drawn_in_parallel(to_draw, out, workers):
                record(page, drawn)
        else:
            for page in to_draw:
                record(page, KINDS[page.kind](night, page.key, out))
        for page in last:
            record(page, KINDS[page.kind](night, page.key, out))
    finally:
        _night = None
    (out / MANIFEST).write_text(json.dumps(manifest, default=str), encoding="utf-8")


def build_site(
    history: History,
    site: Path,
    modalities: Mapping[str, Modality],
    *,
    thresholds: Thresholds | None = None,
    metrics: Metrics = CORE,
    report: Callable[[int, int], None] | None = None,
    workers: int = WORKERS,
    routes: Mapping[str, Route] | None = None,
) -> Path:
    """Write the site of the history into ``site`` (created, old pages replaced); return index.html.

    Parameters
    ----------
    history : History
        The history database; its latest run is the one the index shows.
    site : pathlib.Path
        The site's folder.  Only the site's own files in it
        (:data:`OWNED`) are replaced; anything else there is left alone.
    modalities : Mapping
        The registered modalities by name (``load_registry().modalities``),
        whose scorers name each board's error columns.
    thresholds : Thresholds, optional
        What counts as a regression, an improvement or a step; the defaults
        of :class:`~benchmark.history.regressions.Thresholds`.
    metrics : Metrics
        The catalogue of metrics shown and judged (the registry's).
    report : callable, optional
        Called with ``(done, total)`` pages after each page is drawn or
        reused, for a progress display.
    workers : int
        Processes that draw pages at once (at most the machine's cores);
        1 draws them in this process.
    routes : Mapping, optional
        The route of each closed-loop dataset by its key
        (:func:`benchmark.closedloop.topview.routes_by_dataset` of the
        registry's suites), over which a closed-loop cell's page draws its
        path; a cell whose route is not among them says so instead.

    Returns
    -------
    pathlib.Path
        ``site/index.html``.

    Raises
    ------
    DataError
        If the history holds no run, from the history database, or when the
        site cannot be written (a full or read-only disk), naming the site.
    """
    night = _load(history, modalities, metrics, thresholds or Thresholds(), routes or {})
    site = make_folder(site)
    try:
        with filelock.FileLock(site / LOCK):
            builds = make_folder(site / BUILDS)
            shown = _shown_build(site)
            for leftover in builds.glob("staging-*"):
                shutil.rmtree(leftover, ignore_errors=True)
            staging = Path(tempfile.mkdtemp(prefix="staging-", dir=builds))
            try:
                _write(night, staging, builds / shown if shown and (builds / shown).is_dir() else None,
                       report or (lambda done, total: None), workers)
                build = staging.rename(builds / f"run-{int(night.run['id'])}-{uuid.uuid4().hex[:8]}")
            finally:
                shutil.rmtree(staging, ignore_errors=True)
            _point(site / CURRENT, Path(BUILDS) / build.name)
            for name in OWNED:
                _point(site / name, Path(CURRENT) / name)
            for old in builds.iterdir():
                if old.name not in {build.name, shown}:
                    shutil.rmtree(old, ignore_errors=True)
    except OSError as exc:
        raise DataError(f"site {site}: cannot write it: {exc.strerror or exc}; the site is left as it was") from None
    return site / "index.html"


def _shown_build(site: Path) -> str:
    """The name of the build the site shows now, or ``""``."""
    try:
        return Path(os.readlink(site / CURRENT)).name
    except OSError:
        return ""


def _point(path: Path, target: Path) -> None:
    """Make ``path`` a link to ``target`` (relative to its folder) in one rename; what was there goes.

    A folder or file of an earlier layout at ``path`` is moved aside first
    and removed after, so the name is missing only between two renames.
    """
    if path.is_symlink() and Path(os.readlink(path)) == target:
        return
    temporary = path.with_name(f".{path.name}.{uuid.uuid4().hex[:8]}.link")
    os.symlink(target, temporary)
    aside = None
    if path.exists() and not path.is_symlink():
        aside = path.with_name(f".{path.name}.{uuid.uuid4().hex[:8]}.old")
        path.rename(aside)
    os.replace(temporary, path)
    if aside is not None:
        shutil.rmtree(aside) if aside.is_dir() else aside.unlink()
