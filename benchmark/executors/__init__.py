"""Where cells run: worker processes on this machine, or a Dask cluster.

An :class:`Executor` takes the cells of a run and yields their results as
they finish; the harness alone writes them to the results database.  Every
executor gives a cell the same guarantees (:mod:`benchmark.runner`): a
tracker that raises, exits, crashes or hangs turns its own cell into an
``error`` or ``timeout`` row, its worker is replaced, and the run goes on.

* :class:`~benchmark.executors.local.LocalExecutor` (``--executor local``,
  the default): a pool of ``--jobs`` warm worker processes, or the calling
  process itself with ``--in-process``;
* :class:`~benchmark.executors.dask_cluster.DaskExecutor` (``--executor
  dask``): each cell is a task of a ``dask.distributed`` cluster, the one
  at ``--scheduler ADDRESS`` or a local cluster of ``--jobs`` workers.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator, Sequence
from typing import TYPE_CHECKING, Any, Literal, Protocol

if TYPE_CHECKING:
    from benchmark.results import CellResult
    from benchmark.runner import Cell

ExecutorName = Literal["local", "dask"]
EXECUTORS: tuple[ExecutorName, ...] = ("local", "dask")


class Executor(Protocol):
    """Runs cells, and single functions, with the isolation and time limits of a cell.

    Attributes
    ----------
    runs_here : bool
        The cells run in this process or its child processes, so that this
        process's resource usage counts their CPU time.
    """

    runs_here: bool

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


def open_executor(
    name: ExecutorName = "local",
    *,
    jobs: int | None = None,
    in_process: bool = False,
    scheduler: str | None = None,
) -> Executor:
    """The executor called ``name``.

    Parameters
    ----------
    name : {"local", "dask"}
        Worker processes of this machine, or a Dask cluster.
    jobs : int, optional
        Worker processes (local pool, or the workers of a local Dask
        cluster); None uses every core.
    in_process : bool
        Local only: run the cells in this process, for debuggers.
    scheduler : str, optional
        Dask only: the address of a running scheduler; without it a local
        cluster is started.

    Raises
    ------
    benchmark.errors.DataError
        For an option the executor does not take, a Dask that is not
        installed or a scheduler that cannot be reached.
    """
    from benchmark.errors import DataError

    if name == "local":
        if scheduler is not None:
            raise DataError("--scheduler needs --executor dask")
        from benchmark.executors.local import LocalExecutor

        return LocalExecutor(jobs, in_process=in_process)
    if name == "dask":
        if in_process:
            raise DataError("--in-process runs cells in this process; it does not go with --executor dask")
        from benchmark.executors.dask_cluster import DaskExecutor

        return DaskExecutor(scheduler, jobs)
    raise DataError(f"unknown executor {name!r} (known: {', '.join(EXECUTORS)})")
