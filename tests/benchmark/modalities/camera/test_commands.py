"""``trackbench diagnose``, the camera modality's command, through click's runner with a fake registry."""

from __future__ import annotations

import dataclasses
import types
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

import benchmark.plugins
from benchmark.cli import main
from benchmark.modalities.camera.model import CableState
from benchmark.model import Frame, SequenceInfo
from benchmark.registry import Registry
from benchmark.tracker import Tracker

from ...conftest import Invoke


@dataclasses.dataclass(frozen=True)
class PeakedParams:
    offset_px: float = 0.0


class Peaked(Tracker):
    """Scores states by closeness to the true state moved ``offset_px`` along d; reports the truth moved ``step_px``."""

    name = "peaked"
    version = "1.0"
    modality = "camera"
    Params = PeakedParams
    step_px = 0.0

    def reset(self, info: SequenceInfo, rng: np.random.Generator, init: object = None) -> None:
        pass

    def step(self, frame: Frame) -> CableState:
        return dataclasses.replace(frame.truth.cable, d=frame.truth.cable.d + self.step_px)

    def score_states(self, frame: Frame, states: np.ndarray) -> np.ndarray:
        peak = frame.truth.cable.as_array() + np.array([self.params.offset_px, 0.0, 0.0, 0.0])
        return -np.abs(states - peak) @ np.array([1.0, 100.0, 1.0, 100.0])


@pytest.fixture
def diagnose(fakes: types.ModuleType, monkeypatch: pytest.MonkeyPatch) -> Invoke:
    """The CLI over fakes plus ``peaked`` (ceiling 100 %), ``peaked-off`` (10 px off, 0 %) and a sonar sequence."""

    class SonarSequence(fakes.FakeSequence):
        @property
        def info(self) -> SequenceInfo:
            return dataclasses.replace(super().info, modality="sonar")

    def load_registry(disable: tuple[str, ...] = (), strict: bool = False) -> Registry:
        registry = fakes.make_registry((fakes.Perfect, fakes.SonarOnly))
        registry.add_tracker(Peaked)
        registry.add_tracker(Peaked, name="peaked-off", params={"offset_px": 10.0})
        registry.add_suite("mixed", [fakes.FakeSequence("fake/S3", 4), SonarSequence("sonar/x", 3)])
        return registry

    monkeypatch.setattr(benchmark.plugins, "load_registry", load_registry)
    return lambda *args: CliRunner().invoke(main, ["diagnose", *args])


def ceiling_rows(text: str) -> dict[str, list[str]]:
    """``dataset: [frames, ceiling_pct, correct_pct]`` of a printed diagnose table."""
    lines = [line.strip("|").split("|") for line in text.splitlines() if line.startswith("|")]
    return {row[0].strip(): [cell.strip() for cell in row[1:]] for row in lines[2:]}


def test_diagnose_sets_the_ceiling_beside_the_latest_stored_result(
    diagnose: Invoke, monkeypatch: pytest.MonkeyPatch, tmp_path: Path
) -> None:
    out = str(tmp_path)
    monkeypatch.setattr(Peaked, "step_px", 10.0)
    run = ["run", "--tracker", "peaked", "--tracker", "peaked-off", "--suite", "fake", "--in-process", "--out", out]
    assert CliRunner().invoke(main, [*run, "--seeds", "2"]).exit_code == 0
    monkeypatch.setattr(Peaked, "step_px", 0.0)
    assert CliRunner().invoke(main, run).exit_code == 0  # the latest run: seed 0 only, every frame correct

    result = diagnose("--tracker", "peaked", "--suite", "fake", "--out", out)
    assert result.exit_code == 0, result.output
    assert ceiling_rows(result.stdout) == {"fake/S1": ["10", "100.0", "100.0"], "fake/S2": ["6", "100.0", "100.0"]}
    assert (tmp_path / "diagnose_peaked.md").read_text().strip() == result.stdout.strip()
    off = diagnose("--tracker", "peaked-off", "--dataset", "fake/S2", "--out", out)
    assert off.exit_code == 0, off.output
    assert ceiling_rows(off.stdout) == {"fake/S2": ["6", "0.0", "100.0"]}
    # Another parameter set is another model: its results (here all false) are not set beside this ceiling.
    monkeypatch.setattr(Peaked, "step_px", 10.0)
    assert CliRunner().invoke(main, [*run, "--param", "peaked.offset_px=3"]).exit_code == 0
    assert ceiling_rows(diagnose("--tracker", "peaked", "--suite", "fake", "--out", out).stdout)["fake/S1"] == [
        "10", "100.0", "100.0"
    ]


def test_diagnose_without_a_database_leaves_the_result_empty(diagnose: Invoke, tmp_path: Path) -> None:
    out = tmp_path / "new"
    result = diagnose("--tracker", "peaked", "--suite", "mixed", "--out", str(out))
    assert result.exit_code == 0, result.output
    assert ceiling_rows(result.stdout) == {"fake/S3": ["4", "100.0", ""]}
    assert "skipped sonar/x: a sonar sequence, not a camera sequence" in result.stderr
    assert "sequences 2/2, elapsed " in result.stderr  # the progress of a log that is not a terminal
    assert (out / "diagnose_peaked.md").is_file()


@pytest.mark.parametrize(
    ("args", "words"),
    [
        (["--tracker", "perfect", "--suite", "fake"], ["tracker 'perfect' does not implement score_states"]),
        (["--tracker", "sonar-only", "--suite", "fake"], ["tracker 'sonar-only' reads sonar"]),
        (["--tracker", "nope", "--suite", "fake"], ["unknown tracker 'nope'"]),
        (["--tracker", "peaked", "--dataset", "sonar/x"], ["nothing to diagnose", "skipped sonar/x"]),
    ],
)
def test_diagnose_refuses_what_it_cannot_diagnose(
    diagnose: Invoke, tmp_path: Path, args: list[str], words: list[str]
) -> None:
    result = diagnose(*args, "--out", str(tmp_path))
    assert result.exit_code == 2
    assert result.stderr.startswith("Error: ")
    for word in words:
        assert word in result.stderr
    assert not (tmp_path / "diagnose_peaked.md").exists()
