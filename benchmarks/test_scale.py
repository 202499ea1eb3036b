"""Benchmarks of the frame cache and of a cell's memory; run with ``pytest benchmarks``.

Not part of the test suite (``pytest`` collects ``tests/`` only).  The
run-level figures (CPU of a whole run against its trackers' steps, cold and
warm cache, ``--jobs 1`` against ``--jobs 2``) come from the summary line
every ``trackbench run`` prints; README.md gives the commands.
"""

from __future__ import annotations

import io
import itertools
import json
import pickle
import subprocess
import sys
from pathlib import Path

import pytest

from benchmark import storage
from benchmark.frame_cache import FrameCache
from benchmark.plugins import load_registry

CELL_SCRIPT = """
import dataclasses, json, resource, sys
from pathlib import Path
from benchmark.executors.local import LocalExecutor
from benchmark import storage
from benchmark.frame_cache import FrameCache
from benchmark.plugins import load_registry
from benchmark.runner import Cell
from benchmark.selection import select_trackers

n_frames, cache = int(sys.argv[1]), Path(sys.argv[2])
registry = load_registry()
scene = registry.sequence("camera/S3")
scene = type(scene)(dataclasses.replace(scene.spec, n_frames=n_frames))
[entry] = select_trackers(registry, ["hough"])
cell = Cell(entry, FrameCache(cache).wrap(scene), 0, modality=registry.modalities["camera"])
[result] = LocalExecutor(1).run([cell], None)
assert result.status == "ok" and len(result.scores) == n_frames, result.message
peak_kib = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
print(json.dumps({"frames": n_frames, "peak_rss_mib": peak_kib / 1024}))
"""


def peak_rss_mib(n_frames: int, cache: Path) -> float:
    """Peak RSS of the worker process that ran one hough cell of ``n_frames`` frames (rendered, then read)."""
    output = subprocess.run(
        [sys.executable, "-c", CELL_SCRIPT, str(n_frames), str(cache)], check=True, capture_output=True, text=True
    ).stdout
    return json.loads(output.splitlines()[-1])["peak_rss_mib"]


def test_peak_memory_of_a_cell_is_flat_in_the_sequence_length(tmp_path: Path, benchmark) -> None:  # type: ignore[no-untyped-def]
    """A cell reading from the cache stays flat; the one that renders holds the renderer's seabed map.

    The camera renderer keeps a seabed map as long as the vehicle's path
    (about 35 kB a frame), so the first cell of a sequence, which renders
    it, grows with its length; every other cell only streams frames.
    """
    lengths = (100, 5000)
    cold = {n: peak_rss_mib(n, tmp_path / "cache") for n in lengths}
    warm = {n: peak_rss_mib(n, tmp_path / "cache") for n in lengths}
    benchmark.extra_info.update({f"cold_peak_rss_mib_{n}_frames": round(cold[n], 1) for n in lengths})
    benchmark.extra_info.update({f"warm_peak_rss_mib_{n}_frames": round(warm[n], 1) for n in lengths})
    benchmark.pedantic(lambda: None, rounds=1)
    print(f"peak RSS of a hough cell, MiB: rendering {cold}, reading from the cache {warm}")
    assert warm[5000] <= 1.10 * warm[100], warm


@pytest.fixture(scope="module")
def scene():  # type: ignore[no-untyped-def]
    return load_registry().sequence("camera/S1")


def test_render_camera_s1(benchmark, scene) -> None:  # type: ignore[no-untyped-def]
    benchmark.group = "frames of camera/S1 (248 frames)"
    benchmark.pedantic(lambda: sum(1 for _ in type(scene)(scene.spec).frames()), rounds=3)


def test_read_camera_s1_from_the_frame_cache(benchmark, scene, tmp_path: Path) -> None:  # type: ignore[no-untyped-def]
    benchmark.group = "frames of camera/S1 (248 frames)"
    cached = FrameCache(tmp_path).wrap(scene)
    sum(1 for _ in cached.frames())
    benchmark.pedantic(lambda: sum(1 for _ in cached.frames()), rounds=10)


@pytest.fixture(scope="module")
def streams(scene):  # type: ignore[no-untyped-def]
    """camera/S1's first 60 frames as records (the cache's format) and as the pickles it replaced."""
    frames = list(itertools.islice(scene.frames(), 60))
    packages = storage.packages_of(type(scene))
    records = b"".join(storage.dumps(frame, packages) for frame in frames)
    pickles = b"".join(pickle.dumps(frame, protocol=5) for frame in frames)
    return frames, packages, records, pickles


@pytest.mark.parametrize("stored_as", ["records", "pickles"])
def test_read_60_frames(benchmark, streams, stored_as: str) -> None:  # type: ignore[no-untyped-def]
    """Records, the cache's format, against the pickles it replaced (these bytes were written here)."""
    benchmark.group = "reading back 60 frames of camera/S1 (320 x 240)"
    frames, packages, records, pickles = streams
    data = records if stored_as == "records" else pickles
    read_one = (lambda handle: storage.read(handle, packages, "records")) if stored_as == "records" else pickle.load

    def read() -> None:
        handle = io.BytesIO(data)
        for _ in frames:
            read_one(handle)

    benchmark(read)
