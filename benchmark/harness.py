"""The run sequence: resume, run, store and publish a benchmark.

A benchmark run takes the cells a :class:`~benchmark.selection.Selection`
asks for (:func:`benchmark.selection.select_cells`), leaves out those
whose tracker needs what their sequence lacks (a camera calibration that
a sequence file's sidecar does not give, :func:`benchmark.selection.unmet_needs`),
saying so before any cell runs and listing them with the run's problems, and

1. takes the lock of ``OUT`` (``OUT/results.sqlite.lock``), so that two
   runs never write one database and compute the same cells twice;
2. records the run in the results database ``OUT/results.sqlite``, with the
   plugins that could not be loaded;
3. with ``resume``, takes over every cell the database already finished
   with status ``ok`` (same tracker key, dataset identity, seed and
   initialisation) and runs only the others;
4. reads every simulated sequence through the frame cache
   (:mod:`benchmark.frame_cache`), so that each is rendered once, by the
   first cell that reads it, and never again while the cache holds it;
5. keeps the conditions each sequence was made under
   (:func:`record_conditions`), for the boards by condition;
6. fits the trackers that learn, once per training set, on the cells left
   to run (:func:`benchmark.training.fit_models`), reusing a model stored
   in ``OUT/models``;
7. runs the cells on an executor (:mod:`benchmark.executors`: warm local
   worker processes, or a Dask cluster), storing each one in its own
   transaction as it finishes, so an interrupted run loses nothing
   finished, and telling a :class:`~benchmark.progress.Progress` about it;
8. publishes the run's leaderboards (:func:`publish`): ranked per modality,
   written atomically to ``OUT/leaderboard.{csv,md,html}``, and, where its
   sequences record conditions, correct % by condition in
   ``OUT/conditions.{csv,md}`` (:mod:`benchmark.by_condition`), also after
   the user's Ctrl-C.

Commands (``trackbench run``, ``trackbench leaderboard``) are thin layers
over :func:`run_benchmark` and :func:`publish`; whatever they print goes
through a ``log`` callback, one line per event.
"""

from __future__ import annotations

import collections
import dataclasses
import math
import resource
import signal
import time
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import filelock
import pandas as pd

from benchmark.by_condition import condition_board
from benchmark.errors import DataError
from benchmark.executors import DEFAULT_EXECUTOR, Executor, ExecutorOptions, open_executor, run_cells
from benchmark.files import make_folder
from benchmark.frame_cache import CachedSequence, FrameCache
from benchmark.leaderboard import leaderboards
from benchmark.metrics import CORE, SPEED, Metrics
from benchmark.modality import Modality
from benchmark.progress import Meter, Progress, SilentProgress
from benchmark.report import write_condition_board, write_leaderboards
from benchmark.report.display import NO_TRUTH
from benchmark.text import one_line, printable
from benchmark.results import CellResult
from benchmark.runner import DEFAULT_TIMEOUT_S, Cell
from benchmark.selection import unmet_needs
from benchmark.store import DATABASE_NAME, ResultStore
from benchmark.training import fit_models

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
        ``leaderboard.csv``, ``leaderboard.md`` and ``leaderboard.html``, then
        ``conditions.csv`` and ``conditions.md`` when the run has sequences
        with conditions.
    problems : list of str
        What went wrong outside any cell.
    by_condition : pandas.DataFrame
        Correct, false and missed per cent per suite, condition and bin
        (:func:`benchmark.by_condition.condition_board`); empty when no
        sequence of the run records its conditions.
    metrics : Metrics
        The catalogue the boards were made with, which rounds them for reading.
    """

    run_id: int | None
    boards: dict[str, pd.DataFrame]
    files: list[Path]
    problems: list[str] = field(default_factory=list)
    by_condition: pd.DataFrame = field(default_factory=pd.DataFrame)
    metrics: Metrics = CORE


@dataclass(frozen=True)
class RunSummary:
    """How a benchmark run went.

    Attributes
    ----------
    publication : Publication
        The run's boards and files.
    statuses : collections.Counter
        Cells of the run by status, resumed cells counted as ``ok``.
    interrupted : int
        The signal that stopped the run (``SIGINT`` for Ctrl-C, ``SIGTERM``),
        0 when nothing did; the cells not finished are not in it.
    elapsed_s : float
        Wall time of the run.
    rendered : int
        Sequences rendered into the frame cache by this run.
    step_s, read_s : float
        CPU time the cells run now spent in their trackers' ``step``
        (:mod:`benchmark.runner`), and wall time getting their frames
        (rendering or reading them).
    cpu_s : float or None
        CPU time of this process and its worker processes over the run;
        None when the cells ran elsewhere (a Dask cluster).
    """

    publication: Publication
    statuses: collections.Counter[str]
    interrupted: int = 0
    elapsed_s: float = 0.0
    rendered: int = 0
    step_s: float = 0.0
    read_s: float = 0.0
    cpu_s: float | None = None

    def describe(self) -> str:
        """One line: cells by status, wall time, sequences rendered, where the time went."""
        total = self.statuses.total()
        counts = ", ".join(f"{count} {status}" for status, count in sorted(self.statuses.items())) or "none"
        minutes, seconds = divmod(round(self.elapsed_s), 60)
        line = (
            f"{total} cells ({counts}) in {minutes}:{seconds:02d}; {self.rendered} sequences rendered; "
            f"tracker steps {self.step_s:.1f} s CPU, frames {self.read_s:.1f} s"
        )
        if self.cpu_s is not None:
            line += f", CPU {self.cpu_s:.1f} s"
        return f"{line}; interrupted" if self.interrupted else line

    @property
    def clean(self) -> bool:
        """Every cell ran ``ok``, no plugin was left out and nothing was interrupted."""
        failed = self.statuses.total() - self.statuses["ok"]
        return not (failed or self.publication.problems or self.interrupted)


def _cpu_s() -> float:
    """CPU time of this process and of its child processes that ended (pool workers once joined)."""
    own, children = resource.getrusage(resource.RUSAGE_SELF), resource.getrusage(resource.RUSAGE_CHILDREN)
    return own.ru_utime + own.ru_stime + children.ru_utime + children.ru_stime


def describe_result(result: CellResult) -> str:
    """One line on a finished cell: tracker, dataset, seed, status, correct % (or no truth), CPU fps, frames, time.

    A cell run in real time says so, with its step time's source, after its seed.
    """
    summary = result.summary()
    correct = summary.get("correct_pct", math.nan)
    fps = summary.get(SPEED.name, math.nan)
    unscored = result.status == "ok" and result.scores and not summary.get("frames")
    rate = NO_TRUTH if unscored else f"correct {correct:.1f}%"
    real_time = f"  real time ({result.real_time})" if result.real_time else ""
    line = (
        f"{result.tracker}  {result.dataset}  seed {result.seed}{real_time}  {result.status}  "
        f"{rate}  {fps:.0f} cpu fps  ({len(result.scores)} frames, {result.elapsed_s:.1f} s)"
    )
    return printable(f"{line}  {one_line(result.message)}" if result.message else line)


def publish(
    store: ResultStore,
    modalities: Mapping[str, Modality],
    out: Path,
    run_id: int | None = None,
    *,
    all_runs: bool = False,
    metrics: Metrics = CORE,
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
    metrics : Metrics
        The catalogue of metrics (the registry's).
    """
    run_id = store.latest_run() if run_id is None and not all_runs else run_id
    cells = store.cells(run_id, all_runs=all_runs)
    frames = store.frame_tables(cells["id"])
    boards = leaderboards(cells, frames, modalities, metrics)
    by_condition = condition_board(cells, frames, store.conditions(cells["dataset_key"]))
    problems = [] if all_runs else store.run_problems(run_id)
    caption = (
        f"All runs of {store.path}." if all_runs else f"Run {run_id} of {store.path}." if run_id else "No runs."
    )
    files = write_leaderboards(boards, out, caption, problems=problems, metrics=metrics)
    files += write_condition_board(by_condition, out, caption)
    return Publication(None if all_runs else run_id, boards, files, problems, by_condition, metrics)


def record_conditions(store: ResultStore, cells: Iterable[Cell], log: Log) -> None:
    """Keep the conditions of every sequence the cells read (:meth:`benchmark.model.Sequence.conditions`).

    A sequence that fails to tell its conditions costs only them: the
    failure is logged, naming the sequence, and the run goes on.  A
    sequence whose conditions the store holds already is not asked again
    (a camera scene renders frames to measure its contrast).  The sequences
    asked are counted as they go (:class:`benchmark.progress.Meter`).
    """
    cells = list(cells)
    known = store.conditions(cell.identity.key for cell in cells)
    asked = {cell.identity.key: cell for cell in cells if cell.identity.key not in known}
    found: dict[str, dict[str, Any]] = {}
    if not asked:
        return
    with Meter("sequences' conditions", len(asked)) as meter:
        for key, cell in asked.items():
            try:
                found[key] = dict(cell.sequence.conditions())
            except Exception as exc:  # noqa: BLE001 - a sequence's own failure must not stop the run
                found[key] = {}
                log(f"{cell.identity.name}: its conditions could not be measured ({type(exc).__name__}: {exc})")
            meter.advance()
    store.add_conditions({key: conditions for key, conditions in found.items() if conditions})


def _lock(out: Path) -> filelock.BaseFileLock:
    """The lock of the results database in ``out``, taken; ``out`` is created if missing."""
    lock = filelock.FileLock(make_folder(out) / f"{DATABASE_NAME}.lock")
    try:
        lock.acquire(timeout=0)
    except filelock.Timeout:
        raise DataError(
            f"{out}: another trackbench run is writing this results folder; wait for it or choose another --out"
        ) from None
    except OSError as exc:
        raise DataError(f"{out}: cannot write the results folder: {exc.strerror or exc}") from None
    return lock


def _read_through(cells: list[Cell], cache: FrameCache) -> list[Cell]:
    """The cells, and their training sets, reading every simulated sequence through ``cache``."""
    result = []
    for cell in cells:
        training = cell.training
        if training is not None and training.sequences:
            training = dataclasses.replace(training, sequences=tuple(map(cache.wrap, training.sequences)))
        result.append(dataclasses.replace(cell, sequence=cache.wrap(cell.sequence), training=training))
    return result


def _unrendered(cells: Iterable[Cell], cache: FrameCache) -> list[Path]:
    """The cache files the cells' sequences (and training sets) read that do not exist yet, each once."""
    paths = set()
    for cell in cells:
        training = () if cell.training is None else cell.training.sequences
        for sequence in (cell.sequence, *training):
            if isinstance(sequence, CachedSequence):
                paths.add(cache.path(sequence.key))
    return sorted(path for path in paths if not path.is_file())


def run_benchmark(
    cells: Iterable[Cell],
    modalities: Mapping[str, Modality],
    out: Path,
    *,
    jobs: int | None = None,
    timeout_s: float | None = DEFAULT_TIMEOUT_S,
    in_process: bool = False,
    executor: Executor | None = None,
    frame_cache: FrameCache | None = None,
    resume: bool = False,
    argv: Sequence[str] = (),
    options: Mapping[str, Any] | None = None,
    problems: Sequence[str] = (),
    log: Log = lambda line: None,
    progress: Progress | None = None,
    metrics: Metrics = CORE,
) -> RunSummary:
    """Run cells, store every one as it finishes, and publish the run's leaderboards.

    Parameters
    ----------
    cells : iterable of Cell
        What to run (:func:`benchmark.selection.select_cells`).
    modalities : Mapping
        The registered modalities by name.
    out : pathlib.Path
        Folder of the results database and the leaderboards; created if missing.
    jobs, timeout_s, in_process
        As for :func:`benchmark.executors.run_cells`.
    executor : Executor, optional
        Where the cells run (:mod:`benchmark.executors`); by default the
        local pool of ``jobs`` workers (or this process, ``in_process``).
    frame_cache : FrameCache, optional
        Where simulated sequences are rendered once and read back; None
        renders them in every cell that reads them.
    resume : bool
        Take over the cells this database already finished with status
        ``ok`` (same tracker key, dataset identity, seed and initialisation)
        instead of running them again.
    argv, options
        The command line and its parsed options, recorded with the run.
    problems : sequence of str
        Plugins left out (:attr:`benchmark.registry.Registry.problems`),
        recorded with the run and shown on its boards.  The cells whose
        tracker needs what their sequence lacks
        (:func:`benchmark.selection.unmet_needs`) are not run: each such
        pair is logged before any cell runs and joins these problems, so
        the run is not :attr:`~RunSummary.clean`.
    log : callable
        Receives a line for the resumed cells, the frame cache and every
        training.
    progress : Progress, optional
        Told how many cells run and each cell as it finishes (it decides
        which cells get a line: :class:`~benchmark.progress.TerminalProgress`
        writes one for every failed cell).
    metrics : Metrics
        The catalogue of metrics of the boards (the registry's).

    Returns
    -------
    RunSummary
        The run's boards, files and cell statuses.  On the user's Ctrl-C
        the cells finished so far are published and ``interrupted`` is set.

    Raises
    ------
    DataError
        If ``out`` cannot be written, another run holds its lock, or its
        database is not a trackbench database.
    """
    todo, unmet = unmet_needs(cells)
    for line in unmet:
        log(line)
    problems = [*problems, *unmet]
    statuses: collections.Counter[str] = collections.Counter()
    ran = rendered = 0
    step_s = read_s = 0.0
    interrupted = 0
    started, cpu_started = time.perf_counter(), _cpu_s()
    executor = executor or open_executor(DEFAULT_EXECUTOR, ExecutorOptions(jobs, in_process))
    progress = progress or SilentProgress()
    lock = _lock(out)
    try:
        with ResultStore(out / DATABASE_NAME) as store:
            run_id = store.start_run(argv, dict(options or {}), problems=problems)
            if resume:
                done = store.find_ok_cells(cell.key for cell in todo)
                store.reuse_cells(run_id, done.values())
                todo = [cell for cell in todo if cell.key not in done]
                statuses["ok"] += len(done)
                log(f"resume: {len(done)} cells already finished, {len(todo)} to run")
            missing: list[Path] = []
            if frame_cache is not None:
                todo = _read_through(todo, frame_cache)
                missing = _unrendered(todo, frame_cache)
            try:
                record_conditions(store, todo, log)
                todo = fit_models(todo, out, executor.call, timeout_s, log)
                if frame_cache is not None:  # a reused model needs none of its training sequences
                    log(f"frame cache {frame_cache.folder}: {len(_unrendered(todo, frame_cache))} sequences to render")
                progress.start(len(todo))
                for result in run_cells(todo, timeout_s=timeout_s, executor=executor):
                    store.add_cell(run_id, result)
                    statuses[result.status] += 1
                    ran += 1
                    step_s += sum(score.step_s for score in result.scores)
                    read_s += result.read_s
                    progress.advance(result, executor.running)
                store.finish_run(run_id)
            except KeyboardInterrupt as stop:
                interrupted = getattr(stop, "signum", signal.SIGINT)
                log(f"interrupted: {ran} cells finished and kept, {len(todo) - ran} not run")
            finally:
                progress.close()
                rendered = sum(path.is_file() for path in missing)
            publication = publish(store, modalities, out, run_id, metrics=metrics)
            cpu_s = _cpu_s() - cpu_started if executor.runs_here else None
            elapsed_s = time.perf_counter() - started
            return RunSummary(publication, statuses, interrupted, elapsed_s, rendered, step_s, read_s, cpu_s)
    finally:
        lock.release()
