"""``acme_faults``: a third-party plugin whose trackers misbehave in every way a plugin can.

The fault-injection tests (``test_fault_injection.py``) install this file as
the module ``acme_faults`` of a real distribution, ``acme-faults 1.0``, in a
temporary site folder (a ``.dist-info`` with its entry point), so that
trackbench finds it as it finds any plugin, in the test process and in the
``trackbench`` processes the tests start.

Every faulty tracker returns the true cable state until frame
:data:`FAULT_AT`, then misbehaves: so each cell has finished frames that
must survive the fault.  The suite ``faults`` holds one short sequence.
"""

from __future__ import annotations

import ctypes
import os
import sys
import tempfile
import time
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from benchmark import CableState, CameraFrame, CameraTruth, Frame, Sequence, SequenceInfo, Tracker, hookimpl

FAULT_AT = 2
"""The frame at which a faulty tracker misbehaves; frames before it are scored."""
N_FRAMES = 6
PID_FILE_ENV = "ACME_FAULTS_PID_FILE"
"""Where the spinning tracker writes its process id before it spins, if set."""


@dataclass(frozen=True)
class Corridor(Sequence):
    """A short camera sequence: a cable drifting right over a flat grey seabed."""

    name: str = "faults/corridor"
    n_frames: int = N_FRAMES

    @property
    def info(self) -> SequenceInfo:
        return SequenceInfo(self.name, "camera", n_frames=self.n_frames, frame_size=(32, 24), frame_interval_s=0.04)

    def frames(self) -> Iterator[Frame]:
        for index in range(self.n_frames):
            truth = CameraTruth(CableState(d=-4.0 + index, alpha=0.01 * index, w=6.0, beta=0.02))
            yield Frame(index, np.full((24, 32), 60, dtype=np.uint8), truth, time_s=0.04 * index)


class Faulty(Tracker[CameraTruth, CableState]):
    """Right until frame :data:`FAULT_AT`, then :meth:`fault`."""

    version = "1.0"
    modality = "camera"

    def reset(self, info: SequenceInfo, rng: np.random.Generator, init: CameraTruth | None = None) -> None:
        pass

    def step(self, frame: CameraFrame) -> CableState | None:
        if frame.index >= FAULT_AT:
            return self.fault(frame)
        return frame.truth.cable

    def fault(self, frame: CameraFrame) -> Any:
        return frame.truth.cable


class Honest(Faulty):
    name = "honest"


class Exits(Faulty):
    name = "exits"

    def fault(self, frame: CameraFrame) -> Any:
        sys.exit(3)


class Interrupts(Faulty):
    name = "interrupts"

    def fault(self, frame: CameraFrame) -> Any:
        raise KeyboardInterrupt


class Unprintable(BaseException):
    """A BaseException of the plugin's own, whose message cannot even be shown."""

    def __str__(self) -> str:
        raise RuntimeError("no message")


class RaisesOddly(Faulty):
    name = "raises-oddly"

    def fault(self, frame: CameraFrame) -> Any:
        raise Unprintable


class Spins(Faulty):
    name = "spins"

    def fault(self, frame: CameraFrame) -> Any:
        pid_file = os.environ.get(PID_FILE_ENV)
        if pid_file:
            Path(pid_file).write_text(str(os.getpid()))
        while True:
            pass


class Hangs(Faulty):
    """Never returns from its step, without using the processor: a wait on something that never comes.

    To a run it is what :class:`Spins` is, a step that never ends, stopped by the run's wall-time limit; it
    leaves the processor to the run's other cells.  ``Spins`` is kept for what only a busy loop reaches,
    the conformance kit's CPU-time limit and a killed run's workers.
    """

    name = "hangs"

    def fault(self, frame: CameraFrame) -> Any:
        while True:
            time.sleep(1.0)


class ExitsHard(Faulty):
    name = "exits-hard"

    def fault(self, frame: CameraFrame) -> Any:
        os._exit(7)


class Segfaults(Faulty):
    name = "segfaults"

    def fault(self, frame: CameraFrame) -> Any:
        ctypes.string_at(0)


class ReturnsNan(Faulty):
    name = "returns-nan"

    def fault(self, frame: CameraFrame) -> Any:
        return CableState(float("nan"), 0.0, 6.0, 0.0)


class ReturnsAbsurd(Faulty):
    name = "returns-absurd"

    def fault(self, frame: CameraFrame) -> Any:
        return CableState(1e308, 1e308, 1e308, 1e308)


class Slow(Faulty):
    """Right on every frame, but 0.5 s per frame: something to interrupt."""

    name = "slow"

    def fault(self, frame: CameraFrame) -> Any:
        time.sleep(0.5)
        return frame.truth.cable


class Chatty(Faulty):
    """Right on every frame, but talks on standard output, through Python and through file descriptor 1."""

    name = "chatty"

    def fault(self, frame: CameraFrame) -> Any:
        print(f"chatter from print, frame {frame.index}")
        os.write(1, f"chatter from fd 1, frame {frame.index}\n".encode())
        return frame.truth.cable


class RaisesInColour(Faulty):
    """Raises with terminal escapes in its message: colour, bell, a rewritten window title."""

    name = "raises-in-colour"

    def fault(self, frame: CameraFrame) -> Any:
        raise RuntimeError("\x1b[31mred\x1b[0m\x07\x1b]0;owned\x07")


WANDERED = "ACME_FAULTS_WANDERED"
"""Set by the wandering tracker, which also leaves for a folder of its own."""


class Wanders(Faulty):
    """Right on every frame, but changes its process's working folder, its environment and ``numpy.mean``."""

    name = "wanders"

    def fault(self, frame: CameraFrame) -> Any:
        elsewhere = Path(tempfile.gettempdir()) / "acme-wandered"
        elsewhere.mkdir(exist_ok=True)
        os.chdir(elsewhere)
        os.environ[WANDERED] = "1"
        os.environ["TRACKBENCH_CACHE"] = "relative-cache"
        np.mean = lambda *args, **kwargs: 0.0
        return frame.truth.cable


class LeavesSession(Faulty):
    """Right on every frame, but moves its process to a session of its own, from which no process returns."""

    name = "leaves-session"

    def fault(self, frame: CameraFrame) -> Any:
        if frame.index == FAULT_AT:
            os.setsid()
        return frame.truth.cable


class Regroups(Faulty):
    """Right on every frame, but moves its process to a process group of its own."""

    name = "regroups"

    def fault(self, frame: CameraFrame) -> Any:
        if frame.index == FAULT_AT:
            os.setpgid(0, 0)
        return frame.truth.cable


class Settled(Faulty):
    """Right on every frame, as long as no earlier cell of its process changed folder, environment, numpy or group.

    Its process must be in the session and process group of the process
    that started it (the run's).
    """

    name = "settled"

    def fault(self, frame: CameraFrame) -> Any:
        if WANDERED in os.environ or "acme-wandered" in os.getcwd() or np.mean([1.0, 3.0]) != 2.0:
            raise RuntimeError(f"an earlier cell's folder ({os.getcwd()}), environment or numpy is still here")
        parent = os.getppid()
        if (os.getsid(0), os.getpgrp()) != (os.getsid(parent), os.getpgid(parent)):
            raise RuntimeError("an earlier cell's session or process group is still here")
        return frame.truth.cable


class Daemonises(Faulty):
    """Right on every frame, but starts a daemon (forking twice) that would sleep for ten minutes."""

    name = "daemonises"

    def fault(self, frame: CameraFrame) -> Any:
        if frame.index == FAULT_AT:
            started, ready = os.pipe()
            child = os.fork()
            if child == 0:
                os.setsid()
                if os.fork() == 0:
                    for stream in (0, 1, 2):  # as a daemon does, so the run's pipes close without it
                        os.dup2(os.open(os.devnull, os.O_RDWR), stream)
                    pid_file = os.environ.get(PID_FILE_ENV)
                    if pid_file:
                        Path(f"{pid_file}.{os.getpid()}").write_text(str(os.getpid()))
                    os.write(ready, b"1")
                    time.sleep(600)
                os._exit(0)
            os.waitpid(child, 0)
            os.read(started, 1)  # the daemon has written its pid
            os.close(started)
            os.close(ready)
        return frame.truth.cable


class GlobalRandom(Faulty):
    """Right but for noise from numpy's global generator, which a tracker should never draw from."""

    name = "global-random"

    def fault(self, frame: CameraFrame) -> Any:
        cable = frame.truth.cable
        return CableState(cable.d + np.random.normal(0.0, 1.0), cable.alpha, cable.w, cable.beta)


SAFE = (Honest, Exits, Interrupts, RaisesOddly, ReturnsNan, ReturnsAbsurd)
"""Trackers whose faults a run in the test process survives even without worker processes."""
PROCESS_KILLERS = (Spins, Hangs, ExitsHard, Segfaults)
"""Trackers that only a worker process can contain."""


@hookimpl
def trackbench_register_trackers(registry: Any) -> None:
    for tracker in (*SAFE, *PROCESS_KILLERS, Slow, Chatty, RaisesInColour, Wanders, Settled, Daemonises, GlobalRandom,
                    LeavesSession, Regroups):
        registry.add_tracker(tracker)


@hookimpl
def trackbench_register_datasets(registry: Any) -> None:
    registry.add_suite("faults", [Corridor()])
