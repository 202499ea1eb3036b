"""A nightly run kept in the history: recorded with its machine and commit, and its changes told.

:func:`run_nightly` is the whole sequence of ``trackbench nightly``: it
runs the benchmark like ``trackbench run``, then :func:`record_nightly`
appends the run to the history database,
:func:`benchmark.history.regressions.find_changes` compares it with the
runs before it, and :func:`benchmark.site.build_site` rewrites the site.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from datetime import UTC, datetime
from pathlib import Path
from typing import TYPE_CHECKING

import pandas as pd

from benchmark import __version__
from benchmark.history.database import History
from benchmark.history.machine import describe_machine, git_commit, machine_key
from benchmark.history.regressions import Thresholds, find_changes
from benchmark.metrics import CORE, Metrics
from benchmark.modality import Modality
from benchmark.report.display import alignment, display_table
from benchmark.site import build_site
from benchmark.store import DATABASE_NAME, ResultStore

if TYPE_CHECKING:
    from benchmark.harness import RunSummary
    from benchmark.progress import Report


@dataclass(frozen=True)
class Nightly:
    """A nightly run as kept: how the benchmark run went, its id in the history, its changes and the site."""

    summary: RunSummary
    run_id: int
    changes: pd.DataFrame
    index: Path

    @property
    def regressed(self) -> bool:
        """Whether a change is a regression."""
        return bool((self.changes["verdict"] == "regression").any())


def run_nightly(
    run: Callable[[], RunSummary],
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
) -> Nightly:
    """Run the benchmark into ``out``, append the run to ``history``, find its changes and rewrite ``site``.

    Parameters
    ----------
    run : callable
        Runs the benchmark, writing its results database into ``out``.
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
    """
    started = datetime.now(UTC).isoformat(timespec="seconds")
    summary = run()
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
        )
        changes = find_changes(database.cells(), run_id, thresholds, metrics=metrics)
        index = build_site(database, site, modalities, thresholds=thresholds, metrics=metrics, report=report)
    return Nightly(summary, run_id, changes, index)


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
) -> int:
    """Append run ``run_id`` of the results database in ``out`` to ``history``, with this machine and commit.

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
        )


def describe_changes(changes: pd.DataFrame, title: str) -> str:
    """The changes of :func:`~benchmark.history.regressions.find_changes` as a titled table for a terminal."""
    if changes.empty:
        return f"{title}: no change beyond the thresholds."
    shown = changes.assign(
        ratio=changes["after"] / changes["before"].where(changes["before"] != 0),
    )[["verdict", "tracker", "dataset", "metric", "before", "after", "change", "ratio", "cause"]]
    shown = shown.round({"before": 3, "after": 3, "change": 3, "ratio": 3})
    table = display_table(shown).to_markdown(
        index=False, tablefmt="simple", disable_numparse=True, colalign=alignment(shown)
    )
    return f"{title}\n\n{table}\n"
