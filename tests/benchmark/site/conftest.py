"""Histories to build sites from: a real one of two trackers on a short camera clip, and a hostile one.

``nightly`` runs ``hough`` and ``condensation`` with two seeds on the first
:data:`CLIP_FRAMES` frames of ``camera/S2`` (written as an image sequence
file, so that the runs read files instead of rendering), once with the
defaults and once with a vote threshold so high that ``hough`` misses more
frames.  The history records the good run twice and then the bad one, so
that the last run is a regression against the runs before it, caused by
the changed parameter, and the trend of ``hough`` has a step at the third
run.

``hostile`` is a one-run history of fake trackers whose name and error
message are HTML, to check that the site escapes what plugins supply; its
failed cells have replays, as a nightly records them.
"""

from __future__ import annotations

import dataclasses
import itertools
import types
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

import pytest

from benchmark.harness import run_benchmark
from benchmark.history.database import History
from benchmark.history.replays import DEFAULT_BUDGET, ReplayPlan, record_replays
from benchmark.io import export_sequence
from benchmark.model import Frame, Sequence, SequenceInfo
from benchmark.plugins import load_registry
from benchmark.registry import Registry
from benchmark.selection import Selection, select_cells
from benchmark.site import build_site
from benchmark.site.pages import replay_back
from benchmark.store import ResultStore

CLIP_FRAMES = 30
HOSTILE_NAME = '<script>alert("tracker")</script>'
HOSTILE_MESSAGE = "<img src=x onerror=alert(1)>"


class Clip(Sequence):
    """The first ``n_frames`` frames of a sequence."""

    def __init__(self, sequence: Sequence, n_frames: int) -> None:
        self._sequence = sequence
        self._info = dataclasses.replace(sequence.info, n_frames=n_frames)

    @property
    def info(self) -> SequenceInfo:
        return self._info

    def frames(self) -> Iterator[Frame]:
        return itertools.islice(self._sequence.frames(), self._info.n_frames)


@dataclass(frozen=True)
class Site:
    """A history and the site built from it."""

    history: History
    root: Path
    index: Path


def record(registry: Registry, history: History, selection: Selection, out: Path, days: list[int]) -> None:
    """Run ``selection`` once into ``out`` and record that run in ``history`` once per day of ``days``."""
    run_benchmark(select_cells(registry, selection), registry.modalities, out, in_process=True)
    store = ResultStore(out / "results.sqlite")
    run_id = store.latest_run()
    assert run_id is not None
    for day in days:
        history.record(
            store, run_id, registry.modalities, started=f"2024-06-{day:02d}T02:00:00+00:00", version="0.1.0",
            commit="0123456789abcdef", machine={"cpu": "test cpu", "cores": 2}, machine_key="m", argv=[],
            seeds=selection.seeds,
        )


def build(history: History, root: Path, registry: Registry) -> Site:
    return Site(history, root, build_site(history, root, registry.modalities))


@pytest.fixture(scope="session")
def registry() -> Registry:
    """Every plugin's trackers and suites."""
    return load_registry()


@pytest.fixture(scope="session")
def clip(registry: Registry, tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The first frames of ``camera/S2`` as an image sequence file."""
    folder = tmp_path_factory.mktemp("clip")
    return export_sequence(Clip(registry.sequence("camera/S2"), CLIP_FRAMES), folder, registry.modalities, stem="S2")


@pytest.fixture(scope="session")
def nightly(registry: Registry, clip: Path, tmp_path_factory: pytest.TempPathFactory) -> Site:
    """Three nightly runs, good, good, bad, and the site of the last."""
    folder = tmp_path_factory.mktemp("nightly")
    history = History(folder / "history.sqlite")
    good = Selection(trackers=("hough", "condensation"), datasets=(str(clip),), seeds=2)
    record(registry, history, good, folder / "good", [10, 11])
    bad = dataclasses.replace(good, params=("hough.vote_fraction=0.5",))
    record(registry, history, bad, folder / "bad", [12])
    return build(history, folder / "site", registry)


@pytest.fixture(scope="session")
def first_night(registry: Registry, clip: Path, tmp_path_factory: pytest.TempPathFactory) -> Site:
    """A history of one run."""
    folder = tmp_path_factory.mktemp("first-night")
    history = History(folder / "history.sqlite")
    record(registry, history, Selection(trackers=("hough",), datasets=(str(clip),)), folder / "run", [10])
    return build(history, folder / "site", registry)


@pytest.fixture(scope="session")
def hostile(fakes: types.ModuleType, tmp_path_factory: pytest.TempPathFactory) -> Site:
    """One run of fake trackers named, and failing, in HTML."""

    class Shouting(fakes.Perfect):
        name = "shouting"

        def step(self, frame: Frame) -> object:
            if frame.index == 4:
                raise RuntimeError(HOSTILE_MESSAGE)
            return frame.truth.cable if frame.index % 3 else None

    registry = fakes.make_registry(())
    with registry.acting_for(fakes.ORIGIN):
        registry.add_tracker(fakes.Noisy, name=HOSTILE_NAME)
        registry.add_tracker(Shouting)
    folder = tmp_path_factory.mktemp("hostile")
    history = History(folder / "history.sqlite")
    selection = Selection(trackers=(HOSTILE_NAME, "shouting"), datasets=("fake/S1",), seeds=2)
    record(registry, history, selection, folder / "run", [10])
    plan = ReplayPlan(DEFAULT_BUDGET, lambda: select_cells(registry, selection))
    record_replays(history, int(history.runs()["id"].iloc[-1]), None, plan, folder / "run", replay_back)
    return build(history, folder / "site", registry)



SHORT_ROUTE = {
    "name": "routes/short",
    "legs": [{"length_m": 0.5}, {"length_m": 0.6, "turn_deg": 3.0}],
    "frame_size": [48, 36],
    "focal_px": 57.0,
    "start_offset_m": 0.15,
}
"""A closed-loop route of about 60 tiny frames."""


def route_registry(fakes: types.ModuleType) -> Registry:
    """The fake registry of ``perfect`` with a suite ``routes`` of :data:`SHORT_ROUTE` (not scored) and the following metrics."""
    from benchmark.closedloop.scene import ClosedLoopScene
    from benchmark.metrics.closed_loop import METRICS

    registry = fakes.make_registry((fakes.Perfect,))
    with registry.acting_for(fakes.ORIGIN):
        registry.add_suite("routes", [ClosedLoopScene.from_dict(SHORT_ROUTE)], scored=False)
        for metric in METRICS:
            registry.add_metric(metric)
    return registry


@pytest.fixture(scope="session")
def closed_loop_night(fakes: types.ModuleType, tmp_path_factory: pytest.TempPathFactory) -> Site:
    """One run of a tracker that reports the truth, steering the vehicle along :data:`SHORT_ROUTE`, and its site."""
    from benchmark.closedloop.topview import routes_by_dataset
    from benchmark.leaderboard import load_leaderboards

    registry = route_registry(fakes)
    folder = tmp_path_factory.mktemp("closed-loop")
    history = History(folder / "history.sqlite")
    selection = Selection(trackers=("perfect",), suites=("routes", "fake"))
    run_benchmark(select_cells(registry, selection), registry.modalities, folder / "run", in_process=True,
                  metrics=registry.metrics)
    store = ResultStore(folder / "run" / "results.sqlite")
    run_id = store.latest_run()
    assert run_id is not None
    boards = load_leaderboards(store, registry.modalities, run_id, metrics=registry.metrics)
    history.record(
        store, run_id, registry.modalities, started="2024-06-10T02:00:00+00:00", version="0.1.0",
        commit="0123456789abcdef", machine={"cpu": "test cpu", "cores": 2}, machine_key="m", argv=[], seeds=1,
        metrics=registry.metrics, boards=boards,
    )
    routes = routes_by_dataset(registry.suites["routes"].sequences)
    return Site(history, folder / "site",
                build_site(history, folder / "site", registry.modalities, metrics=registry.metrics, routes=routes))
