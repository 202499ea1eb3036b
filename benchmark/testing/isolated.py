"""The conformance kit in a worker process, for ``trackbench check``.

In this process a tracker's exception, ``sys.exit`` and a hang in Python
code are each the failure of one check (:func:`benchmark.testing.run_check`).
What no process survives, ``os._exit``, a crash in native code or a hang
inside one native call, would end a ``trackbench check`` of many trackers.
So each check runs as a task of a warm worker (the pebble pool of
:func:`benchmark.executors.local.worker_pool`, one native thread): the
worker prepares a tracker's frames and model once and keeps them for the
tracker's next checks, and a worker that dies, or is stopped a grace
period after the check's time limit, costs only that check's row; pebble
starts another in its place, which prepares the tracker again.

Workers are forked with the registry the command already loaded, so they
see the same plugins, ``--disable`` included; where processes are not
forked they load the installed plugins themselves.
"""

from __future__ import annotations

import functools
from collections.abc import Iterator, Sequence
from typing import Any

from benchmark.executors.local import call_of_future, hard_limit_s, worker_pool
from benchmark.registry import Registry
from benchmark.testing import (
    DEFAULT_FRAMES,
    DEFAULT_TIME_LIMIT_S,
    RANDOM_FRAMES,
    Check,
    CheckResult,
    Subject,
    checks,
    expected,
    prepare_within,
    run_check,
    run_in_order,
    with_root_causes,
)
from benchmark.testing.time_limit import WAIT_FACTOR

_REGISTRY: Registry | None = None
"""The registry of the command that started the workers, which forked workers inherit."""


def check_in_workers(
    names: Sequence[str],
    registry: Registry,
    n_frames: int = DEFAULT_FRAMES,
    time_limit_s: float = DEFAULT_TIME_LIMIT_S,
    random_frames: int = RANDOM_FRAMES,
) -> Iterator[CheckResult]:
    """Every check of every tracker named, each in a worker process; the results as they come.

    Parameters
    ----------
    names : sequence of str
        Registered trackers, in the order to check them.
    registry : Registry
        Where they are registered.
    n_frames : int
        Frames each run of a check reads.
    time_limit_s : float
        Time one check may take (and the preparation of a tracker's frames and model).
    random_frames : int
        Frames of each random sequence the ``random_sequences`` check draws.

    Yields
    ------
    CheckResult
        One per tracker and check, a tracker's results together once its
        last check ended, root causes first (:func:`~benchmark.testing.with_root_causes`);
        a check whose worker died or had to be stopped fails with what
        became of the worker.
    """
    global _REGISTRY
    _REGISTRY = registry
    # A tracker's first check also prepares it, each under the limit and its wall-time bound (time_limit); the
    # worker gets a grace period on top, and is stopped only when native code holds it past both.
    limit = 2.0 * float(hard_limit_s(time_limit_s * WAIT_FACTOR))
    pool = worker_pool(1)
    try:
        for name in names:
            entry = registry.trackers[name]
            expected_failures = getattr(entry.tracker_class, "expected_failed_checks", {})

            def in_a_worker(check: Check) -> CheckResult:
                arguments = (name, check.name, n_frames, time_limit_s, random_frames)
                future = pool.schedule(_check_here, args=arguments, timeout=limit)
                return expected(_result(name, check.name, future, limit), expected_failures)

            yield from with_root_causes(run_in_order(entry, in_a_worker))
    finally:
        pool.stop()
        pool.join()
        _REGISTRY = None


WHY_THE_CHECK_FAILED = {
    "timeout": "its worker was still busy after {limit:g} s and was stopped: does it hang in native code?",
    "died": "{summary} during the check: os._exit, or a crash?",
    "retired": "{summary} during the check: os._exit, or a crash?",
    "error": "the worker could not return the result: {summary}",
}
"""A failed check's reason, by how its task ended, when the worker did not return the check's own result."""


def _result(name: str, check: str, future: Any, limit: float) -> CheckResult:
    """The check's own result, or a failure saying what became of its worker."""
    ended = call_of_future(future, "", limit)
    if ended.ok:
        return ended.value()
    reason = WHY_THE_CHECK_FAILED[ended.ending].format(limit=limit, summary=ended.summary)
    return CheckResult(name, check, "failed", f"tracker {name!r}: {reason}", hung=ended.ending == "timeout")


@functools.cache
def _registry() -> Registry:
    """The registry: the command's, inherited through fork, or the installed plugins'."""
    if _REGISTRY is not None:
        return _REGISTRY
    from benchmark.plugins import load_registry

    return load_registry()


@functools.lru_cache(maxsize=1)
def _subject(name: str, n_frames: int, time_limit_s: float, random_frames: int) -> Subject:
    """The prepared subject of tracker ``name``, kept for its next checks in this worker."""
    registry = _registry()
    return prepare_within(
        registry.trackers[name], registry, n_frames=n_frames, time_limit_s=time_limit_s, random_frames=random_frames
    )


def _check_here(name: str, check_name: str, n_frames: int, time_limit_s: float, random_frames: int) -> CheckResult:
    """In a worker: run check ``check_name`` on tracker ``name``."""
    (check,) = [check for check in checks() if check.name == check_name]
    return run_check(check, _subject(name, n_frames, time_limit_s, random_frames), time_limit_s)
