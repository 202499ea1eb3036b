"""A fourth modality from a third-party distribution: registered, run, ranked, read and exported.

The sensor is a single-beam altimeter over the seabed: each frame is one
range reading, the truth is the seabed's depth, and a tracker estimates
the depth.  Nothing in trackbench knows it; it arrives through the
``trackbench`` entry-point group like any plugin, with its own types,
scorer, file reader, exporter and scene kind.
"""

from __future__ import annotations

import math
import sys
import types
from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd
import pytest
from click.testing import CliRunner

from benchmark import Frame, Modality, Outcome, Reader, Sequence, SequenceInfo, Tracker, hookimpl
from benchmark.cli import main
from benchmark.modality import EstimateError
from benchmark.plugins import load_registry

SUFFIX = ".alt"


@dataclass(frozen=True)
class Echo:
    """One altimeter reading: the range to the seabed, m."""

    range_m: float


@dataclass(frozen=True)
class SeabedTruth:
    depth_m: float


@dataclass(frozen=True)
class DepthEstimate:
    depth_m: float


@dataclass(frozen=True)
class DepthScorer:
    """Correct within ``tolerance_m`` of the true depth."""

    tolerance_m: float = 0.1
    error_columns: tuple[str, ...] = ("err_depth_m",)

    def check(self, estimate: DepthEstimate) -> None:
        if not math.isfinite(estimate.depth_m):
            raise EstimateError(f"estimate has a non-finite depth: {estimate}")

    def score(self, estimate: DepthEstimate | None, truth: SeabedTruth | None, info: SequenceInfo) -> tuple:
        if truth is None:
            return None, (math.nan,)
        if estimate is None:
            return Outcome.MISSED, (math.nan,)
        error = estimate.depth_m - truth.depth_m
        return (Outcome.CORRECT if abs(error) <= self.tolerance_m else Outcome.FALSE), (error,)


@dataclass(frozen=True)
class AltimeterRun(Sequence):
    """A synthetic run: a seabed sloping down, readings with Gaussian noise and a spike every tenth ping."""

    name: str
    n_frames: int = 40
    noise_m: float = 0.02
    seed: int = 0

    @property
    def info(self) -> SequenceInfo:
        return SequenceInfo(self.name, "altimeter", n_frames=self.n_frames, frame_interval_s=0.1)

    def frames(self) -> Iterator[Frame]:
        rng = np.random.default_rng(self.seed)
        for k in range(self.n_frames):
            depth = 20.0 + 0.05 * k
            reading = depth + self.noise_m * rng.standard_normal() + (5.0 if k % 10 == 9 else 0.0)
            yield Frame(k, Echo(reading), SeabedTruth(depth), time_s=0.1 * k)

    @classmethod
    def from_table(cls, table: Mapping[str, Any], source: str) -> AltimeterRun:
        return cls(str(table["name"]), int(table.get("n_frames", 40)), float(table.get("noise_m", 0.02)))


@dataclass(frozen=True)
class AltimeterFile(Sequence):
    """A file of readings, one ``range_m depth_m`` pair per line."""

    path: str

    @property
    def info(self) -> SequenceInfo:
        return SequenceInfo(self.path, "altimeter", frame_interval_s=0.1)

    def frames(self) -> Iterator[Frame]:
        for k, line in enumerate(Path(self.path).read_text().splitlines()):
            reading, depth = (float(value) for value in line.split())
            yield Frame(k, Echo(reading), SeabedTruth(depth), time_s=0.1 * k)


def export_altimeter(sequence: Sequence, out: Path, stem: str) -> Path:
    out.mkdir(parents=True, exist_ok=True)
    path = out / f"{stem}{SUFFIX}"
    path.write_text("".join(f"{frame.observation.range_m!r} {frame.truth.depth_m!r}\n" for frame in sequence.frames()))
    return path


ALTIMETER = Modality(
    name="altimeter",
    observation_type=Echo,
    truth_type=SeabedTruth,
    estimate_type=DepthEstimate,
    scorer=DepthScorer(),
    readers=(Reader(AltimeterFile, "an altimeter file (.alt)", suffixes=(SUFFIX,)),),
    exporter=export_altimeter,
    scene_kinds={"altimeter-run": AltimeterRun.from_table},
)


class RawDepth(Tracker[SeabedTruth, DepthEstimate]):
    """Reports every reading as it is, spikes included."""

    name, version, modality = "raw_depth", "1.0", "altimeter"

    def reset(self, info: SequenceInfo, rng: np.random.Generator, init: SeabedTruth | None = None) -> None:
        self.init = init

    def step(self, frame: Frame[Echo, SeabedTruth]) -> DepthEstimate | None:
        return DepthEstimate(frame.observation.range_m)


class MedianDepth(RawDepth):
    """The median of the last three readings: spikes removed."""

    name = "median_depth"

    def reset(self, info: SequenceInfo, rng: np.random.Generator, init: SeabedTruth | None = None) -> None:
        self.recent: list[float] = [] if init is None else [init.depth_m]

    def step(self, frame: Frame[Echo, SeabedTruth]) -> DepthEstimate | None:
        self.recent = [*self.recent[-2:], frame.observation.range_m]
        return DepthEstimate(float(np.median(self.recent)))


def register_modalities(registry):
    registry.add_modality(ALTIMETER)


def register_trackers(registry):
    registry.add_tracker(RawDepth)
    registry.add_tracker(MedianDepth)


def register_datasets(registry):
    kind = registry.scene_kinds["altimeter-run"]
    runs = [kind({"name": "altimeter/slope"}, "test"), kind({"name": "altimeter/calm", "noise_m": 0.0}, "test")]
    registry.add_suite("altimeter", runs)


@pytest.fixture
def altimeter_installed(monkeypatch: pytest.MonkeyPatch, installed: Callable[..., object]) -> None:
    """The distribution ``acme-altimeter`` installed, offering one plugin module with all three hooks."""
    module = types.ModuleType("acme_altimeter")
    module.trackbench_register_modalities = hookimpl(register_modalities)
    module.trackbench_register_trackers = hookimpl(register_trackers)
    module.trackbench_register_datasets = hookimpl(register_datasets)
    monkeypatch.setitem(sys.modules, "acme_altimeter", module)
    installed("acme-altimeter", {"altimeter": "acme_altimeter"}, version="2.1")


def test_the_modality_arrives_through_its_entry_point_like_the_built_in_ones(altimeter_installed: None) -> None:
    registry = load_registry()
    assert registry.modalities["altimeter"] is ALTIMETER
    assert set(registry.modalities) >= {"camera", "sonar", "stereo", "altimeter"}
    assert registry.trackers["median_depth"].modality == "altimeter"
    assert registry.trackers["median_depth"].origin.distribution == "acme-altimeter 2.1"
    assert [seq.info.name for seq in registry.suites["altimeter"].sequences] == ["altimeter/slope", "altimeter/calm"]


@pytest.mark.parametrize("jobs", ["0", "1"])
def test_its_trackers_run_and_are_ranked_on_a_board_of_their_own(
    altimeter_installed: None, tmp_path: Path, jobs: str
) -> None:
    result = CliRunner().invoke(main, ["run", "--suite", "altimeter", "--jobs", jobs, "--out", str(tmp_path)])
    assert result.exit_code == 0, result.output
    board = pd.read_csv(tmp_path / "leaderboard.csv")
    assert set(board["modality"]) == {"altimeter"}
    assert {"rmse_depth_m", "correct_pct", "cpu_fps", "wall_fps"} <= set(board.columns)
    assert not any(column.startswith("rmse_d_") for column in board.columns)
    overall = board[board["dataset"] == "(all)"].set_index("tracker")
    # The spikes (every tenth reading, 5 m) make the raw tracker false on 10 % of frames; the median removes them.
    assert overall.loc["raw_depth", "false_pct"] == pytest.approx(10.0)
    assert overall.loc["median_depth", "correct_pct"] > overall.loc["raw_depth", "correct_pct"]
    assert overall.loc["median_depth", "rank"] == 1 and overall.loc["raw_depth", "rank"] == 2
    assert overall.loc["median_depth", "rmse_depth_m"] < overall.loc["raw_depth", "rmse_depth_m"]
    assert "altimeter" in result.stdout and "median_depth" in result.stdout


def test_its_files_are_exported_and_read_back_through_its_reader_and_exporter(
    altimeter_installed: None, tmp_path: Path
) -> None:
    runner = CliRunner()
    exported = runner.invoke(main, ["make-dataset", "altimeter", "--out", str(tmp_path / "data")])
    assert exported.exit_code == 0, exported.output
    path = tmp_path / "data" / f"altimeter_slope{SUFFIX}"
    assert path.is_file() and len(path.read_text().splitlines()) == 40
    out = tmp_path / "run"
    result = runner.invoke(main, ["run", "--tracker", "median_depth", "--dataset", str(path), "--out", str(out)])
    assert result.exit_code == 0, result.output
    board = pd.read_csv(out / "leaderboard.csv")
    row = board[board["dataset"] == str(path)].iloc[0]
    assert row["modality"] == "altimeter" and row["frames"] == 40 and row["status"] == "ok"


def test_a_tracker_of_another_modality_never_meets_its_sequences(altimeter_installed: None, tmp_path: Path) -> None:
    result = CliRunner().invoke(
        main, ["run", "--tracker", "hough", "--suite", "altimeter", "--jobs", "0", "--out", str(tmp_path)]
    )
    assert result.exit_code == 2
    assert "nothing to run" in result.output and "hough (camera)" in result.output
