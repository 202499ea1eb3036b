"""The machine a nightly ran on, and the commit it ran: what makes its speeds comparable.

Speeds are compared only between runs of the same machine: the same CPU
model and core count, and the same Python, numpy and OpenCV, whose builds
decide how fast the same code runs.  Accuracy does not depend on the
machine and is compared across machines.
"""

from __future__ import annotations

import hashlib
import json
import os
import platform
import subprocess
from pathlib import Path

import cv2
import numpy as np


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
