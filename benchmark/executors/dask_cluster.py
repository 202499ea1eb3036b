"""Cells as tasks of a Dask cluster (``dask.distributed``).

:class:`DaskExecutor` connects to the scheduler at ``--scheduler ADDRESS``,
or starts a ``LocalCluster`` of ``--jobs`` single-threaded worker processes
so that the same path runs on one machine.  Each cell is one task; results
stream back to this process as they finish, and only this process writes
the results database, so no database ever sits on a shared file system.

A Dask worker does not run a tracker itself: it hands each cell to a pool
of warm processes of its own (:func:`benchmark.executors.local.worker_pool`,
one per worker thread), exactly as the local executor does.  So a cell that
raises, exits, crashes or hangs becomes an ``error`` or ``timeout`` row in
the same words wherever it ran, the process that ran it is replaced, and the
Dask worker, its connection to the scheduler and the run carry on.  Should a
Dask worker itself die, the cells it held are retried elsewhere by the
scheduler, and after its allowed failures become error rows.

Frames: a cell's sequence reads through the frame cache it was given
(:class:`benchmark.frame_cache.FrameCache`).  Its default folder is
resolved on the worker, so each machine renders what it lacks into its own
cache; a ``--cache`` folder that every machine mounts is shared instead.
Fitted models travel with the cells: a worker that cannot see the results
folder gets the model's bytes and stores them in a temporary folder of its
own (made by :func:`tempfile.mkdtemp`, so only its user may write there),
named by their hash; the model is a record of :mod:`benchmark.storage` and
is checked again when a cell reads it.
"""

from __future__ import annotations

import atexit
import dataclasses
import functools
import hashlib
import logging
import os
import shutil
import tempfile
import threading
import uuid
from collections.abc import Callable, Iterator, Sequence
from pathlib import Path
from typing import Any

from benchmark.errors import DataError
from benchmark.executors import ExecutorOptions
from benchmark.executors.local import cell_from_call, cell_in_pool, value_from_future, worker_pool
from benchmark.faults import Call
from benchmark.results import CellResult
from benchmark.runner import Cell

CONNECT_TIMEOUT_S = 20.0
"""How long to wait for a scheduler before giving up."""

_pool: Any = None
_pool_lock = threading.Lock()


def _worker_pool() -> Any:
    """This Dask worker's pool of warm cell processes, one per worker thread, started on first use.

    A worker under a nanny runs as a daemon process, which multiprocessing
    forbids to have children, since they would outlive it.  The pool's
    processes cannot: each dies with its parent (:func:`benchmark.workers.init_worker`),
    so the flag is lifted here for workers started without
    ``distributed.worker.daemon: false``.
    """
    global _pool
    with _pool_lock:
        if _pool is not None and not _pool.active:
            _pool.stop()  # broken, e.g. a replacement for a crashed process failed to start: start afresh
            _pool = None
        if _pool is None:
            import multiprocessing

            from distributed import get_worker

            multiprocessing.current_process()._config["daemon"] = False  # type: ignore[attr-defined]
            _pool = worker_pool(get_worker().state.nthreads)
            atexit.register(_pool.stop)
        return _pool


def _in_worker_pool(work: Callable[[Any], Any]) -> Any:
    """``work(pool)``, which schedules on the pool, in this worker's pool; again in a fresh pool if that one broke.

    A pebble pool that fails to replace a process (a crashed cell's) goes
    into an error state, and every later ``schedule`` raises
    ``RuntimeError``: the task it was given never ran, so it is given to a
    new pool rather than charged with the pool's fault.
    """
    pool = _worker_pool()
    try:
        return work(pool)
    except RuntimeError:
        if pool.active:
            raise
        return work(_worker_pool())


@functools.cache
def _models_folder() -> Path:
    """This worker's own folder for fitted models, removed when it exits."""
    folder = Path(tempfile.mkdtemp(prefix="trackbench-models-"))
    atexit.register(shutil.rmtree, folder, ignore_errors=True)
    return folder


def _adopt_model(cell: Cell, model: bytes | None) -> Cell:
    """``cell`` reading its fitted model from a file of this machine, written from ``model`` when missing."""
    training = cell.training
    if model is None or training is None or training.model_path is None or training.model_path.is_file():
        return cell
    path = _models_folder() / f"{hashlib.sha256(model).hexdigest()[:24]}{training.model_path.suffix}"
    if not path.is_file():
        from benchmark.files import write_bytes_atomically

        write_bytes_atomically(path, model, "fitted model")
    return dataclasses.replace(cell, training=dataclasses.replace(training, model_path=path))


def run_cell_on_worker(cell: Cell, timeout_s: float | None, model: bytes | None = None) -> CellResult:
    """The Dask task of a cell: run it in this worker's warm process pool, under its time limit."""
    adopted = Call.of(lambda: _adopt_model(cell, model), "storing the fitted model on the worker")
    if not adopted.ok:
        return cell_from_call(cell, adopted, timeout_s)
    return _in_worker_pool(lambda pool: cell_in_pool(pool, adopted.value(), timeout_s))


def call_on_worker(function: Callable[..., Any], args: tuple[Any, ...], timeout_s: float | None) -> Any:
    """The Dask task of :meth:`DaskExecutor.call`: ``function(*args)`` in this worker's process pool."""
    future = _in_worker_pool(lambda pool: pool.schedule(function, args=args, timeout=timeout_s))
    return value_from_future(future, timeout_s)


class DaskExecutor:
    """Cells as tasks of a Dask cluster; results come back here as they finish.

    Parameters
    ----------
    scheduler : str, optional
        Address of a running scheduler (``tcp://host:8786``).  Without it, a
        local cluster of ``jobs`` worker processes with one thread each is
        started, and stopped by :meth:`close`.
    jobs : int, optional
        Workers of the local cluster; None uses every core.

    Raises
    ------
    DataError
        If Dask is not installed or the scheduler cannot be reached.
    """

    runs_here = False

    def __init__(self, scheduler: str | None = None, jobs: int | None = None) -> None:
        try:
            from distributed import Client, LocalCluster
        except ImportError:
            raise DataError(
                "--executor dask needs dask.distributed: pip install 'subsea-trackbench[dask]'"
            ) from None
        self._cluster = None
        self._futures: dict[Any, Cell] = {}
        if scheduler is None:
            import dask

            workers = max(jobs or os.cpu_count() or 1, 1)
            with dask.config.set({"distributed.worker.daemon": False}):
                self._cluster = LocalCluster(
                    n_workers=workers,
                    threads_per_worker=1,
                    processes=True,
                    dashboard_address=None,
                    silence_logs=logging.ERROR,
                )
            self._client = Client(self._cluster)
        else:
            try:
                self._client = Client(scheduler, timeout=CONNECT_TIMEOUT_S)
            except (OSError, TimeoutError, ValueError) as exc:
                raise DataError(f"--scheduler {scheduler}: cannot reach the Dask scheduler: {exc}") from None

    @classmethod
    def open(cls, options: ExecutorOptions) -> DaskExecutor:
        """A client of the scheduler at ``options.scheduler``, or of a local cluster of ``options.jobs`` workers.

        Raises
        ------
        benchmark.errors.DataError
            For ``in_process``, which a cluster cannot do, and as the constructor does.
        """
        if options.in_process:
            raise DataError("--in-process runs cells in this process; it does not go with --executor dask")
        return cls(options.scheduler, options.jobs)

    @property
    def address(self) -> str:
        """The scheduler's address."""
        return self._client.scheduler.address

    def _models(self, cells: Sequence[Cell]) -> dict[Path, Any]:
        """Each fitted model the cells read, scattered to the cluster once as bytes."""
        paths = {cell.training.model_path for cell in cells if cell.training is not None}
        paths.discard(None)
        return {path: self._client.scatter(path.read_bytes(), broadcast=False) for path in paths if path.is_file()}

    def run(self, cells: Sequence[Cell], timeout_s: float | None) -> Iterator[CellResult]:
        """Submit every cell as a task and yield each result as it comes back."""
        from distributed import as_completed

        if not cells:
            return
        models = self._models(cells)
        tag = uuid.uuid4().hex[:8]
        try:
            for index, cell in enumerate(cells):
                path = None if cell.training is None else cell.training.model_path
                future = self._client.submit(
                    run_cell_on_worker,
                    cell,
                    timeout_s,
                    models.get(path) if path is not None else None,
                    key=f"trackbench-cell-{tag}-{index}",
                    pure=False,
                )
                self._futures[future] = cell
            for future in as_completed(list(self._futures)):
                cell = self._futures.pop(future)
                ended = Call.of(future.result, "Dask worker", reraise=(KeyboardInterrupt,))  # the user's, here
                yield cell_from_call(cell, ended, timeout_s)
        finally:
            if self._futures:
                self._client.cancel(list(self._futures))
            self._futures = {}

    def call(self, function: Callable[..., Any], args: tuple[Any, ...], timeout_s: float | None) -> Any:
        """``function(*args)`` as a task, in a process of a worker's pool, under a time limit."""
        return self._client.submit(call_on_worker, function, args, timeout_s, pure=False).result()

    def running(self) -> list[str]:
        """Labels of the cells the workers are processing now; none while the scheduler does not answer."""
        asked = Call.of(self._client.processing, "asking the scheduler", reraise=(KeyboardInterrupt,))
        processing = {key for keys in (asked.value() if asked.ok else {}).values() for key in keys}
        return [cell.label() for future, cell in list(self._futures.items()) if future.key in processing]

    def close(self) -> None:
        """Disconnect, and stop the local cluster if this executor started one."""
        self._client.close()
        if self._cluster is not None:
            self._cluster.close()

    def __enter__(self) -> DaskExecutor:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()
