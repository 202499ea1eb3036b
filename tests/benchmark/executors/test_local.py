"""How a task of the local pool ended, from its future, and the cell's row it becomes; how its workers are stopped."""

from __future__ import annotations

import concurrent.futures
import signal
import types

import pytest
from pebble import CONSTS, ProcessExpired

from benchmark.executors.local import LocalExecutor, WorkerDied, call_of_future, value_from_future, worker_pool
from benchmark.selection import Selection, select_cells
from benchmark.workers import RETIRED_STATUS


def finished(value: object = None, error: BaseException | None = None) -> concurrent.futures.Future:
    future: concurrent.futures.Future = concurrent.futures.Future()
    if error is None:
        future.set_result(value)
    else:
        future.set_exception(error)
    return future


@pytest.mark.parametrize(
    ("error", "ending", "summary"),
    [
        (None, "ok", ""),
        (TimeoutError("Task timeout"), "timeout", "no result within the 2.5 s limit; the worker was stopped"),
        (ProcessExpired("Abnormal termination", code=-signal.SIGSEGV), "died", "the worker process ended (killed by SIGSEGV)"),
        (ProcessExpired("Abnormal termination", code=7), "died", "the worker process ended (exit status 7)"),
        (ProcessExpired("Abnormal termination", code=RETIRED_STATUS), "retired", "the worker process ended (exit status 75)"),
        (ValueError("bad  frame"), "error", "ValueError: bad frame"),
    ],
    ids=["ok", "timeout", "segfault", "exit", "retired", "error"],
)
def test_a_future_s_ending_is_told_from_what_it_raised(error: BaseException | None, ending: str, summary: str) -> None:
    call = call_of_future(finished("value", error), "worker process", 2.5)
    assert (call.ending, call.summary) == (ending, summary)
    assert call.result == ("value" if error is None else None)


def test_value_from_future_raises_the_worker_s_fate_or_the_task_s_own_exception() -> None:
    assert value_from_future(finished(3), 1.0) == 3
    with pytest.raises(TimeoutError, match="no result within the 1 s limit; the worker was stopped"):
        value_from_future(finished(error=TimeoutError()), 1.0)
    with pytest.raises(WorkerDied, match=r"the worker process ended \(exit status 7\)"):
        value_from_future(finished(error=ProcessExpired("gone", code=7)), 1.0)
    with pytest.raises(KeyError, match="own"):
        value_from_future(finished(error=KeyError("own")), 1.0)


def test_a_worker_is_killed_at_once_rather_than_sent_the_sigterm_it_ignores_and_waited_for() -> None:
    pool = worker_pool(1)
    try:
        assert CONSTS.term_timeout == 0
    finally:
        pool.stop()
        pool.join()


def test_cells_found_finished_together_are_yielded_in_the_order_they_were_scheduled(
    fakes: types.ModuleType, monkeypatch: pytest.MonkeyPatch
) -> None:
    cells = select_cells(fakes.make_registry(), Selection(trackers=("perfect", "raising"), suites=("fake",)))
    wait = concurrent.futures.wait

    def all_at_once_latest_first(futures, timeout=None, return_when=None):  # type: ignore[no-untyped-def]
        done, not_done = wait(futures, timeout, concurrent.futures.ALL_COMPLETED)
        return [future for future in reversed(list(futures)) if future in done], not_done

    monkeypatch.setattr(concurrent.futures, "wait", all_at_once_latest_first)
    results = list(LocalExecutor(1).run(cells, 60.0))
    ran = [(result.tracker, result.dataset, result.seed) for result in results]
    assert ran == [(cell.tracker.name, cell.dataset, cell.seed) for cell in cells]
