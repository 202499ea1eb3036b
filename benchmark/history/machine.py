"""The machine a nightly ran on, how busy it was, and the commit it ran: what makes its speeds comparable.

Speeds are compared only between runs of the same machine: the same CPU
model and core count, and the same Python, numpy and OpenCV, whose builds
decide how fast the same code runs.  Accuracy does not depend on the
machine and is compared across machines.  How busy the machine was while a
run ran (:class:`LoadMeter`) is kept with the run, so that a reader of a
speed sees what else the machine was doing.
"""

from __future__ import annotations

import hashlib
import json
import os
import platform
import resource
import subprocess
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import cv2
import numpy as np
import psutil


def _cpu_model() -> str:
    """The CPU's model name from ``/proc/cpuinfo``, else what :mod:`platform` knows."""
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.lower().startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or platform.machine()


def describe_machine() -> dict[str, str | int]:
    """CPU model, cores, operating system, and the versions of Python, numpy and OpenCV."""
    return {
        "cpu": _cpu_model(),
        "cores": os.cpu_count() or 1,
        "system": f"{platform.system()} {platform.machine()}",
        "python": platform.python_version(),
        "numpy": np.__version__,
        "opencv": cv2.__version__,
    }


def machine_key(machine: dict[str, str | int]) -> str:
    """A short hash of everything :func:`describe_machine` reports: runs with equal keys compare speeds."""
    return hashlib.sha256(json.dumps(machine, sort_keys=True).encode()).hexdigest()[:12]


def git_commit(folder: Path | None = None) -> str:
    """The commit checked out in the git work tree holding ``folder`` (default: trackbench's source), or ``""``.

    A trackbench installed from a wheel has no work tree; its version then
    identifies it alone.
    """
    folder = folder or Path(__file__).resolve().parent
    try:
        done = subprocess.run(
            ["git", "-C", str(folder), "rev-parse", "HEAD"], capture_output=True, text=True, timeout=10, check=False
        )
    except (OSError, subprocess.SubprocessError):
        return ""
    return done.stdout.strip() if done.returncode == 0 else ""


def _busy_s(times: Any) -> float:
    """Seconds the machine's cores spent on any work, of a :func:`psutil.cpu_times` total."""
    idle = times.idle + getattr(times, "iowait", 0.0)
    return sum(times) - idle


def _own_cpu_s() -> float:
    """CPU time of this process, its ended child processes and those still running (workers of a pool)."""
    own, ended = resource.getrusage(resource.RUSAGE_SELF), resource.getrusage(resource.RUSAGE_CHILDREN)
    total = own.ru_utime + own.ru_stime + ended.ru_utime + ended.ru_stime
    for child in psutil.Process().children(recursive=True):
        try:
            times = child.cpu_times()
        except psutil.Error:  # ended between the listing and the question
            continue
        total += times.user + times.system
    return total


def _load_1min() -> float:
    return round(os.getloadavg()[0], 2)


@dataclass(frozen=True)
class LoadMeter:
    """How busy the machine is while a run runs, from its start (:meth:`start`) to its end (:meth:`stop`).

    Attributes
    ----------
    load_1min : float
        The 1-minute load average at the start (runnable processes, all
        cores together).
    started : float
        :func:`time.perf_counter` at the start.
    busy_s : float
        Seconds the machine's cores had been busy at the start.
    own_s : float
        CPU seconds of this process and its child processes at the start.
    """

    load_1min: float
    started: float
    busy_s: float
    own_s: float

    @classmethod
    def start(cls) -> LoadMeter:
        """The machine's counters now."""
        return cls(_load_1min(), time.perf_counter(), _busy_s(psutil.cpu_times()), _own_cpu_s())

    def stop(self) -> dict[str, float]:
        """How busy the machine was since :meth:`start`.

        Returns
        -------
        dict
            ``cores``; ``load_1min_start`` and ``load_1min_end``, the
            1-minute load average at both ends; ``busy_pct``, the share of
            all cores' time that was busy over the run (100: every core
            all the time); ``others_pct``, the share busy with processes
            other than this one and its children (the run's workers), which
            is what slowed the run's wall-clock speed; and ``seconds``, the
            run's wall time.  Shares are rounded to 0.1.
        """
        seconds = time.perf_counter() - self.started
        capacity = max(seconds, 1e-9) * (psutil.cpu_count() or 1)
        busy = _busy_s(psutil.cpu_times()) - self.busy_s
        own = _own_cpu_s() - self.own_s
        return {
            "cores": psutil.cpu_count() or 1,
            "load_1min_start": self.load_1min,
            "load_1min_end": _load_1min(),
            "busy_pct": round(min(100.0, 100.0 * busy / capacity), 1),
            "others_pct": round(min(100.0, max(0.0, 100.0 * (busy - own) / capacity)), 1),
            "seconds": round(seconds, 1),
        }


def describe_load(load: dict[str, float]) -> str:
    """A run's load (:meth:`LoadMeter.stop`) as one line: ``key: value`` pairs, as the site shows it."""
    return ", ".join(f"{key}: {value}" for key, value in load.items()) or "not recorded"
