"""Worker processes that belong to the run that started them.

Cells run in worker processes (:func:`benchmark.executors.run_cells`).  Each
worker is prepared by :func:`init_worker` before its first cell:

* it ignores ``SIGINT`` and ``SIGTERM``: a Ctrl-C in the terminal, or a
  job scheduler's ``SIGTERM`` to the process group, reaches every process of
  the group, and it is the main process's to act on (stop the run, keep the
  finished cells); a worker that took it would turn the cell it was running
  into an error row;
* it dies with its parent: if the main process is killed (``kill -9``), the
  kernel kills the worker too (``PR_SET_PDEATHSIG`` on Linux), or, where
  that is not available, a watch thread ends it within
  :data:`PARENT_POLL_S`, so that no orphan runs on to the end of its cell;
* it runs one native thread (:func:`limit_native_threads`): OpenBLAS,
  OpenMP, OpenCV and numba otherwise start a thread per core in every
  worker, and on two cores two workers then fight over them: ``--jobs 2``
  was slower than ``--jobs 1``, and the board's frames per second measured
  the fight rather than the tracker;
* its standard output is its standard error (:func:`quiet_stdout`): the
  command's standard output carries the board, and a tracker's ``print``
  (or a native library's write to file descriptor 1) must not land in it;
* it adopts the processes its cells leave behind (on Linux,
  ``PR_SET_CHILD_SUBREAPER``: a daemon a tracker starts, forking twice,
  becomes the worker's child rather than the system's).

A worker stays alive from cell to cell, so what it imports and loads once
(plugins, compiled numba kernels, fitted models) serves all its cells.
What a cell changes in its process is undone before the next one
(:func:`cell_isolation`): its working folder, its environment, the names of
the modules every tracker shares (:mod:`benchmark.shared_modules`) and, in
a worker, every process it started, which is killed, and the worker's
process group: a cell that moved the worker to another group of its session
is moved back; one that started a new session (``os.setsid``), which no
process can leave, retires the worker: it takes no further cell and exits
with :data:`RETIRED_STATUS` when handed one, and the executor gives that
cell to another worker (:func:`benchmark.executors.local.call_of_future` says ``retired``).
"""

from __future__ import annotations

import ctypes
import ctypes.util
import os
import signal
import sys
import threading
import time
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

from benchmark.shared_modules import Snapshot

PARENT_POLL_S = 0.5
"""How often a worker without ``PR_SET_PDEATHSIG`` checks that its parent lives."""

_PR_SET_PDEATHSIG = 1
_PR_SET_CHILD_SUBREAPER = 36
CHILDREN_GRACE_S = 5.0
"""How long a worker waits for the processes it killed after a cell to be gone."""
RETIRED_STATUS = 75
"""Exit status of a worker that refuses a cell because an earlier one left it in a session of its own."""
_in_worker = False
_process_group: tuple[int, int] | None = None
"""The worker's session and process group when it started (POSIX)."""
_retired = False
_shared = Snapshot.take()  # before any plugin: this module is read before a cell's tracker is (see shared_modules)

THREAD_VARIABLES = (
    "OMP_NUM_THREADS",
    "OPENBLAS_NUM_THREADS",
    "MKL_NUM_THREADS",
    "BLIS_NUM_THREADS",
    "VECLIB_MAXIMUM_THREADS",
    "NUMEXPR_NUM_THREADS",
)
"""Variables that native libraries loaded later in the process read for their thread count.

Not ``NUMBA_NUM_THREADS``: numba reads it again when it compiles, and
refuses a value other than that of its running threads.
"""


def limit_native_threads() -> None:
    """Give every native thread pool of this process one thread, now and for libraries loaded later.

    Pools already loaded (numpy's and OpenCV's OpenBLAS, an OpenMP runtime)
    are limited through threadpoolctl, OpenCV's own pool and numba's
    through their calls; the environment variables of
    :data:`THREAD_VARIABLES` cover libraries a tracker loads afterwards
    (scikit-learn's OpenMP runtime, say).

    The process that starts workers calls it too, before it forks them
    (:func:`benchmark.executors.local.worker_pool`): OpenCV cannot resize a
    pool it inherited through ``fork`` (the call never returns), so the
    workers inherit a pool of one instead, and a pool already of one is
    left alone here.
    """
    for name in THREAD_VARIABLES:
        os.environ[name] = "1"
    # numba is imported, not looked up in sys.modules: a plugin that imported it later would start it with
    # a thread per core, and a Dask worker may be half way through importing it on another thread.
    import cv2
    import numba
    import threadpoolctl

    if numba.get_num_threads() != 1:  # first: it may load an OpenMP runtime
        numba.set_num_threads(1)
    threadpoolctl.threadpool_limits(1)
    if cv2.getNumThreads() != 1:
        cv2.setNumThreads(1)


def native_threads() -> dict[str, int]:
    """The thread count of every native pool of this process (library file or ``opencv``/``numba``)."""
    import cv2
    import threadpoolctl

    counts = {Path(pool["filepath"]).name: pool["num_threads"] for pool in threadpoolctl.threadpool_info()}
    counts["opencv"] = cv2.getNumThreads()
    if "numba" in sys.modules:
        counts["numba"] = sys.modules["numba"].get_num_threads()
    return counts


def _prctl(option: int, value: int) -> bool:
    """Linux's ``prctl(option, value)``; False where unavailable or refused."""
    if not sys.platform.startswith("linux"):
        return False
    try:
        libc = ctypes.CDLL(ctypes.util.find_library("c") or "libc.so.6", use_errno=True)
        return libc.prctl(option, value, 0, 0, 0) == 0
    except (OSError, AttributeError):
        return False


def _kill_on_parent_death() -> bool:
    """Ask Linux to send SIGKILL to this process when its parent ends; False where unavailable."""
    return _prctl(_PR_SET_PDEATHSIG, signal.SIGKILL)


def adopt_orphans() -> bool:
    """Make this process the parent of every orphan among its descendants (Linux); False where unavailable."""
    return _prctl(_PR_SET_CHILD_SUBREAPER, 1)


def end_children() -> int:
    """Kill every process this one started, and theirs, and wait for them; how many there were."""
    import psutil

    try:
        children = psutil.Process().children(recursive=True)
    except psutil.Error:
        return 0
    for child in children:
        try:
            child.kill()
        except psutil.Error:
            pass
    psutil.wait_procs(children, timeout=CHILDREN_GRACE_S)
    return len(children)


@contextmanager
def cell_isolation() -> Iterator[None]:
    """Undo, when the block ends, what it changed in the process: working folder, environment, and, in a worker, children.

    A tracker that changes folder or sets a variable would otherwise change
    every later cell of the worker (a relative cache folder, a library
    reading the environment), and a process it starts would outlive the run.
    """
    if _retired:
        os._exit(RETIRED_STATUS)  # nothing of the cell has run: the executor hands it to another worker
    shared = _shared.in_folder_now()
    environment = dict(os.environ)
    shared.restore()
    try:
        yield
    finally:
        shared.restore()
        if dict(os.environ) != environment:
            os.environ.clear()
            os.environ.update(environment)
        if _in_worker:
            end_children()
            _keep_process_group()


def _keep_process_group() -> None:
    """Move this worker back to its process group if a cell moved it; retire it if the cell left its session."""
    global _retired
    if _process_group is None:
        return
    session, group = _process_group
    if os.getsid(0) != session:
        _retired = True
    elif os.getpgrp() != group:
        try:
            os.setpgid(0, group)
        except OSError:  # the group is gone
            _retired = True


def _watch_parent(parent_pid: int) -> None:
    while os.getppid() == parent_pid:
        time.sleep(PARENT_POLL_S)
    os._exit(1)


def quiet_stdout() -> None:
    """Send this process's standard output, Python's and file descriptor 1, to its standard error.

    Where either stream is closed, standard output is sent nowhere instead.
    """
    try:
        os.dup2(sys.stderr.fileno(), 1)
    except (OSError, ValueError, AttributeError):
        os.dup2(os.open(os.devnull, os.O_WRONLY), 1)
    sys.stdout = sys.stderr if sys.stderr is not None else open(os.devnull, "w")  # noqa: SIM115


def init_worker(parent_pid: int) -> None:
    """Prepare a worker process: leave Ctrl-C to the parent, die with it, run one native thread, keep stdout clean.

    Parameters
    ----------
    parent_pid : int
        The pid of the main process, taken there before the worker started.
    """
    for signum in (signal.SIGINT, signal.SIGTERM):
        signal.signal(signum, signal.SIG_IGN)
    if not _kill_on_parent_death():
        threading.Thread(target=_watch_parent, args=(parent_pid,), name="watch-parent", daemon=True).start()
    if os.getppid() != parent_pid:  # the parent ended before the request above took effect
        os._exit(1)
    limit_native_threads()
    quiet_stdout()
    adopt_orphans()
    global _in_worker, _shared, _process_group
    _in_worker = True
    if hasattr(os, "getsid"):
        _process_group = (os.getsid(0), os.getpgrp())
    _shared = _shared.extended()
