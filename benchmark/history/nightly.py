"""A nightly run kept in the history: recorded with its machine, load and commit, and its changes told.

:func:`run_nightly` is the whole sequence of ``trackbench nightly``: it
runs the benchmark like ``trackbench run`` while measuring how busy the
machine is (:class:`benchmark.history.machine.LoadMeter`), then
:func:`record_nightly` appends the run to the history database,
:func:`benchmark.history.regressions.find_changes` compares it with the
runs before it, the cells of every series with a speed change run once
more into ``OUT/repeat`` and a change holds only if the repeat shows it
too (:func:`benchmark.history.regressions.confirm_speed`), the failed
cells are replayed into the history within a size budget
(:func:`benchmark.history.replays.record_replays`), and
:func:`benchmark.site.build_site` rewrites the site.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from datetime import UTC, datetime
from pathlib import Path
from typing import TYPE_CHECKING, Any

import pandas as pd

from benchmark import __version__
from benchmark.history.database import History
from benchmark.history.machine import LoadMeter, describe_machine, git_commit, machine_key
from benchmark.history.regressions import Thresholds, confirm_speed, find_changes, group_changes, judged_speed
from benchmark.history.replays import ReplayPlan, ReplaySummary, record_replays
from benchmark.metrics import CORE, Metrics
from benchmark.modality import Modality
from benchmark.report.summary import terminal_width
from benchmark.results import summarise
from benchmark.site import build_site
from benchmark.site.pages import replay_back
from benchmark.store import DATABASE_NAME, ResultStore
from benchmark.text import counted, one_line, shortened

if TYPE_CHECKING:
    from benchmark.closedloop.route import Route
    from benchmark.harness import RunSummary
    from benchmark.progress import Report
    from benchmark.runner import Cell

REPEAT_FOLDER = "repeat"
"""The folder of ``OUT`` the repeat of the cells with a speed change writes its results database into."""

Series = frozenset[tuple[str, str]]
"""Tracker and dataset names whose cells a repeat runs again."""
RunInto = Callable[[Path, "Callable[[Cell], bool] | None"], "RunSummary"]
"""``run(out, only)``: runs the benchmark into ``out``, only the cells ``only`` keeps when given."""


CHANGES_NAME = "changes.csv"
"""The file of the run's folder holding every change the nightly found, one row per tracker, dataset and metric."""


@dataclass(frozen=True)
class Nightly:
    """A nightly run as kept: how the benchmark run went, its id in the history, its changes and the site.

    Attributes
    ----------
    summary : RunSummary
        How the benchmark run went.
    run_id : int
        Its id in the history.
    changes : pandas.DataFrame
        Its changes (:func:`~benchmark.history.regressions.find_changes`),
        speed changes held against the repeat.
    index : pathlib.Path
        The site's front page.
    load : dict
        How busy the machine was during the run (:meth:`LoadMeter.stop`).
    repeat : RunSummary or None
        The repeat of the cells with a speed change; None when none had one.
    replays : ReplaySummary or None
        What the replay step recorded; None when the nightly was given no replay plan.
    """

    summary: RunSummary
    run_id: int
    changes: pd.DataFrame
    index: Path
    load: dict[str, Any] = field(default_factory=dict)
    repeat: RunSummary | None = None
    replays: ReplaySummary | None = None

    def _regressed(self, kind: str) -> bool:
        return bool(((self.changes["verdict"] == "regression") & (self.changes["kind"] == kind)).any())

    @property
    def accuracy_regressed(self) -> bool:
        """Whether a metric other than speed regressed (detection rates, RMSEs, robustness)."""
        return self._regressed("accuracy")

    @property
    def speed_regressed(self) -> bool:
        """Whether a speed regressed beyond its noise and held on the repeat."""
        return self._regressed("speed")


def speed_series(changes: pd.DataFrame) -> Series:
    """The tracker and dataset names of the speed changes that a repeat is to hold or drop."""
    judged = changes[judged_speed(changes)]
    return frozenset(zip(judged["tracker"], judged["dataset"]))


def of_series(series: Series) -> Callable[[Cell], bool]:
    """Whether a cell belongs to one of ``series`` (its tracker's and its dataset's names)."""
    return lambda cell: (cell.tracker.name, cell.dataset) in series


def repeat_speeds(folder: Path, run_id: int | None, metrics: Metrics = CORE) -> pd.DataFrame:
    """The speeds of the cells of run ``run_id`` of the results database in ``folder`` that ended ok.

    Returns
    -------
    pandas.DataFrame
        ``tracker``, ``dataset``, ``seed`` and a column per speed metric of
        every board (:meth:`benchmark.metrics.Metrics.for_board`).
    """
    speeds = [metric for metric in metrics.for_board(None, ()) if metric.kind == "speed"]
    with ResultStore(folder / DATABASE_NAME) as results:
        cells = results.cells(run_id)
        cells = cells[cells["status"] == "ok"]
        frames = results.frame_tables(cells["id"])
    rows = [
        {"tracker": cell.tracker, "dataset": cell.dataset, "seed": cell.seed,
         **summarise(frames[frames["cell_id"] == cell.id], speeds)}
        for cell in cells.itertuples(index=False)
    ]
    return pd.DataFrame(rows, columns=["tracker", "dataset", "seed", *(metric.name for metric in speeds)])


def run_nightly(
    run: RunInto,
    history: str | Path,
    out: Path,
    site: Path,
    modalities: Mapping[str, Modality],
    thresholds: Thresholds,
    *,
    argv: Sequence[str],
    seeds: int,
    metrics: Metrics = CORE,
    report: Report | None = None,
    replays: ReplayPlan | None = None,
    log: Callable[[str], None] = lambda line: None,
    routes: Mapping[str, Route] | None = None,
) -> Nightly:
    """Run the benchmark into ``out``, append the run to ``history``, find its changes and rewrite ``site``.

    Parameters
    ----------
    run : callable
        ``run(folder, only)`` runs the benchmark with the nightly's options,
        writing its results database into ``folder``; ``only``, when given,
        keeps the cells to run (the repeat's).  It must not take over
        earlier cells (``--resume``) when ``only`` is given.
    history : str or pathlib.Path
        The history database: an SQLite file or an SQLAlchemy URL.
    out, site : pathlib.Path
        The run's results folder and the site's folder.
    modalities : Mapping
        The registered modalities by name.
    thresholds : Thresholds
        What counts as a regression or an improvement.
    argv, seeds
        The command line and the number of seeds, kept with the run.
    metrics : Metrics
        The catalogue of metrics kept, judged and shown (the registry's).
    report : callable, optional
        Told ``report(done, total)`` pages as the site is built
        (:class:`benchmark.progress.Meter`).
    replays : ReplayPlan, optional
        The budget and the cells of the replays of the failed cells
        (:func:`~benchmark.history.replays.record_replays`); none without it.
    log : callable
        Told a line for each replay that failed (which fails nothing else).
    routes : Mapping, optional
        The route of each closed-loop dataset by its key, over which the
        site draws each closed-loop cell's path (:func:`benchmark.site.build_site`).

    Notes
    -----
    A speed change (:func:`~benchmark.history.regressions.find_changes`)
    runs the cells of its tracker and dataset once more, right away, into
    ``out/repeat``; it stands only if the repeat's median is beyond the same
    threshold in the same direction
    (:func:`~benchmark.history.regressions.confirm_speed`).  A burst of load
    on a shared machine seldom lasts over both, a slower tracker always
    does.  The repeat's cells are not recorded in the history; the verdicts
    it gave are, with the run's changes (:meth:`History.record_changes`).
    """
    started = datetime.now(UTC).isoformat(timespec="seconds")
    meter = LoadMeter.start()
    summary = run(out, None)
    load = meter.stop()
    repeat = None
    with History(history) as database:
        run_id = record_nightly(
            database,
            out,
            summary.publication.run_id,
            modalities,
            started=started,
            argv=argv,
            seeds=seeds,
            metrics=metrics,
            load=load,
            boards=summary.publication.boards,
        )
        changes = find_changes(database.cells(), run_id, thresholds, metrics=metrics)
        series = speed_series(changes)
        if series:
            repeat = run(out / REPEAT_FOLDER, of_series(series))
            speeds = repeat_speeds(out / REPEAT_FOLDER, repeat.publication.run_id, metrics)
            changes = confirm_speed(changes, speeds)
        database.record_changes(run_id, changes)
        changes.to_csv(out / CHANGES_NAME, index=False)
        replayed = None
        if replays is not None:
            replayed = record_replays(database, run_id, changes, replays, out, replay_back, log)
        index = build_site(database, site, modalities, thresholds=thresholds, metrics=metrics, report=report,
                           routes=routes)
    return Nightly(summary, run_id, changes, index, load, repeat, replayed)


def record_nightly(
    history: History,
    out: Path,
    run_id: int,
    modalities: Mapping[str, Modality],
    *,
    started: str,
    argv: Sequence[str],
    seeds: int,
    metrics: Metrics = CORE,
    load: Mapping[str, Any] | None = None,
    boards: Mapping[str, pd.DataFrame] | None = None,
) -> int:
    """Append run ``run_id`` of the results database in ``out`` to ``history``, with this machine, its load and commit.

    ``boards``, the run's published leaderboards, are kept with it.

    Returns
    -------
    int
        The run's id in the history.
    """
    machine = describe_machine()
    with ResultStore(out / DATABASE_NAME) as results:
        return history.record(
            results,
            run_id,
            modalities,
            started=started,
            version=__version__,
            commit=git_commit(),
            machine=machine,
            machine_key=machine_key(machine),
            argv=argv,
            seeds=seeds,
            metrics=metrics,
            load=load,
            boards=boards,
        )


def describe_changes(
    changes: pd.DataFrame, title: str, metrics: Metrics = CORE, file: Path | None = None, width: int | None = None
) -> str:
    """The changes of :func:`~benchmark.history.regressions.find_changes` for a terminal: accuracy and speed apart,
    one entry per tracker and cause (:func:`~benchmark.history.regressions.group_changes`), the largest first.

    Each entry is its verdict, tracker and largest change on one line, then
    its cause, what it touched and its note, each line cut to ``width`` (the terminal's by
    default); ``file``, where given, is named as the place that holds every
    change.
    """
    if changes.empty:
        return f"{title}: no change beyond the thresholds."
    width = width or terminal_width()
    groups = group_changes(changes, metrics)
    where = f"; every change in {file}" if file is not None else ""
    lines = [f"{title}: {len(changes)} changes, {len(groups)} by tracker and cause{where}"]
    for kind, of_kind in groups.groupby("kind", sort=False):
        verdicts = of_kind["verdict"].value_counts()
        counts = ", ".join(f"{verdicts[v]} {v}{'s' if verdicts[v] > 1 else ''}" for v in verdicts.index)
        lines += ["", f"{str(kind).capitalize()}: {counts}"]
        for group in of_kind.itertuples():
            touched = f"{counted(len(group.datasets), 'dataset')}, {counted(len(group.metrics), 'metric')}"
            entry = [f"  {group.verdict:<12} {one_line(group.tracker)}  {group.headline}",
                     f"  {'':<12} cause: {one_line(group.cause) or '(none found)'}",
                     f"  {'':<12} {counted(group.count, 'change')} on {touched}: {_first(group.metrics)}"]
            if note := _note(group.rows):
                entry.append(f"  {'':<12} note: {one_line(note)}")
            lines += [shortened(line, width) for line in entry]
    return "\n".join(lines) + "\n"


def _first(names: list[str], shown: int = 3) -> str:
    """The first ``shown`` of ``names``, and how many more."""
    more = f" (+{len(names) - shown})" if len(names) > shown else ""
    return ", ".join(names[:shown]) + more


def _note(rows: pd.DataFrame) -> str:
    """What a reader must know of a group's changes: the first note of its rows, and how many more there are."""
    notes = [note for note in rows["note"].fillna("") if note]
    return notes[0] + (f" (+{len(notes) - 1})" if len(notes) > 1 else "") if notes else ""
