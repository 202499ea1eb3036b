"""The time limit of one check: a hang becomes a CheckTimeout, and the timer is gone afterwards."""

from __future__ import annotations

import signal
import threading
import time

import pytest

from benchmark.testing.time_limit import CheckTimeout, can_limit, time_limit

pytestmark = pytest.mark.skipif(not can_limit(), reason="needs POSIX interval timers in the main thread")


def test_a_busy_loop_is_interrupted() -> None:
    started = time.perf_counter()
    with pytest.raises(CheckTimeout, match="within 0.2 s"), time_limit(0.2):
        while True:
            pass
    assert time.perf_counter() - started < 5.0


def test_a_tracker_cannot_swallow_it() -> None:
    with pytest.raises(CheckTimeout), time_limit(0.1):
        try:
            time.sleep(5.0)
        except Exception:  # what a careless tracker writes
            pass


def test_a_quick_body_leaves_no_timer_and_the_old_handler() -> None:
    previous = signal.getsignal(signal.SIGALRM)
    with time_limit(5.0):
        pass
    assert signal.getitimer(signal.ITIMER_REAL) == (0.0, 0.0)
    assert signal.getsignal(signal.SIGALRM) is previous


def test_no_limit_outside_the_main_thread() -> None:
    seen: list[bool] = []

    def body() -> None:
        seen.append(can_limit())
        with time_limit(0.01):
            time.sleep(0.05)
        seen.append(True)

    worker = threading.Thread(target=body)
    worker.start()
    worker.join()
    assert seen == [False, True]
