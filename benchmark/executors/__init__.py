"""Where cells run: worker processes on this machine, a Dask cluster, or any engine a distribution adds.

An :class:`Executor` takes the cells of a run and yields their results as
they finish; the harness alone writes them to the results database.  Every
executor gives a cell the same guarantees (:mod:`benchmark.runner`): a
tracker that raises, exits, crashes or hangs turns its own cell into an
``error`` or ``timeout`` row, its worker is replaced, and the run goes on.

Executors are found by name in the entry-point group
:data:`ENTRY_POINT_GROUP`, as trackers are found in theirs; trackbench's own
are registered there too:

* ``local`` (:class:`~benchmark.executors.local.LocalExecutor`, the
  default): a pool of ``--jobs`` warm worker processes, or the calling
  process itself with ``--in-process``;
* ``dask`` (:class:`~benchmark.executors.dask_cluster.DaskExecutor`): each
  cell is a task of a ``dask.distributed`` cluster, the one at
  ``--scheduler ADDRESS`` or a local cluster of ``--jobs`` workers.

A new engine (Ray, Slurm) is one module with a class that has
:meth:`Executor.open`, and one entry point::

    [project.entry-points."trackbench.executors"]
    slurm = "my_package.slurm:SlurmExecutor"
"""

from __future__ import annotations

import importlib.metadata
from collections.abc import Callable, Iterable, Iterator, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Protocol

from benchmark.errors import DataError
from benchmark.faults import Call
from benchmark.runner import DEFAULT_TIMEOUT_S, sigint_is_user_interrupt

if TYPE_CHECKING:
    from benchmark.results import CellResult
    from benchmark.runner import Cell

ENTRY_POINT_GROUP = "trackbench.executors"
DEFAULT_EXECUTOR = "local"


@dataclass(frozen=True)
class ExecutorOptions:
    """The command line's choices for where cells run; each executor takes those it understands.

    Attributes
    ----------
    jobs : int or None
        Worker processes; None uses every core.
    in_process : bool
        Run the cells in the calling process, for debuggers.
    scheduler : str or None
        The address of a running scheduler.
    """

    jobs: int | None = None
    in_process: bool = False
    scheduler: str | None = None


class Executor(Protocol):
    """Runs cells, and single functions, with the isolation and time limits of a cell.

    Attributes
    ----------
    runs_here : bool
        The cells run in this process or its child processes, so that this
        process's resource usage counts their CPU time.
    """

    runs_here: bool

    @classmethod
    def open(cls, options: ExecutorOptions) -> Executor:
        """An executor for ``options``.

        Raises
        ------
        benchmark.errors.DataError
            For an option it does not take, or an engine it cannot reach, naming the option.
        """

    def run(self, cells: Sequence[Cell], timeout_s: float | None) -> Iterator[CellResult]:
        """Run ``cells`` and yield each result as it finishes; closing the iterator stops the rest."""

    def call(self, function: Callable[..., Any], args: tuple[Any, ...], timeout_s: float | None) -> Any:
        """``function(*args)`` in a worker under a time limit (a tracker's training).

        Raises whatever ``function`` raised, ``TimeoutError`` past the
        limit, or ``WorkerDied`` (a ``RuntimeError``) if the worker process ended.
        """

    def running(self) -> list[str]:
        """Labels of the cells running now, where the executor can tell."""

    def close(self) -> None:
        """Stop the workers."""


def _entry_points() -> dict[str, importlib.metadata.EntryPoint]:
    return {ep.name: ep for ep in importlib.metadata.entry_points(group=ENTRY_POINT_GROUP)}


def executor_names() -> tuple[str, ...]:
    """The names of the installed executors, the default first."""
    return tuple(sorted(_entry_points(), key=lambda name: (name != DEFAULT_EXECUTOR, name)))


def open_executor(name: str = DEFAULT_EXECUTOR, options: ExecutorOptions | None = None) -> Executor:
    """The installed executor called ``name``, opened with ``options``.

    Raises
    ------
    benchmark.errors.DataError
        For an executor that is not installed or cannot be loaded, an option
        it does not take, or an engine it cannot reach.
    """
    found = _entry_points()
    if name not in found:
        raise DataError(f"unknown executor {name!r} (installed: {', '.join(executor_names()) or 'none'})")
    entry = found[name]
    loading = Call.of(entry.load, f"loading executor {name!r}")
    if not loading.ok:
        where = entry.dist.name if entry.dist is not None else entry.value
        raise DataError(f"executor {name!r} ({where}) cannot be loaded: {loading.summary}")
    return loading.value().open(options or ExecutorOptions())


def run_cells(
    cells: Iterable[Cell],
    *,
    jobs: int | None = None,
    timeout_s: float | None = DEFAULT_TIMEOUT_S,
    in_process: bool = False,
    executor: Executor | None = None,
) -> Iterator[CellResult]:
    """Run cells and yield each result as it finishes (:mod:`benchmark.runner` defines a cell).

    Parameters
    ----------
    cells : iterable of Cell
        The cells to run.
    jobs : int, optional
        Worker processes; None uses every core (``os.cpu_count()``), and 0
        or 1 run one cell at a time in one worker.
    timeout_s : float, optional
        Time limit of each cell (None: no limit).  A worker still busy a
        grace period after the limit is killed and its cell becomes a
        ``"timeout"`` result without frames.
    in_process : bool
        Run the cells one after another in this process, for debuggers and
        profilers: the limit is then checked between frames only, and a
        tracker that ends the process ends the run.
    executor : Executor, optional
        Where to run them; by default the local pool of ``jobs`` workers,
        or this process with ``in_process``.

    Yields
    ------
    CellResult
        One per cell, in order of completion (input order in process).

    Raises
    ------
    benchmark.runner.UserInterrupt
        On the user's Ctrl-C; the workers are stopped first.

    Notes
    -----
    Closing the generator early stops the workers.
    """
    todo = list(cells)
    executor = executor or open_executor(DEFAULT_EXECUTOR, ExecutorOptions(jobs, in_process))
    with sigint_is_user_interrupt():
        yield from executor.run(todo, timeout_s)
