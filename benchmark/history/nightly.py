"""A nightly run kept in the history: recorded with its machine and commit, and its changes told.

``trackbench nightly`` runs the benchmark like ``trackbench run``, then
:func:`record_nightly` appends the run to the history database,
:func:`benchmark.history.regressions.find_changes` compares it with the
runs before it, and :func:`benchmark.site.build_site` rewrites the site.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from pathlib import Path

import pandas as pd

from benchmark import __version__
from benchmark.history.database import History
from benchmark.history.machine import describe_machine, git_commit, machine_key
from benchmark.metrics import CORE, Metrics
from benchmark.modality import Modality
from benchmark.report.display import alignment, display_table
from benchmark.store import DATABASE_NAME, ResultStore


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
