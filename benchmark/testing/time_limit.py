"""A time limit on one check, so that a tracker that hangs fails its check instead of the test run.

The limit is a POSIX interval timer whose signal raises :class:`CheckTimeout`
in the main thread, wherever the tracker is: in Python code, in a sleep, in
a wait on a lock or a socket.  Code that holds the interpreter inside one
native call (a numba loop, a long OpenCV call) is interrupted when that call
returns.  Where there is no such timer (Windows, or a check run from another
thread) the limit does not apply.

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


class CheckTimeout(BaseException):
    """A check ran past its time limit."""


def can_limit() -> bool:
    """Whether :func:`time_limit` can interrupt the calling thread."""
    return hasattr(signal, "setitimer") and threading.current_thread() is threading.main_thread()


@contextmanager
def time_limit(seconds: float | None) -> Iterator[None]:
    """Raise :class:`CheckTimeout` in the body if it runs longer than ``seconds``.

    Parameters
    ----------
    seconds : float or None
        The limit, s; None (or a thread without timer) sets none.

    Raises
    ------
    CheckTimeout
        From wherever the body was when the time ran out.
    """
    if seconds is None or not can_limit():
        yield
        return

    def expire(signum: int, frame: FrameType | None) -> None:
        raise CheckTimeout(f"did not finish within {seconds:g} s")

    previous = signal.signal(signal.SIGALRM, expire)
    signal.setitimer(signal.ITIMER_REAL, seconds)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0.0)
        signal.signal(signal.SIGALRM, previous)
