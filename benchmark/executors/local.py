"""Cells in warm worker processes of this machine (pebble), or in this process.

:class:`LocalExecutor` runs each batch of cells in a pebble process pool of
``jobs`` workers, each prepared by :func:`benchmark.workers.init_worker`
(one native thread, Ctrl-C left to the parent, killed with it).  A worker
runs cell after cell, so the plugins it imported, the numba kernels it
compiled and the models it read serve all its cells.  A worker still busy a
grace period after a cell's time limit is killed, and one that exits or
crashes (``os._exit``, a segmentation fault) costs only its cell: pebble
starts another in its place.  A worker that an earlier cell left in a
session of its own refuses its next cell before running any of it
(:data:`benchmark.workers.RETIRED_STATUS`), and that cell is scheduled
again on another.

:func:`call_of_future` says how a task of the pool ended (a
:class:`benchmark.faults.Call`), and :func:`cell_from_call` turns that into
the cell's result; the Dask executor runs its cells through the same
functions (:func:`cell_in_pool`), so that a cell fails the same way wherever it ran.
"""

from __future__ import annotations

import concurrent.futures
import contextlib
import dataclasses
import os
import sys
from collections.abc import Callable, Iterator, Sequence
from typing import Any

from benchmark.errors import DataError
from benchmark.executors import ExecutorOptions
from benchmark.faults import Call
from benchmark.results import CellResult
from benchmark.runner import Cell, cell_result, run_cell


def grace_s(timeout_s: float) -> float:
    """Extra time a worker gets before it is killed, so ``run_cell`` can stop on its own first."""
    return max(1.0, 0.05 * timeout_s)


def hard_limit_s(timeout_s: float | None) -> float | None:
    """When a worker still running a cell is killed: the cell's limit and a grace period."""
    return None if timeout_s is None else timeout_s + grace_s(timeout_s)


CELL_PHASE = "worker process"
"""The phase of a cell's fault that its worker's future raised (the cell's own faults name theirs)."""

LOST = {
    "timeout": " and the frames are lost",
    "died": " while running the cell; its frames are lost",
    "retired": " while running the cell; its frames are lost",
}
"""What a cell's message adds to a worker's timeout or death: its frames went with the worker."""


def call_of_future(future: concurrent.futures.Future, phase: str, limit_s: float | None) -> Call[Any]:
    """How the task of a finished pebble future ended, as a :class:`~benchmark.faults.Call`.

    ``ok`` with its value; ``timeout`` if the worker was stopped at
    ``limit_s``; ``retired`` if the worker refused the task untouched
    (:data:`benchmark.workers.RETIRED_STATUS`); ``died`` if the worker
    process ended otherwise; ``error`` with whatever else the future raised
    (the task's own exception, or one returning its value).
    """
    from pebble import ProcessExpired

    from benchmark.workers import RETIRED_STATUS

    fetched = Call.of(future.result, phase, reraise=(KeyboardInterrupt,))  # the user's, here
    if fetched.ok:
        return fetched
    error = future.exception()
    if isinstance(error, TimeoutError):
        return Call.timed_out("", f"no result within the {limit_s or 0.0:g} s limit; the worker was stopped")
    if isinstance(error, ProcessExpired):
        ending = "retired" if error.exitcode == RETIRED_STATUS else "died"
        return dataclasses.replace(fetched, ending=ending, exit_code=error.exitcode)
    return fetched


def cell_in_pool(pool: Any, cell: Cell, timeout_s: float | None) -> CellResult:
    """Run ``cell`` in a worker of ``pebble`` pool ``pool`` and wait for its result, or its timeout or error row."""
    while True:
        future = pool.schedule(run_cell, args=(cell, timeout_s), timeout=hard_limit_s(timeout_s))
        concurrent.futures.wait([future])
        ended = call_of_future(future, CELL_PHASE, timeout_s)
        if ended.ending != "retired":
            return cell_from_call(cell, ended, timeout_s)


def cell_from_call(cell: Cell, call: Call[CellResult], timeout_s: float | None) -> CellResult:
    """The result of ``cell`` from how its task ended: its own result, or a timeout or error row.

    A worker's timeout or death loses the cell's frames, and its message
    says so; any other fault is ``ExceptionType: message (phase)``, with its traceback as the detail.
    """
    if call.ok:
        return call.value()
    message = call.summary + LOST[call.ending] if call.ending in LOST else call.message
    elapsed_s = float(timeout_s or 0.0) if call.ending == "timeout" else 0.0
    return cell_result(cell, call.status, message, elapsed_s=elapsed_s, detail=call.detail)


class WorkerDied(RuntimeError):
    """The worker process ended while it ran a task (``os._exit``, a crash in native code)."""


def value_from_future(future: concurrent.futures.Future, timeout_s: float | None) -> Any:
    """The value of a pebble future of :meth:`LocalExecutor.call`, with the worker's fate as the exception.

    Raises
    ------
    TimeoutError
        If the worker was stopped at the limit.
    WorkerDied
        If the worker process ended, saying how.
    Exception
        Whatever the task raised, as it raised it.
    """
    call = call_of_future(future, "", timeout_s)
    if call.ending == "timeout":
        raise TimeoutError(call.summary)
    if call.ending in ("died", "retired"):
        raise WorkerDied(call.summary)
    return future.result()


def worker_pool(workers: int) -> Any:
    """A pebble process pool whose workers are prepared by :func:`benchmark.workers.init_worker`.

    This process is limited to one native thread first, so that the workers
    forked from it inherit pools of one (:func:`benchmark.workers.limit_native_threads`).
    A worker is stopped (past a cell's limit, or with the run) by ``SIGKILL``
    at once: it ignores the ``SIGTERM`` pebble sends first, which is the
    parent's to act on, so pebble's wait for that signal to work
    (``CONSTS.term_timeout``, 3 s) would only delay each stop.
    """
    from pebble import CONSTS, ProcessPool

    from benchmark.workers import init_worker, limit_native_threads

    CONSTS.term_timeout = 0.0
    limit_native_threads()
    return ProcessPool(max_workers=workers, initializer=init_worker, initargs=(os.getpid(),))


class LocalExecutor:
    """Cells in a pool of warm worker processes on this machine, or in this process.

    Parameters
    ----------
    jobs : int, optional
        Worker processes; None uses every core (``os.cpu_count()``), and 0
        or 1 run one cell at a time in one worker.
    in_process : bool
        Run the cells one after another in this process, for debuggers and
        profilers: the limit is then checked between frames only, and a
        tracker that ends the process ends the run.
    """

    runs_here = True

    def __init__(self, jobs: int | None = None, *, in_process: bool = False) -> None:
        if jobs is None:
            jobs = os.cpu_count() or 1
        if jobs < 0:
            raise ValueError(f"jobs must be >= 0, not {jobs}")
        self.jobs = max(jobs, 1)
        self.in_process = in_process
        self._futures: dict[concurrent.futures.Future, Cell] = {}
        self._current: Cell | None = None

    @classmethod
    def open(cls, options: ExecutorOptions) -> LocalExecutor:
        """A pool of ``options.jobs`` workers, or this process with ``options.in_process``.

        Raises
        ------
        benchmark.errors.DataError
            For a scheduler, which a local pool has not.
        """
        if options.scheduler is not None:
            raise DataError("--scheduler needs --executor dask")
        return cls(options.jobs, in_process=options.in_process)

    def run(self, cells: Sequence[Cell], timeout_s: float | None) -> Iterator[CellResult]:
        """Yield the result of each cell, in order of completion (input order in process).

        Cells found finished together are yielded in the order they were scheduled,
        so one worker yields them in input order.
        """
        if self.in_process:
            from benchmark.workers import limit_native_threads

            limit_native_threads()
            for cell in cells:
                self._current = cell
                with contextlib.redirect_stdout(sys.stderr):  # the board goes to stdout; a tracker's print does not
                    result = run_cell(cell, timeout_s)
                yield result
            self._current = None
            return
        if not cells:
            return
        pool = worker_pool(min(self.jobs, len(cells)))
        limit = hard_limit_s(timeout_s)

        def schedule(cell: Cell) -> None:
            self._futures[pool.schedule(run_cell, args=(cell, timeout_s), timeout=limit)] = cell

        try:
            for cell in cells:
                schedule(cell)
            while self._futures:
                done, _ = concurrent.futures.wait(self._futures, return_when=concurrent.futures.FIRST_COMPLETED)
                for future in [future for future in self._futures if future in done]:  # scheduled order
                    cell = self._futures.pop(future)
                    ended = call_of_future(future, CELL_PHASE, timeout_s)
                    if ended.ending == "retired":
                        schedule(cell)
                    else:
                        yield cell_from_call(cell, ended, timeout_s)
        finally:
            self._futures = {}
            pool.stop()
            pool.join()

    def call(self, function: Callable[..., Any], args: tuple[Any, ...], timeout_s: float | None) -> Any:
        """``function(*args)`` in a fresh worker process under a time limit (here, in process)."""
        if self.in_process:
            return function(*args)
        pool = worker_pool(1)
        try:
            return value_from_future(pool.schedule(function, args=args, timeout=timeout_s), timeout_s)
        finally:
            pool.stop()
            pool.join()

    def running(self) -> list[str]:
        """Labels of the cells a worker is running now."""
        if self._current is not None:
            return [self._current.label()]
        return [cell.label() for future, cell in list(self._futures.items()) if future.running()]

    def close(self) -> None:
        """Nothing to stop: each :meth:`run` stops its pool when it ends."""

    def __enter__(self) -> LocalExecutor:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()
