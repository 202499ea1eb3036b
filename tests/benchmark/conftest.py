"""Fixtures of the harness tests: fake trackers, a fake camera sequence, a fake registry, tiny image files.

The fakes are module-level classes so that worker processes can unpickle
them; tests reach them through the ``fakes`` fixture (this module).  The
fake registry holds the built-in camera and sonar modalities, registered
before the trackers as the plugin manager does.
"""

from __future__ import annotations

import dataclasses
import importlib.metadata
import math
import sys
import time
import types
from collections.abc import Callable, Iterable, Iterator, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Annotated, Any, ClassVar

import annotated_types
import cv2
import numpy as np
import pytest
from click.testing import CliRunner, Result

import benchmark.plugins
from benchmark.cli import main
from benchmark.errors import DataError
from benchmark.modalities.camera.modality import CAMERA
from benchmark.modalities.camera.model import CableState, CameraTruth
from benchmark.modalities.sonar.modality import SONAR
from benchmark.modality import Modality
from benchmark.model import Frame, Sequence, SequenceInfo
from benchmark.registry import Origin, Registry, TrackerEntry
from benchmark.runner import Cell
from benchmark.tracker import Tracker

WIDTH, HEIGHT = 64, 48


def truth_at(index: int) -> CameraTruth:
    """The ground truth of frame ``index`` of every fake sequence: a cable drifting right."""
    return CameraTruth(CableState(d=-6.0 + 1.5 * index, alpha=0.01 * index, w=12.0, beta=0.02), visible_fraction=1.0)


@dataclass(frozen=True)
class FakeSequence(Sequence):
    """A tiny camera sequence; ``corrupt_at`` makes reading that frame raise a DataError."""

    name: str = "fake/S1"
    n_frames: int = 10
    corrupt_at: int | None = None
    description: str = "tiny fake sequence"

    @property
    def info(self) -> SequenceInfo:
        return SequenceInfo(
            name=self.name,
            modality="camera",
            n_frames=self.n_frames,
            frame_size=(WIDTH, HEIGHT),
            frame_interval_s=0.04,
            extra={"description": self.description},
        )

    def frames(self) -> Iterator[Frame]:
        for index in range(self.n_frames):
            if index == self.corrupt_at:
                raise DataError(f"{self.name}: frame {index} is corrupt")
            image = np.full((HEIGHT, WIDTH), 40 + index, dtype=np.uint8)
            yield Frame(index, image, truth_at(index), time_s=0.04 * index)


class Perfect(Tracker):
    """Returns the frame's true cable state."""

    name = "perfect"
    version = "1.0"
    modality = "camera"
    deterministic = True

    def reset(self, info: SequenceInfo, rng: np.random.Generator, init: Any = None) -> None:
        self.init = init

    def step(self, frame: Frame) -> Any:
        return frame.truth.cable


class Counting(Perfect):
    """A perfect tracker that counts its instances (in this process)."""

    name = "counting"
    created: ClassVar[int] = 0

    def __init__(self, params: Any = None) -> None:
        super().__init__(params)
        type(self).created += 1


class Blind(Perfect):
    """Never detects anything."""

    name = "blind"

    def step(self, frame: Frame) -> Any:
        return None


@dataclasses.dataclass(frozen=True)
class RaisingParams:
    fail_at: int = 3


class Raising(Perfect):
    """Correct until frame ``fail_at``, where it raises."""

    name = "raising"
    Params = RaisingParams

    def step(self, frame: Frame) -> Any:
        if frame.index == self.params.fail_at:
            raise RuntimeError("lost the cable")
        return frame.truth.cable


@dataclasses.dataclass(frozen=True)
class SleepyParams:
    from_frame: int = 1
    sleep_s: float = 60.0


class Sleepy(Perfect):
    """Sleeps ``sleep_s`` in every step from frame ``from_frame`` on (a hang when long)."""

    name = "sleepy"
    Params = SleepyParams

    def step(self, frame: Frame) -> Any:
        if frame.index >= self.params.from_frame:
            time.sleep(self.params.sleep_s)
        return frame.truth.cable


@dataclasses.dataclass(frozen=True)
class GarbageParams:
    kind: str = "string"
    at: int = 2


class Garbage(Perfect):
    """Returns a string (or a NaN state, ``kind="nan"``) at frame ``at``."""

    name = "garbage"
    Params = GarbageParams

    def step(self, frame: Frame) -> Any:
        if frame.index != self.params.at:
            return frame.truth.cable
        if self.params.kind == "nan":
            return CableState(math.nan, 0.0, 10.0, 0.0)
        return "a cable, probably"


@dataclasses.dataclass(frozen=True)
class NoisyParams:
    sigma_px: float = 4.0


class Noisy(Perfect):
    """The true state plus Gaussian noise from the cell's generator, sometimes nothing."""

    name = "noisy"
    Params = NoisyParams
    deterministic = False

    def reset(self, info: SequenceInfo, rng: np.random.Generator, init: Any = None) -> None:
        self.rng = rng

    def step(self, frame: Frame) -> Any:
        if self.rng.random() < 0.2:
            return None
        noise = self.rng.normal(0.0, 1.0, 4) * np.array([self.params.sigma_px, 0.03, 2.0, 0.01])
        return CableState.from_array(frame.truth.cable.as_array() + noise)


class SonarOnly(Perfect):
    """Reads sonar, so never meets a camera sequence."""

    name = "sonar-only"
    modality = "sonar"


@dataclasses.dataclass(frozen=True)
class BoundedParams:
    window: Annotated[int, annotated_types.Ge(1)] = 3


class Bounded(Counting):
    """A counting tracker whose parameter declares its range (not among ALL_TRACKERS)."""

    name = "bounded"
    Params = BoundedParams


ALL_TRACKERS = (Perfect, Counting, Blind, Raising, Sleepy, Garbage, Noisy, SonarOnly)
MODALITIES: tuple[Modality, ...] = (CAMERA, SONAR)
BUILT_IN = Origin("modalities", "subsea-trackbench 0.0")
ORIGIN = Origin("fakes", "fake-trackers 9.9")


def make_registry(trackers: tuple[type[Tracker], ...] = ALL_TRACKERS) -> Registry:
    """A registry with the camera and sonar modalities, the fake trackers and a suite ``fake`` of two sequences."""
    registry = Registry()
    with registry.acting_for(BUILT_IN):
        for modality in MODALITIES:
            registry.add_modality(modality)
    with registry.acting_for(ORIGIN):
        for tracker in trackers:
            registry.add_tracker(tracker)
        registry.add_suite("fake", [FakeSequence("fake/S1", 10), FakeSequence("fake/S2", 6, description="shorter")])
    return registry


def make_cell(entry: TrackerEntry, sequence: Sequence, seed: int = 0, init: str = "truth") -> Cell:
    """A cell of a fake tracker, carrying the built-in modality the tracker reads."""
    modality = {modality.name: modality for modality in MODALITIES}[entry.modality]
    return Cell(entry, sequence, seed, init, modality=modality)  # type: ignore[arg-type]


class FakeDistribution(importlib.metadata.Distribution):
    """An installed distribution as importlib.metadata sees one: its METADATA and its entry points of one group."""

    def __init__(
        self,
        name: str,
        entry_points: Mapping[str, str] | Iterable[tuple[str, str]],
        version: str = "0.3",
        group: str = "trackbench",
    ) -> None:
        pairs = entry_points.items() if isinstance(entry_points, Mapping) else entry_points
        self.files_text = {
            "METADATA": f"Metadata-Version: 2.1\nName: {name}\nVersion: {version}\n",
            "entry_points.txt": f"[{group}]\n" + "".join(f"{ep} = {value}\n" for ep, value in pairs),
        }

    def read_text(self, filename: str) -> str | None:
        return self.files_text.get(filename)

    def locate_file(self, path: str | Path) -> Path:
        return Path(path)


Install = Callable[..., FakeDistribution]


@pytest.fixture
def installed(monkeypatch: pytest.MonkeyPatch) -> Install:
    """``install(name, entry_points, version="0.3", group="trackbench")`` adds a fake distribution next to the real ones."""
    real = list(importlib.metadata.distributions())
    extra: list[FakeDistribution] = []
    monkeypatch.setattr(importlib.metadata, "distributions", lambda: [*real, *extra])

    def install(
        name: str,
        entry_points: Mapping[str, str] | Iterable[tuple[str, str]],
        version: str = "0.3",
        group: str = "trackbench",
    ) -> FakeDistribution:
        extra.append(FakeDistribution(name, entry_points, version, group))
        return extra[-1]

    return install


@pytest.fixture(scope="session")
def fakes() -> types.ModuleType:
    """This module: the fake classes and helpers above."""
    return sys.modules[__name__]


@pytest.fixture
def fake_registry() -> Registry:
    """A fresh registry of fake trackers and the suite ``fake``."""
    return make_registry()


ImageMaker = Callable[..., np.ndarray]


@pytest.fixture
def make_image() -> ImageMaker:
    """Write a small random grey PNG (or any OpenCV format, by the name's ending) and return its pixels."""
    rng = np.random.default_rng(20240611)

    def make(path: Path, width: int = 12, height: int = 8) -> np.ndarray:
        path.parent.mkdir(parents=True, exist_ok=True)
        image = rng.integers(0, 256, size=(height, width), dtype=np.uint8)
        assert cv2.imwrite(str(path), image)
        return image

    return make


Invoke = Callable[..., Result]


@pytest.fixture
def loads(fakes: types.ModuleType, monkeypatch: pytest.MonkeyPatch) -> list[tuple[str, ...]]:
    """Serve the fake registry to the CLI; records the ``disable`` argument of every load."""
    calls: list[tuple[str, ...]] = []

    def load_registry(disable: tuple[str, ...] = (), strict: bool = False) -> Registry:
        calls.append(tuple(disable))
        return fakes.make_registry()

    monkeypatch.setattr(benchmark.plugins, "load_registry", load_registry)
    return calls


@pytest.fixture
def invoke(loads: list[tuple[str, ...]]) -> Invoke:
    def run(*args: str) -> Result:
        return CliRunner().invoke(main, list(args))

    return run


CHROMIUM = Path("/usr/bin/chromium")
"""Debian's Chromium, which the browser tests drive through playwright."""
CHROMIUM_ARGS = [
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
]


@pytest.fixture(scope="module")
def chromium() -> Iterator[Any]:
    """A headless :data:`CHROMIUM` launched by playwright; the test is skipped without either."""
    sync_api = pytest.importorskip("playwright.sync_api", reason="the browser tests need Python playwright")
    if not CHROMIUM.exists():
        pytest.skip(f"the browser tests need Chromium at {CHROMIUM}")
    with sync_api.sync_playwright() as playwright:
        launched = playwright.chromium.launch(executable_path=str(CHROMIUM), args=CHROMIUM_ARGS)
        try:
            yield UntimedBrowser(launched)
        finally:
            launched.close()


class UntimedBrowser:
    """A playwright browser whose pages and contexts wait without a time limit: a busy machine is slow, not wrong."""

    def __init__(self, browser: Any) -> None:
        self._browser = browser

    def new_page(self, **options: Any) -> Any:
        page = self._browser.new_page(**options)
        page.set_default_timeout(0)
        return page

    def new_context(self, **options: Any) -> Any:
        context = self._browser.new_context(**options)
        context.set_default_timeout(0)
        return context

    def __getattr__(self, name: str) -> Any:
        return getattr(self._browser, name)
