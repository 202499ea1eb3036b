"""A Dask worker's process pool: one that broke is replaced, and the task it refused goes to the new one."""

from __future__ import annotations

import types
from typing import Any

import pytest

from benchmark.executors import dask_cluster

distributed = pytest.importorskip("distributed", reason="the Dask executor needs dask.distributed")


class Pool:
    """A pebble pool's ``active``, ``schedule`` and ``stop``; a broken one refuses every task as pebble does."""

    def __init__(self, broken: bool = False) -> None:
        self.broken, self.stopped, self.scheduled = broken, False, []

    @property
    def active(self) -> bool:
        return not self.broken and not self.stopped

    def schedule(self, function: Any, args: tuple[Any, ...] = (), timeout: float | None = None) -> str:
        if self.broken:
            raise RuntimeError("Unexpected error within the Pool")
        self.scheduled.append(function)
        return "future"

    def stop(self) -> None:
        self.stopped = True


@pytest.fixture
def pools(monkeypatch: pytest.MonkeyPatch) -> list[Pool]:
    """The pools the worker starts, in order; the worker's own pool starts broken."""
    started: list[Pool] = [Pool(broken=True)]
    monkeypatch.setattr(dask_cluster, "_pool", started[0])
    worker = types.SimpleNamespace(state=types.SimpleNamespace(nthreads=1))
    monkeypatch.setattr(distributed, "get_worker", lambda: worker)

    def start(processes: int) -> Pool:
        started.append(Pool())
        return started[-1]

    monkeypatch.setattr(dask_cluster, "worker_pool", start)
    return started


def test_a_task_a_broken_pool_refused_runs_in_a_new_pool(pools: list[Pool]) -> None:
    future = dask_cluster._in_worker_pool(lambda pool: pool.schedule(print))
    assert future == "future"
    broken, fresh = pools
    assert broken.stopped and fresh.scheduled == [print]
    assert dask_cluster._worker_pool() is fresh


def test_a_task_s_own_runtime_error_is_not_taken_for_a_broken_pool(pools: list[Pool]) -> None:
    dask_cluster._worker_pool()  # replaces the broken pool

    def failing(pool: Pool) -> None:
        raise RuntimeError("the task's own")

    with pytest.raises(RuntimeError, match="the task's own"):
        dask_cluster._in_worker_pool(failing)
    assert len(pools) == 2
