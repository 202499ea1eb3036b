"""The pages of the site, one function per kind of page, each drawn from a :class:`Night`.

A page function takes the night, the page's key (a run id, a tracker, a
cell id, or nothing) and the site folder being written; it writes the page
(and its pictures) there and returns a :class:`Drawn`: the files it wrote,
relative to the site's root, and what other pages need from it (a run's
counts of regressions, for the runs page).  :data:`PAGE_KINDS` is the
registry of page kinds; :mod:`benchmark.site.build` decides which pages a
history has, and which must be drawn again.
"""

from __future__ import annotations

import functools
import hashlib
import math
import re
from collections import defaultdict
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, field
from datetime import datetime
from pathlib import Path
from typing import TYPE_CHECKING, Any

import jinja2
import pandas as pd
from markupsafe import Markup, escape

from benchmark.closedloop.topview import has_loop_values, top_view
from benchmark.history.database import DETAILED_RUNS, RECORDED, REPLAY_COLUMNS, SERIES, History
from benchmark.history.regressions import VERDICTS, Step, Thresholds, find_changes, group_changes, steps
from benchmark.history.replays import shown_size
from benchmark.leaderboard import error_columns, is_pooled, key_labels, leaderboards
from benchmark.metrics import Metric, Metrics, error_columns_of
from benchmark.modality import Modality
from benchmark.report.display import alignment, display_table, format_value
from benchmark.results import Picture
from benchmark.site.figures import OUTCOME_COLOURS, cell_figure, plot, top_view_figure, trend_figure
from benchmark.site.tables import datatable, escaped, link

if TYPE_CHECKING:
    from benchmark.closedloop.route import Route

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


def when(started: str) -> str:
    """A run's start as ``YYYY-MM-DD HH:MM zone``."""
    try:
        return datetime.fromisoformat(started).strftime("%Y-%m-%d %H:%M %Z").strip()
    except ValueError:
        return started


def run_label(run: Mapping[str, Any]) -> str:
    """A run as the trend axes and menus name it: ``#id · commit · date time``, distinct for runs of one day."""
    commit = str(run.get("commit") or "")[:7] or "no commit"
    return f"#{int(run['id'])} \u00b7 {commit} \u00b7 {when(str(run['started']))[:16]}"


def signed(metric: str, value: float, metrics: Metrics) -> str:
    """A change as shown, with its sign."""
    shown = format_value(metric, value, metrics)
    return f"+{shown}" if value > 0 and shown.strip("0.") else shown


def described(value: object) -> str:
    """A parameter's value as text, or ``(none)``."""
    return "(none)" if value is None else str(value)


def changed_parameters(now: Mapping[str, Any], before: list[Mapping[str, Any]]) -> dict[str, str]:
    """The parameters of ``now`` whose value differs from the earlier cells' ``before``: name to earlier value(s).

    A parameter the earlier cells had and ``now`` lacks is named too; no
    earlier cells means nothing changed.
    """
    if not before:
        return {}
    changed = {}
    for name in sorted({*now, *(key for params in before for key in params)}):
        earlier = sorted({described(params.get(name)) for params in before})
        if earlier != [described(now.get(name))]:
            changed[name] = ", ".join(earlier)
    return changed


def replay_name(run_id: int, cell_id: int) -> str:
    """Where the replay of a cell is in the site: ``replays/<run>/<cell>.html``, with its run's other replays."""
    return f"replays/{int(run_id)}/{int(cell_id)}.html"


def replay_back(cell_id: int) -> tuple[str, str]:
    """The address of a cell's page as seen from its replay (:func:`replay_name`), and its label."""
    return f"../../cells/{int(cell_id)}.html", f"cell #{int(cell_id)} of the nightly site"


@dataclass(frozen=True)
class Drawn:
    """What drawing a page left: its files, relative to the site's root, and facts other pages use.

    ``frames`` is the frame table a cell page of the latest run read, handed
    to the index's boards so that it is read once.
    """

    files: list[str]
    facts: dict[str, Any] = field(default_factory=dict)
    frames: pd.DataFrame | None = None


@dataclass
class Night:
    """What the pages of a history are made of: every run and cell, the latest run's frames and changes."""

    history: History
    modalities: Mapping[str, Modality]
    metrics: Metrics
    thresholds: Thresholds
    runs: pd.DataFrame
    cells: pd.DataFrame
    frames: dict[int, pd.DataFrame]
    kept: Mapping[int, pd.DataFrame]
    run_facts: dict[int, dict[str, Any]] = field(default_factory=dict)
    replays: pd.DataFrame = field(default_factory=lambda: pd.DataFrame(columns=REPLAY_COLUMNS))
    """What the nightlies did about their cells' replays (:meth:`History.replays`)."""
    routes: Mapping[str, Route] = field(default_factory=dict)
    """The route of each closed-loop dataset the registry knows, by dataset key
    (:func:`benchmark.closedloop.topview.routes_by_dataset`), for the cells' top views."""

    @property
    def run(self) -> pd.Series:
        return self.runs.iloc[-1]

    @functools.cached_property
    def latest(self) -> pd.DataFrame:
        return self.cells_of(int(self.run["id"]))

    @functools.cached_property
    def detailed(self) -> set[int]:
        """The runs whose cells keep their frames and pictures, so have pages."""
        return {int(run) for run in self.runs["id"].iloc[-DETAILED_RUNS:]}

    @functools.cached_property
    def previous(self) -> dict[int, int]:
        """Each cell's predecessor: the cell of its series (:data:`SERIES`) in the last run before its own."""
        ordered = self.cells.sort_values(["run_id", "id"], kind="stable")
        before = ordered.groupby(SERIES, sort=False)["id"].shift(1)
        return {int(cell): int(earlier) for cell, earlier in zip(ordered["id"], before) if pd.notna(earlier)}

    @functools.cached_property
    def changes(self) -> pd.DataFrame | None:
        """The changes of the latest run."""
        return self.changes_of(int(self.run["id"]))

    def cells_of(self, run_id: int) -> pd.DataFrame:
        return self.cells[self.cells["run_id"] == run_id].reset_index(drop=True)

    def run_row(self, run_id: int) -> pd.Series:
        return self.runs[self.runs["id"] == run_id].iloc[0]

    def neighbours(self, run_id: int) -> tuple[int | None, int | None]:
        """The runs before and after ``run_id``."""
        ids = [int(run) for run in self.runs["id"]]
        at = ids.index(run_id)
        return (ids[at - 1] if at else None), (ids[at + 1] if at + 1 < len(ids) else None)

    @functools.cached_property
    def replay_rows(self) -> dict[int, dict[str, Any]]:
        """Each replayed cell's row of :attr:`replays`, by cell id."""
        return {int(row["cell_id"]): row for row in self.replays.to_dict("records")}

    def frames_of(self, cell_id: int) -> pd.DataFrame:
        if cell_id not in self.frames:
            self.frames[cell_id] = self.history.frames(cell_id)
        return self.frames[cell_id]

    def pictures_of(self, cell_id: int) -> list[Picture]:
        return self.history.pictures(cell_id)

    def tracker_href(self, tracker: str, root: str) -> str:
        return f"{root}trackers/{page_name(tracker)}.html"

    def cell_links(self, cells: pd.DataFrame, root: str) -> Markup:
        """Links to the pages of ``cells``, one per seed; none for cells of runs that keep no details."""
        return self.seed_links(zip(cells["seed"], cells["id"], cells["run_id"]), root)

    def seed_links(self, cells: Iterable[tuple[Any, Any, Any]], root: str) -> Markup:
        """Links to the pages of cells given as ``(seed, id, run_id)``, in seed order."""
        shown = sorted((int(seed), int(cell)) for seed, cell, run in cells if int(run) in self.detailed)
        return Markup(" ").join(link(f"seed {seed}", f"{root}cells/{cell}.html") for seed, cell in shown)

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

    def earlier_cells(self, run_id: int, **same: object) -> pd.DataFrame:
        """The cells of the last run before ``run_id`` that has cells with the ``same`` column values."""
        cells = self.cells[self.cells["run_id"] < run_id]
        for column, value in same.items():
            cells = cells[cells[column] == value]
        return cells[cells["run_id"] == cells["run_id"].max()] if len(cells) else cells

    def changes_of(self, run_id: int) -> pd.DataFrame | None:
        """The changes of a run against the runs before it; None for the history's first run.

        Those the nightly kept in the history where it did, else found now.
        """
        if run_id == int(self.runs["id"].iloc[0]):
            return None
        kept = self.kept.get(run_id)
        if kept is not None:
            return kept
        return find_changes(self.cells[self.cells["run_id"] <= run_id], run_id, self.thresholds, metrics=self.metrics)


def render(template: str, night: Night, run: Mapping[str, Any], root: str, title: str, **context: Any) -> str:
    """A page: ``template`` with ``run``'s header and the site's menu, links relative to the page's folder ``root``."""
    machine = run["machine"] if isinstance(run.get("machine"), Mapping) else {}
    load = run.get("load")
    context.setdefault("standalone", False)
    context.setdefault("plotly", False)
    return _templates.get_template(template).render(
        root=root,
        title=title,
        run=run,
        when=when(str(run["started"])),
        machine=" \u00b7 ".join(f"{key}: {value}" for key, value in machine.items()),
        load=" \u00b7 ".join(f"{key}: {value}" for key, value in load.items()) if isinstance(load, Mapping) else "",
        colours=OUTCOME_COLOURS,
        **context,
    )


def _change_row(night: Night, change: pd.Series, cells: pd.DataFrame, root: str) -> dict[str, Any]:
    metric = str(change["metric"])
    interval = ""
    low, high = float(change["low"]), float(change["high"])
    if math.isfinite(low) and math.isfinite(high) and low != high:
        interval = f"[{signed(metric, low, night.metrics)}, {signed(metric, high, night.metrics)}]"
    of_row = cells[(cells["tracker"] == change["tracker"]) & (cells["dataset"] == change["dataset"])]
    return dict(
        dataset=change["dataset"], metric=metric, note=str(change.get("note", "") or ""),
        before=format_value(metric, change["before"], night.metrics),
        after=format_value(metric, change["after"], night.metrics),
        change=signed(metric, float(change["change"]), night.metrics), interval=interval,
        cells=night.cell_links(of_row, root) if len(cells) else Markup(""),
    )


def grouped_changes(
    night: Night, changes: pd.DataFrame | None, cells: pd.DataFrame, root: str, tracker: str | None = None
) -> dict[str, dict[str, list[dict[str, Any]]]]:
    """Changes folded by verdict, kind, tracker and cause, for ``changes.html``: verdict -> kind -> groups.

    Each group has its tracker, cause, headline, count, datasets and
    metrics, and ``rows``, its changes as shown (with links to ``cells``).
    """
    shown: dict[str, dict[str, list[dict[str, Any]]]] = {
        verdict: {"accuracy": [], "speed": []} for verdict in VERDICTS
    }
    if changes is None or changes.empty:
        return shown
    if tracker is not None:
        changes = changes[changes["tracker"] == tracker]
    for group in group_changes(changes, night.metrics).itertuples():
        shown[str(group.verdict)][str(group.kind)].append(
            dict(
                tracker=group.tracker, tracker_href=night.tracker_href(str(group.tracker), root),
                cause=group.cause, headline=group.headline, count=group.count,
                datasets=list(group.datasets), metrics=list(group.metrics),
                rows=[_change_row(night, row, cells, root) for _, row in group.rows.iterrows()],
            )
        )
    return shown


def _board(night: Night, board: pd.DataFrame, cells: pd.DataFrame, table_id: str, root: str) -> dict[str, Any]:
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
    # Cells by the labels the board gives them (modality_board's), so that each row finds its own at once.
    tracker_labels = key_labels(cells, "tracker", "tracker_key")
    dataset_labels = key_labels(cells, "dataset", "dataset_key")
    names = dict(zip(tracker_labels, cells["tracker"]))
    of_row: dict[tuple[str, str, str], list[tuple[Any, Any, Any]]] = defaultdict(list)
    for tracker, dataset, init, seed, cell, run in zip(
        tracker_labels, dataset_labels, cells["init"], cells["seed"], cells["id"], cells["run_id"]
    ):
        of_row[(str(tracker), str(dataset), str(init))].append((seed, cell, run))
    trackers, links = [], []
    for row in board.itertuples():
        trackers.append(link(row.tracker, night.tracker_href(str(names.get(row.tracker, row.tracker)), root)))
        cells_of_row = [] if is_pooled(row.dataset) else of_row[(str(row.tracker), str(row.dataset), str(row.init))]
        links.append(night.seed_links(cells_of_row, root))
    table["tracker"] = [str(markup) for markup in trackers]
    table.insert(list(table.columns).index("dataset") + 1, "cells", [str(markup) for markup in links])
    return {"table": datatable(table, table_id, numeric), "shared": shared}


def _summary_board(night: Night, cells: pd.DataFrame, modality: str, table_id: str, root: str) -> dict[str, Any]:
    """A run's board from the cells' summaries: per tracker, dataset and init, each metric's mean over seeds."""
    metrics = [m for m in night.metrics_of(cells) if m.kind == "detection" or m.headline]
    rows = []
    for (tracker, dataset, init), group in cells.groupby(["tracker", "dataset", "init"], sort=True):
        failed = int((group["status"] != "ok").sum())
        rows.append(
            dict(tracker=str(link(tracker, night.tracker_href(str(tracker), root))), dataset=str(escape(dataset)),
                 cells=str(night.cell_links(group, root)), init=str(escape(init)), seeds=str(len(group)),
                 **{m.name: format_value(m.name, group[m.name].mean(), night.metrics) for m in metrics},
                 status="ok" if not failed else f"{failed} failed")
        )
    table = pd.DataFrame(rows, dtype=object)
    return {"table": datatable(table, table_id, ["seeds", *(m.name for m in metrics)]), "shared": {}}


def _run_page(night: Night, run_id: int, root: str, index: bool) -> tuple[str, dict[str, Any]]:
    """The page of a run: its changes against the runs before it, grouped, and its boards.

    The boards are those the nightly published and kept; for a run that kept
    none, the index works them out from the frame tables, and a run's own
    page shows each metric's mean over the seeds' summaries.
    """
    cells = night.cells_of(run_id)
    changes = night.changes if run_id == int(night.run["id"]) else night.changes_of(run_id)
    boards = night.history.boards(run_id)  # as the nightly published them; else worked out from the frames
    if boards is None and index:
        frames = [night.frames_of(int(cell_id)).assign(cell_id=int(cell_id)) for cell_id in cells["id"]]
        boards = leaderboards(cells, pd.concat(frames, ignore_index=True) if frames else pd.DataFrame(),
                              night.modalities, night.metrics)
    if boards is not None:
        # A board's cells are those of its datasets (a modality's open-loop board, a suite's closed-loop one).
        datasets = key_labels(cells, "dataset", "dataset_key")
        tables = {name: _board(night, board, cells[datasets.isin(board["dataset"])], f"board-{i}", root)
                  for i, (name, board) in enumerate(boards.items())}
    else:
        tables = {str(modality): _summary_board(night, group, str(modality), f"board-{i}", root)
                  for i, (modality, group) in enumerate(cells.groupby("modality", sort=True))}
    previous, following = night.neighbours(run_id)
    groups = grouped_changes(night, changes, cells, root)
    facts = {verdict: sum(len(group["rows"]) for kind in by_kind.values() for group in kind)
             for verdict, by_kind in groups.items()}
    run = night.run_row(run_id).to_dict()
    html = render(
        "run.html", night, run, root,
        "trackbench nightly" if index else f"run #{run_id} \u00b7 trackbench nightly",
        index=index, compared=changes is not None, earlier=int((night.runs["id"] < run_id).sum()),
        changes=groups, boards=tables, previous=previous, following=following, detailed=run_id in night.detailed,
        full_boards=boards is not None, datatables=True,
    )
    return html, facts


def index_page(night: Night, key: None, site: Path) -> Drawn:
    """``index.html``: the latest run, its grouped changes and full leaderboards."""
    html, facts = _run_page(night, int(night.run["id"]), "", index=True)
    (site / "index.html").write_text(html, encoding="utf-8")
    return Drawn(["index.html"], facts)


def run_page(night: Night, run_id: int, site: Path) -> Drawn:
    """``runs/<id>.html``: a run, its changes against the runs before it, and its boards."""
    html, facts = _run_page(night, run_id, "../", index=False)
    path = site / "runs" / f"{run_id}.html"
    path.parent.mkdir(exist_ok=True)
    path.write_text(html, encoding="utf-8")
    return Drawn([f"runs/{run_id}.html"], facts)


def runs_page(night: Night, key: None, site: Path) -> Drawn:
    """``runs.html``: every run, newest first, with its cells' outcome and its regressions."""
    rows = []
    for run in night.runs.iloc[::-1].to_dict("records"):
        run_id = int(run["id"])
        cells = night.cells[night.cells["run_id"] == run_id]
        load = run.get("load")
        machine = run["machine"] if isinstance(run.get("machine"), Mapping) else {}
        facts = night.run_facts.get(run_id, {})
        rows.append(dict(
            id=run_id, when=when(str(run["started"])), commit=str(run.get("commit") or "")[:12],
            version=run["version"], machine=" \u00b7 ".join(f"{k}: {v}" for k, v in machine.items()),
            load=" \u00b7 ".join(f"{k}: {v}" for k, v in load.items()) if isinstance(load, Mapping) else "",
            cells=len(cells), ok=int((cells["status"] == "ok").sum()), failed=int((cells["status"] != "ok").sum()),
            regressions=facts.get("regression"), improvements=facts.get("improvement"),
            detailed=run_id in night.detailed,
        ))
    html = render("runs.html", night, night.run.to_dict(), "", "runs \u00b7 trackbench nightly", rows=rows,
                  datatables=False)
    (site / "runs.html").write_text(html, encoding="utf-8")
    return Drawn(["runs.html"])


def _trend_levels(night: Night, tracker: str) -> tuple[dict[str, pd.DataFrame], dict[tuple[str, str], list[Step]]]:
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


def _parameter_sets(night: Night, cells: pd.DataFrame, run_id: int) -> list[dict[str, Any]]:
    """Each parameter set of ``cells`` (one per tracker key), with what changed since the run before.

    The earlier values are those of the last earlier run's cells of the same
    tracker on the same datasets.
    """
    shown = []
    for key, group in cells.groupby("tracker_key", sort=False):
        tracker = str(group["tracker"].iloc[0])
        earlier = night.earlier_cells(run_id, tracker=tracker)
        earlier = earlier[earlier["dataset_key"].isin(group["dataset_key"])] if len(earlier) else earlier
        first = group.iloc[0]
        versions = sorted({str(version) for version in earlier["tracker_version"]})
        shown.append(dict(
            key=key, version=first["tracker_version"], params=first["params"],
            changed=changed_parameters(first["params"], list(earlier["params"])),
            old_version=", ".join(versions) if versions and versions != [str(first["tracker_version"])] else "",
            earlier_run=int(earlier["run_id"].iloc[0]) if len(earlier) else None,
        ))
    return shown


def tracker_page(night: Night, tracker: str, site: Path) -> Drawn:
    """``trackers/<name>.html``: a tracker's headline metrics over the runs, its changes, cells and parameters."""
    levels, found = _trend_levels(night, tracker)
    labels = [run_label(run) for run in night.runs.to_dict("records")]
    figure = plot(*trend_figure(levels, labels, found, night.metrics), "trends") if levels else None
    cells = night.latest[night.latest["tracker"] == tracker]
    numeric = ["seed", *(m.name for m in night.metrics_of(cells) if m.kind == "detection" or m.headline)]
    columns = ["dataset", "init", "seed", "status", *numeric[1:], "message"]
    shown = pd.DataFrame({c: [format_value(c, v, night.metrics) for v in cells[c]] for c in columns}, dtype=object)
    table = escaped(shown)
    table.insert(0, "cell", [str(link(f"#{cell_id}", f"../cells/{cell_id}.html")) for cell_id in cells["id"]])
    steps_found = [
        dict(metric=metric, dataset=dataset, run=labels[step.run_id],
             run_id=int(night.runs["id"].iloc[step.run_id]),
             before=format_value(metric, step.before, night.metrics),
             after=format_value(metric, step.after, night.metrics))
        for (metric, dataset), found_steps in found.items() for step in found_steps
    ]
    run_id = int(night.run["id"])
    html = render(
        "tracker.html", night, night.run.to_dict(), "../", f"{tracker} \u00b7 trackbench nightly",
        tracker=tracker, figure=figure, steps=steps_found,
        changes=grouped_changes(night, night.changes, night.latest, "../", tracker),
        cells=datatable(table, "cells", numeric), parameters=_parameter_sets(night, cells, run_id), datatables=True,
        plotly=figure is not None,
    )
    name = f"trackers/{page_name(tracker)}.html"
    (site / name).parent.mkdir(exist_ok=True)
    (site / name).write_text(html, encoding="utf-8")
    return Drawn([name])


def cell_page(night: Night, cell_id: int, site: Path) -> Drawn:
    """``cells/<id>.html``: one cell, its frames (interactive), the frames it failed on, and its parameters."""
    cell = night.cells[night.cells["id"] == cell_id].iloc[0]
    frames = night.frames_of(cell_id)
    errors = night.errors_of(str(cell["modality"]), frames)
    figure = None
    if len(frames):
        spec, height = cell_figure(frames, errors)
        figure = plot(spec, height, "frames")
    closed_loop = has_loop_values(frames)
    route = night.routes.get(str(cell["dataset_key"])) if closed_loop else None
    path = None if route is None else plot(*top_view_figure(top_view(route, frames)), "top-view")
    folder = site / "cells"
    folder.mkdir(exist_ok=True)
    files = [f"cells/{cell_id}.html"]
    pictures = []
    for picture in night.pictures_of(cell_id):
        name = f"{cell_id}-frame-{picture.frame}.png"
        (folder / name).write_bytes(picture.png)
        files.append(f"cells/{name}")
        pictures.append(dict(src=name, frame=picture.frame, outcome=picture.outcome))
    counts = frames["outcome"].fillna("unscored").value_counts() if "outcome" in frames else pd.Series(dtype=int)
    of_board = night.metrics.for_board(str(cell["modality"]), errors)
    summary = {metric.name: metric.format(cell[metric.name]) for metric in of_board if metric.name in cell}
    run_id = int(cell["run_id"])
    replay = night.replay_rows.get(cell_id)
    if replay is not None:
        recorded = replay["state"] == RECORDED
        first, _, stop = str(replay["frames"]).partition(":")
        replay = dict(replay, href=f"../{replay_name(run_id, cell_id)}" if recorded else None,
                      shown_size=shown_size(int(replay["size"])), shown_frames=f"{first}\u2013{int(stop or 1) - 1}")
    earlier = night.cells[night.cells["id"] == night.previous.get(cell_id, -1)]
    versions = sorted({str(version) for version in earlier["tracker_version"]})
    html = render(
        "cell.html", night, night.run_row(run_id).to_dict(), "../",
        f"{cell['tracker']} on {cell['dataset']} \u00b7 trackbench nightly",
        cell=cell.to_dict(), tracker_href=night.tracker_href(str(cell["tracker"]), "../"), figure=figure,
        outcomes={outcome: int(counts.get(outcome, 0)) for outcome in OUTCOME_COLOURS}, summary=summary,
        pictures=pictures, replay=replay, changed=changed_parameters(cell["params"], list(earlier["params"])),
        closed_loop=closed_loop, path=path,
        old_version=", ".join(versions) if versions and versions != [str(cell["tracker_version"])] else "",
        earlier=int(earlier["id"].iloc[0]) if len(earlier) and int(earlier["run_id"].iloc[0]) in night.detailed
        else None,
        earlier_run=int(earlier["run_id"].iloc[0]) if len(earlier) else None,
        datatables=False, plotly=figure is not None or path is not None,
    )
    (folder / f"{cell_id}.html").write_text(html, encoding="utf-8")
    return Drawn(files, frames=frames if run_id == int(night.run["id"]) else None)


def replay_page(night: Night, cell_id: int, site: Path) -> Drawn:
    """``replays/<run>/<cell>.html``: a cell's replay page as the nightly recorded it, written out as it was kept."""
    run_id = int(night.cells.loc[night.cells["id"] == cell_id, "run_id"].iloc[0])
    name = replay_name(run_id, cell_id)
    (site / name).parent.mkdir(parents=True, exist_ok=True)
    (site / name).write_bytes(night.history.replay_page(cell_id))
    return Drawn([name])


PageKind = Callable[[Night, Any, Path], Drawn]

PAGE_KINDS: dict[str, PageKind] = {
    "index": index_page,
    "run": run_page,
    "tracker": tracker_page,
    "cell": cell_page,
    "replay": replay_page,
    "runs": runs_page,
}
"""Every kind of page but the compare page (:mod:`benchmark.site.compare`), by name."""
