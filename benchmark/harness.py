"""The run sequence: resume, run, store and publish a benchmark.

A benchmark run takes the cells a :class:`~benchmark.selection.Selection`
asks for (:func:`benchmark.selection.select_cells`) and

1. records the run in the results database ``OUT/results.sqlite``;
2. with ``resume``, takes over every cell the database already finished
   with status ``ok`` and runs only the others;
3. runs the cells (:func:`benchmark.runner.run_cells`), storing each one in
   its own transaction as it finishes, so an interrupted run loses nothing
   finished;
4. publishes the run's leaderboards (:func:`publish`): ranked per modality,
   written to ``OUT/leaderboard.{csv,md,html}``.

Commands (``trackbench run``, ``trackbench leaderboard``) are thin layers
over :func:`run_benchmark` and :func:`publish`; whatever they print goes
through a ``log`` callback, one line per event.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import pandas as pd

from benchmark.leaderboard import load_leaderboards
from benchmark.modality import Modality
from benchmark.report import write_leaderboards
from benchmark.results import CellResult
from benchmark.runner import DEFAULT_TIMEOUT_S, Cell, run_cells
from benchmark.store import DATABASE_NAME, ResultStore

Log = Callable[[str], None]
"""Receives one line of progress at a time."""


@dataclass(frozen=True)
class Publication:
    """The leaderboards of a run and the files they were written to.

    Attributes
    ----------
    run_id : int or None
        The run published (None for the latest cell of every run).
    boards : dict
        Modality name to ranked board (:func:`benchmark.leaderboard.leaderboards`).
    files : list of pathlib.Path
        ``leaderboard.csv``, ``leaderboard.md`` and ``leaderboard.html``.
    """

    run_id: int | None
    boards: dict[str, pd.DataFrame]
    files: list[Path]


def describe_result(result: CellResult) -> str:
    """One line on a finished cell: tracker, dataset, seed, status, correct %, fps, frames and time."""
    summary = result.summary()
    correct = summary.get("correct_pct", math.nan)
    fps = summary.get("fps", math.nan)
    line = (
        f"{result.tracker}  {result.dataset}  seed {result.seed}  {result.status}  "
        f"correct {correct:.1f}%  {fps:.0f} fps  ({len(result.scores)} frames, {result.elapsed_s:.1f} s)"
    )
    return f"{line}  {result.message}" if result.message else line


def publish(
    store: ResultStore,
    modalities: Mapping[str, Modality],
    out: Path,
    run_id: int | None = None,
    *,
    all_runs: bool = False,
) -> Publication:
    """Rank a stored run's cells per modality and write the leaderboards into ``out``.

    Parameters
    ----------
    store : ResultStore
        The results database.
    modalities : Mapping
        The registered modalities, whose scorers name each board's error columns.
    out : pathlib.Path
        Folder for the leaderboard files.
    run_id : int, optional
        The run to publish; defaults to the latest run with cells.
    all_runs : bool
        Publish the latest cell of every run instead.
    """
    run_id = store.latest_run() if run_id is None and not all_runs else run_id
    boards = load_leaderboards(store, modalities, run_id, all_runs=all_runs)
    caption = (
        f"All runs of {store.path}." if all_runs else f"Run {run_id} of {store.path}." if run_id else "No runs."
    )
    return Publication(None if all_runs else run_id, boards, write_leaderboards(boards, out, caption))


def run_benchmark(
    cells: Iterable[Cell],
    modalities: Mapping[str, Modality],
    out: Path,
    *,
    jobs: int | None = None,
    timeout_s: float | None = DEFAULT_TIMEOUT_S,
    resume: bool = False,
    argv: Sequence[str] = (),
    options: Mapping[str, Any] | None = None,
    log: Log = lambda line: None,
) -> Publication:
    """Run cells, store every one as it finishes, and publish the run's leaderboards.

    Parameters
    ----------
    cells : iterable of Cell
        What to run (:func:`benchmark.selection.select_cells`).
    modalities : Mapping
        The registered modalities by name.
    out : pathlib.Path
        Folder of the results database and the leaderboards; created if missing.
    jobs, timeout_s
        As for :func:`benchmark.runner.run_cells`.
    resume : bool
        Take over the cells this database already finished with status
        ``ok`` (same tracker key, dataset, seed and initialisation) instead
        of running them again.
    argv, options
        The command line and its parsed options, recorded with the run.
    log : callable
        Receives a line for the resumed cells and for every finished cell.

    Returns
    -------
    Publication
        The run's boards and the files written.
    """
    todo = list(cells)
    out.mkdir(parents=True, exist_ok=True)
    with ResultStore(out / DATABASE_NAME) as store:
        run_id = store.start_run(argv, dict(options or {}))
        if resume:
            done = store.find_ok_cells(cell.key for cell in todo)
            store.reuse_cells(run_id, done.values())
            todo = [cell for cell in todo if cell.key not in done]
            log(f"resume: {len(done)} cells already finished, {len(todo)} to run")
        for result in run_cells(todo, jobs=jobs, timeout_s=timeout_s):
            store.add_cell(run_id, result)
            log(describe_result(result))
        store.finish_run(run_id)
        return publish(store, modalities, out, run_id)
