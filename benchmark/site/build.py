"""The nightly site: what the latest run of a history shows, page by page.

:func:`build_site` writes::

    index.html             the run, its regressions and improvements, one board per modality
    trackers/<name>.html   a tracker's metrics over the history, and its cells of the run
    cells/<id>.html        one cell of the run: its frames, errors, failed frames and parameters
    assets/itables.js      the table library, shared by every page (:mod:`benchmark.site.tables`)

with each figure as a PNG file beside its page.

The site changes in one step.  A build writes its pages into a folder of
their own, ``site/.builds/run-N-XXXX``; when all are written, the link
``site/.current`` is pointed at it by one rename, and ``index.html``,
``trackers``, ``cells`` and ``assets`` are links through ``.current``.  So
a reader (a browser, a web server, a copy) sees the previous site or the new
one, never a mixture, and a build that is killed or fails (a full or
read-only disk is a :class:`~benchmark.errors.DataError` naming the site)
leaves the previous site as it was.  Builds take turns (a lock,
``site/.lock``): each removes what killed builds left, and every build
but the new one and the one before it, which a reader may still be
browsing.
"""

from __future__ import annotations

import hashlib
import math
import os
import re
import shutil
import tempfile
import uuid
from collections.abc import Mapping
from dataclasses import dataclass
from datetime import datetime
from pathlib import Path
from typing import Any

import filelock
import jinja2
import pandas as pd
from markupsafe import Markup

from benchmark.errors import DataError
from benchmark.files import make_folder
from benchmark.history.database import History
from benchmark.history.regressions import Step, Thresholds, find_changes, steps
from benchmark.leaderboard import error_columns, is_pooled, leaderboards
from benchmark.metrics import CORE, Metric, Metrics, error_columns_of
from benchmark.modality import Modality
from benchmark.report.display import alignment, display_table, format_value
from benchmark.site.figures import OUTCOME_COLOURS, cell_figure, trend_figure
from benchmark.site.tables import datatable, escaped, link, write_bundle

OWNED = ("index.html", "assets", "trackers", "cells")
"""What the site shows at its top, each a link through :data:`CURRENT`; nothing else there is touched."""
BUILDS = ".builds"
"""The site's folder of builds, each a complete site."""
CURRENT = ".current"
"""The link to the build the site shows."""
LOCK = ".lock"

SHARED_COLUMNS = ("init", "seeds", "training")
"""Board columns shown once above the board instead when every row has the same value."""


_templates = jinja2.Environment(
    loader=jinja2.FileSystemLoader(Path(__file__).with_name("templates")),
    autoescape=True,
    undefined=jinja2.StrictUndefined,
    trim_blocks=True,
    lstrip_blocks=True,
)


def page_name(tracker: str) -> str:
    """A file stem for a tracker's page: its name where that is a safe file name, else a slug and a hash."""
    slug = re.sub(r"[^A-Za-z0-9._-]+", "-", tracker).strip("-.") or "tracker"
    if slug == tracker:
        return slug
    return f"{slug}-{hashlib.sha256(tracker.encode()).hexdigest()[:8]}"


def _when(started: str) -> str:
    try:
        return datetime.fromisoformat(started).strftime("%Y-%m-%d %H:%M %Z").strip()
    except ValueError:
        return started


def _signed(metric: str, value: float, metrics: Metrics) -> str:
    shown = format_value(metric, value, metrics)
    return f"+{shown}" if value > 0 and shown.strip("0.") else shown


def _named_by(label: str, name: str, key: str) -> bool:
    """Whether a board label (``name`` or ``name [key prefix]``) stands for ``name`` with ``key``."""
    return label == name or label == f"{name} [{key[:8]}]"


def _labelled(cells: pd.DataFrame, label: str, name: str, key: str) -> pd.DataFrame:
    """The cells whose ``name`` and ``key`` columns a board label stands for."""
    mask = [_named_by(label, str(n), str(k)) for n, k in zip(cells[name], cells[key])]
    return cells[pd.Series(mask, index=cells.index, dtype=bool)]


@dataclass
class _Night:
    """What the pages of one run are made of."""

    history: History
    modalities: Mapping[str, Modality]
    metrics: Metrics
    thresholds: Thresholds
    runs: pd.DataFrame
    cells: pd.DataFrame
    latest: pd.DataFrame
    frames: dict[int, pd.DataFrame]
    changes: pd.DataFrame | None

    @property
    def run(self) -> pd.Series:
        return self.runs.iloc[-1]

    def tracker_href(self, tracker: str, root: str) -> str:
        return f"{root}trackers/{page_name(tracker)}.html"

    def cell_links(self, cells: pd.DataFrame, root: str) -> Markup:
        """Links to the pages of ``cells``, one per seed."""
        ordered = cells.sort_values(["seed", "id"])
        return Markup(" ").join(
            link(f"seed {cell.seed}", f"{root}cells/{cell.id}.html") for cell in ordered.itertuples()
        )

    def metrics_of(self, cells: pd.DataFrame) -> list[Metric]:
        """The metrics of the boards of ``cells``'s modalities that have a value in ``cells``, in board order."""
        found: dict[str, Metric] = {}
        for modality in cells["modality"].unique():
            registered = self.modalities.get(str(modality))
            errors = registered.error_columns if registered else error_columns_of(cells.columns)
            found |= {metric.name: metric for metric in self.metrics.for_board(str(modality), errors)}
        return [metric for metric in found.values() if metric.name in cells and cells[metric.name].notna().any()]

    def errors_of(self, modality: str, frames: pd.DataFrame) -> list[str]:
        """The error columns of a modality that have a value in ``frames``."""
        columns = error_columns(self.modalities.get(modality), frames)
        return [c for c in columns if c in frames and pd.to_numeric(frames[c], errors="coerce").notna().any()]


def _load(history: History, modalities: Mapping[str, Modality], metrics: Metrics, thresholds: Thresholds) -> _Night:
    runs = history.runs()
    if runs.empty:
        raise DataError(f"history database {history.location}: no runs yet, so no site to build")
    cells = history.cells()
    run_id = int(runs["id"].iloc[-1])
    latest = cells[cells["run_id"] == run_id].reset_index(drop=True)
    frames = {int(cell_id): history.frames(int(cell_id)) for cell_id in latest["id"]}
    changes = find_changes(cells, run_id, thresholds, metrics=metrics) if len(runs) > 1 else None
    return _Night(history, modalities, metrics, thresholds, runs, cells, latest, frames, changes)


def _render(template: str, night: _Night, root: str, title: str, **context: Any) -> str:
    """A page: ``template`` with the run's header, links relative to the page's folder ``root``."""
    run = night.run.to_dict()
    machine = run["machine"] if isinstance(run["machine"], Mapping) else {}
    return _templates.get_template(template).render(
        root=root,
        title=title,
        run=run,
        when=_when(str(run["started"])),
        machine=" \u00b7 ".join(f"{key}: {value}" for key, value in machine.items()),
        colours=OUTCOME_COLOURS,
        **context,
    )


def _change_rows(night: _Night, verdict: str, root: str) -> list[dict[str, Any]]:
    if night.changes is None:
        return []
    rows = []
    for change in night.changes[night.changes["verdict"] == verdict].itertuples():
        metric = str(change.metric)
        interval = ""
        if math.isfinite(change.low) and math.isfinite(change.high) and change.low != change.high:
            interval = f"[{_signed(metric, change.low, night.metrics)}, {_signed(metric, change.high, night.metrics)}]"
        cells = night.latest[(night.latest["tracker"] == change.tracker) & (night.latest["dataset"] == change.dataset)]
        rows.append(
            dict(
                tracker=change.tracker, dataset=change.dataset, metric=metric, kind=change.kind, verdict=verdict,
                before=format_value(metric, change.before, night.metrics),
                after=format_value(metric, change.after, night.metrics),
                change=_signed(metric, change.change, night.metrics), interval=interval, cause=change.cause,
                tracker_href=night.tracker_href(str(change.tracker), root), cells=night.cell_links(cells, root),
            )
        )
    return rows


def _board(night: _Night, board: pd.DataFrame, table_id: str, root: str) -> dict[str, Any]:
    """A leaderboard as an interactive table, trackers linked to their pages and dataset rows to their cells.

    Returns ``table``, the table, and ``shared``, the columns left out of it
    because every row has the same value there (``init``, ``seeds``), with
    that value.
    """
    shown = display_table(board, night.metrics)
    numeric = [c for c, side in zip(shown.columns, alignment(board, night.metrics)) if side == "right" and c != "rank"]
    empty = [c for c in shown.columns if c not in ("tracker", "dataset") and (shown[c] == "").all()]
    shared = {c: shown[c].iloc[0] for c in SHARED_COLUMNS if c not in empty and len(shown) and shown[c].nunique() == 1}
    table = escaped(shown.drop(columns=[*empty, *shared]))
    numeric = [c for c in numeric if c in table]
    for column in numeric:
        table[column] = table[column].str.replace(r"^(\S+) (\[.*\])$", r'\1 <span class="ci">\2</span>', regex=True)
    latest = night.latest
    trackers, cells = [], []
    for row in board.itertuples():
        of_tracker = _labelled(latest, row.tracker, "tracker", "tracker_key")
        name = str(of_tracker["tracker"].iloc[0]) if len(of_tracker) else str(row.tracker)
        trackers.append(link(row.tracker, night.tracker_href(name, root)))
        of_row = _labelled(of_tracker[of_tracker["init"] == row.init], row.dataset, "dataset", "dataset_key")
        cells.append(night.cell_links(of_row, root) if not is_pooled(row.dataset) else Markup(""))
    table["tracker"] = [str(markup) for markup in trackers]
    table.insert(list(table.columns).index("dataset") + 1, "cells", [str(markup) for markup in cells])
    return {"table": datatable(table, table_id, numeric), "shared": shared}


def _index(night: _Night) -> str:
    boards = leaderboards(
        night.latest,
        pd.concat([frames.assign(cell_id=cell_id) for cell_id, frames in night.frames.items()], ignore_index=True)
        if night.frames else pd.DataFrame(),
        night.modalities,
        night.metrics,
    )
    return _render(
        "index.html",
        night,
        "",
        "trackbench nightly",
        compared=night.changes is not None,
        earlier=len(night.runs) - 1,
        regressions=_change_rows(night, "regression", ""),
        improvements=_change_rows(night, "improvement", ""),
        boards={modality: _board(night, board, f"board-{i}", "") for i, (modality, board) in enumerate(boards.items())},
        datatables=True,
    )


def _trend_levels(night: _Night, tracker: str) -> tuple[dict[str, pd.DataFrame], dict[tuple[str, str], list[Step]]]:
    """Per metric, the mean over seeds of each run and dataset of ``tracker``; and the steps of each series."""
    cells = night.cells[(night.cells["tracker"] == tracker) & (night.cells["status"] == "ok")]
    several_inits = cells["init"].nunique() > 1
    series = cells["dataset"] + (" [init " + cells["init"] + "]" if several_inits else "")
    position = cells["run_id"].map({int(run): i for i, run in enumerate(night.runs["id"])})
    levels, found = {}, {}
    for metric in (m for m in night.metrics_of(cells) if m.headline):
        table = cells.groupby([position, series])[metric.name].mean().unstack()
        table = table.reindex(range(len(night.runs)))
        levels[metric.name] = table
        for name in table.columns:
            values = table[name].dropna()
            if len(values):
                minimum = night.thresholds.minimum_effect(metric, float(values.median()))
                found[(metric.name, str(name))] = steps(values, minimum)
    return levels, found


def _tracker(night: _Night, tracker: str, folder: Path) -> str:
    stem = page_name(tracker)
    levels, found = _trend_levels(night, tracker)
    runs = [_when(str(started))[:10] for started in night.runs["started"]]
    figure = trend_figure(levels, runs, found, folder / f"{stem}-trends.png", night.metrics) if levels else None
    cells = night.latest[night.latest["tracker"] == tracker]
    numeric = ["seed", *(m.name for m in night.metrics_of(cells) if m.kind == "detection" or m.headline)]
    columns = ["dataset", "init", "seed", "status", *numeric[1:], "message"]
    shown = pd.DataFrame({c: [format_value(c, v, night.metrics) for v in cells[c]] for c in columns}, dtype=object)
    table = escaped(shown)
    table.insert(0, "cell", [str(link(f"#{cell_id}", f"../cells/{cell_id}.html")) for cell_id in cells["id"]])
    steps_found = [
        dict(metric=metric, dataset=dataset, run=runs[step.run_id],
             before=format_value(metric, step.before, night.metrics),
             after=format_value(metric, step.after, night.metrics))
        for (metric, dataset), found_steps in found.items() for step in found_steps
    ]
    changes = [row for verdict in ("regression", "improvement") for row in _change_rows(night, verdict, "../")
               if row["tracker"] == tracker]
    parameters = {cell.tracker_key: (cell.tracker_version, cell.params) for cell in cells.itertuples()}
    return _render(
        "tracker.html",
        night,
        "../",
        f"{tracker} \u00b7 trackbench nightly",
        tracker=tracker,
        figure=figure.name if figure else None,
        steps=steps_found,
        changes=changes,
        cells=datatable(table, "cells", numeric),
        parameters=parameters,
        datatables=True,
    )


def _cell(night: _Night, cell: pd.Series, folder: Path) -> str:
    cell_id = int(cell["id"])
    frames = night.frames[cell_id]
    errors = night.errors_of(str(cell["modality"]), frames)
    figure = cell_figure(frames, errors, folder / f"{cell_id}-frames.png") if len(frames) else None
    pictures = []
    for picture in night.history.pictures(cell_id):
        name = f"{cell_id}-frame-{picture.frame}.png"
        (folder / name).write_bytes(picture.png)
        pictures.append(dict(src=name, frame=picture.frame, outcome=picture.outcome))
    counts = frames["outcome"].fillna("unscored").value_counts() if "outcome" in frames else pd.Series(dtype=int)
    of_board = night.metrics.for_board(str(cell["modality"]), errors)
    summary = {metric.name: metric.format(cell[metric.name]) for metric in of_board if metric.name in cell}
    return _render(
        "cell.html",
        night,
        "../",
        f"{cell['tracker']} on {cell['dataset']} \u00b7 trackbench nightly",
        cell=cell.to_dict(),
        tracker_href=night.tracker_href(str(cell["tracker"]), "../"),
        figure=figure.name if figure else None,
        outcomes={outcome: int(counts.get(outcome, 0)) for outcome in OUTCOME_COLOURS},
        summary=summary,
        pictures=pictures,
        datatables=False,
    )


def _write(night: _Night, out: Path) -> None:
    write_bundle(out)
    (out / "index.html").write_text(_index(night), encoding="utf-8")
    trackers = out / "trackers"
    trackers.mkdir()
    for tracker in sorted(night.latest["tracker"].unique()):
        (trackers / f"{page_name(tracker)}.html").write_text(_tracker(night, tracker, trackers), encoding="utf-8")
    cells = out / "cells"
    cells.mkdir()
    for _, cell in night.latest.iterrows():
        (cells / f"{int(cell['id'])}.html").write_text(_cell(night, cell, cells), encoding="utf-8")


def build_site(
    history: History,
    site: Path,
    modalities: Mapping[str, Modality],
    *,
    thresholds: Thresholds | None = None,
    metrics: Metrics = CORE,
) -> Path:
    """Write the whole site for the history's latest run into ``site`` (created, old pages replaced); return index.html.

    Parameters
    ----------
    history : History
        The history database; its latest run is the one shown.
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
    night = _load(history, modalities, metrics, thresholds or Thresholds())
    site = make_folder(site)
    try:
        with filelock.FileLock(site / LOCK):
            builds = make_folder(site / BUILDS)
            shown = _shown_build(site)
            for leftover in builds.glob("staging-*"):
                shutil.rmtree(leftover, ignore_errors=True)
            staging = Path(tempfile.mkdtemp(prefix="staging-", dir=builds))
            try:
                _write(night, staging)
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
