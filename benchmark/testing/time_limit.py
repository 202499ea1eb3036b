"""A time limit on one check, so that a tracker that hangs fails its check instead of the test run.

The limit is on the process's CPU time, so that a check on a machine busy
with other work is not failed for waiting its turn: a tracker that spins
uses its CPU time up as surely on a loaded machine as on a quiet one.  A
tracker that hangs without using the processor (a sleep, a wait on a lock
or a socket) is stopped after :data:`WAIT_FACTOR` times the limit in wall
time instead.  Both are POSIX interval timers (``ITIMER_PROF`` and
``ITIMER_REAL``) whose signals raise :class:`CheckTimeout` in the main
thread, wherever the tracker is.  Code that holds the interpreter inside
one native call (a numba loop, a long OpenCV call) is interrupted when that
call returns.  Where there are no such timers (Windows, or a check run
from another thread) the limit does not apply.

:class:`CheckTimeout` derives from :class:`BaseException`, as
:class:`KeyboardInterrupt` does, so that a tracker's own ``except
Exception`` cannot swallow it.
"""

from __future__ import annotations

import signal
import threading
from collections.abc import Iterator
from contextlib import contextmanager
from types import FrameType


WAIT_FACTOR = 10.0
"""Wall time a check may take, as a multiple of its CPU-time limit."""


class CheckTimeout(BaseException):
    """A check ran past its time limit."""


def can_limit() -> bool:
    """Whether :func:`time_limit` can interrupt the calling thread."""
    return hasattr(signal, "setitimer") and threading.current_thread() is threading.main_thread()


@contextmanager
def time_limit(seconds: float | None) -> Iterator[None]:
    """Raise :class:`CheckTimeout` in the body once it has used ``seconds`` of CPU time, or waited ``WAIT_FACTOR`` times as long.

    Parameters
    ----------
    seconds : float or None
        The limit, s of CPU time of this process; None (or a thread without
        timers) sets none.

    Raises
    ------
    CheckTimeout
        From wherever the body was when the time ran out.
    """
    if seconds is None or not can_limit():
        yield
        return
    waited = seconds * WAIT_FACTOR

    def spent(signum: int, frame: FrameType | None) -> None:
        raise CheckTimeout(f"did not finish within {seconds:g} s of CPU time")

    def waiting(signum: int, frame: FrameType | None) -> None:
        raise CheckTimeout(f"did not finish within {waited:g} s of waiting ({seconds:g} s of CPU time allowed)")

    previous = {signal.SIGPROF: signal.signal(signal.SIGPROF, spent), signal.SIGALRM: signal.signal(signal.SIGALRM, waiting)}
    signal.setitimer(signal.ITIMER_PROF, seconds)
    signal.setitimer(signal.ITIMER_REAL, waited)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_PROF, 0.0)
        signal.setitimer(signal.ITIMER_REAL, 0.0)
        for signum, handler in previous.items():
            signal.signal(signum, handler)
