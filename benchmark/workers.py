"""Worker processes that belong to the run that started them.

Cells run in worker processes (:func:`benchmark.runner.run_cells`).  Each
worker is prepared by :func:`init_worker` before its first cell:

* it ignores ``SIGINT``: a Ctrl-C in the terminal reaches every process of
  the group, and it is the main process's to act on (stop the run, keep the
  finished cells); a worker that took it would turn the cell it was running
  into an error row;
* it dies with its parent: if the main process is killed (``kill -9``), the
  kernel kills the worker too (``PR_SET_PDEATHSIG`` on Linux), or, where
  that is not available, a watch thread ends it within
  :data:`PARENT_POLL_S`, so that no orphan runs on to the end of its cell.
"""

from __future__ import annotations

import ctypes
import ctypes.util
import os
import signal
import sys
import threading
import time

PARENT_POLL_S = 0.5
"""How often a worker without ``PR_SET_PDEATHSIG`` checks that its parent lives."""

_PR_SET_PDEATHSIG = 1


def _kill_on_parent_death() -> bool:
    """Ask Linux to send SIGKILL to this process when its parent ends; False where unavailable."""
    if not sys.platform.startswith("linux"):
        return False
    try:
        libc = ctypes.CDLL(ctypes.util.find_library("c") or "libc.so.6", use_errno=True)
        return libc.prctl(_PR_SET_PDEATHSIG, signal.SIGKILL, 0, 0, 0) == 0
    except (OSError, AttributeError):
        return False


def _watch_parent(parent_pid: int) -> None:
    while os.getppid() == parent_pid:
        time.sleep(PARENT_POLL_S)
    os._exit(1)


def init_worker(parent_pid: int) -> None:
    """Prepare a worker process: leave Ctrl-C to the parent, and die with it.

    Parameters
    ----------
    parent_pid : int
        The pid of the main process, taken there before the worker started.
    """
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    if not _kill_on_parent_death():
        threading.Thread(target=_watch_parent, args=(parent_pid,), name="watch-parent", daemon=True).start()
    if os.getppid() != parent_pid:  # the parent ended before the request above took effect
        os._exit(1)
