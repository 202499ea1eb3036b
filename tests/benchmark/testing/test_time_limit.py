"""The time limit of one check: a hang becomes a CheckTimeout, and the timer is gone afterwards."""

from __future__ import annotations

import signal
import threading
import time

import pytest

from benchmark.testing.time_limit import CheckTimeout, can_limit, time_limit

pytestmark = pytest.mark.skipif(not can_limit(), reason="needs POSIX interval timers in the main thread")


def test_a_busy_loop_is_interrupted_when_it_has_used_its_cpu_time() -> None:
    started = time.process_time()
    with pytest.raises(CheckTimeout, match="within 0.2 s of CPU time"), time_limit(0.2):
        while True:
            pass
    # Not at once, but after CPU time was used.  The interval timer is charged by the kernel's sampling ticks, which
    # on a loaded machine can fall short of the precise process time by tens of milliseconds: half the limit is sure.
    assert time.process_time() - started >= 0.1


def test_waiting_for_the_processor_or_a_while_is_not_held_against_a_check() -> None:
    with time_limit(0.2):  # a machine busy with other work makes a check wait; it is not its CPU time
        time.sleep(0.5)


def test_a_hang_that_waits_is_stopped_after_ten_times_the_limit() -> None:
    with pytest.raises(CheckTimeout, match="within 1 s of waiting \\(0.1 s of CPU time allowed\\)"), time_limit(0.1):
        threading.Event().wait()


def test_a_tracker_cannot_swallow_it() -> None:
    with pytest.raises(CheckTimeout), time_limit(0.1):
        try:
            time.sleep(5.0)
        except Exception:  # what a careless tracker writes
            pass


def test_a_quick_body_leaves_no_timer_and_the_old_handlers() -> None:
    previous = signal.getsignal(signal.SIGALRM), signal.getsignal(signal.SIGPROF)
    with time_limit(5.0):
        pass
    assert signal.getitimer(signal.ITIMER_REAL) == signal.getitimer(signal.ITIMER_PROF) == (0.0, 0.0)
    assert (signal.getsignal(signal.SIGALRM), signal.getsignal(signal.SIGPROF)) == previous


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
