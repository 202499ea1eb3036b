"""``trackbench replay``: writes the page of one cell, refuses bad inputs with one ``Error:`` line."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest
from click.testing import CliRunner, Result

import benchmark.plugins
import benchmark.replay.views
from benchmark.cli import main
from benchmark.registry import Registry
from benchmark.replay.camera import CameraView

from ..conftest import ALL_TRACKERS, make_registry
from ..replay.conftest import Gaussian, Particles


@pytest.fixture
def replay(monkeypatch: pytest.MonkeyPatch, tmp_path: Path):
    registry: Registry = make_registry((*ALL_TRACKERS, Particles, Gaussian))
    monkeypatch.setattr(benchmark.plugins, "load_registry", lambda disable=(), strict=False: registry)
    monkeypatch.setenv("TRACKBENCH_CACHE", str(tmp_path / "cache"))
    monkeypatch.chdir(tmp_path)

    def run(*args: str) -> Result:
        return CliRunner().invoke(main, ["replay", *args])

    return run


def frames_of(path: Path) -> list[int]:
    text = path.read_text()
    data = json.loads(re.search(r'id="replay-data">(.*?)</script>', text, re.S).group(1))
    return [frame["index"] for frame in data["frames"]]


def test_replay_writes_the_page_of_the_frames_asked_for(replay, tmp_path: Path) -> None:
    result = replay(
        "--tracker", "fake-particles", "--dataset", "fake/S1", "--seed", "2", "--frames", "2:5", "--out", "r.html"
    )
    assert result.exit_code == 0, result.output
    assert frames_of(tmp_path / "r.html") == [2, 3, 4]
    assert "wrote r.html: 3 frames" in result.output


def test_replay_names_its_page_after_the_cell_by_default(replay, tmp_path: Path) -> None:
    result = replay("--tracker", "fake-gaussian", "--dataset", "fake/S2")
    assert result.exit_code == 0, result.output
    assert frames_of(tmp_path / "reports" / "replay" / "fake-gaussian_fake-S2_s0.html") == list(range(6))


def test_a_tracker_that_raises_is_replayed_up_to_its_fault(replay, tmp_path: Path) -> None:
    result = replay("--tracker", "raising", "--dataset", "fake/S1", "--out", "r.html")
    assert result.exit_code == 0, result.output
    assert "Warning: the tracker stopped the recording: RuntimeError: lost the cable (frame 3)" in result.output
    assert frames_of(tmp_path / "r.html") == [0, 1, 2]


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (("--tracker", "nobody", "--dataset", "fake/S1"), "unknown tracker 'nobody'"),
        (("--tracker", "perfect", "--dataset", "fake/S9"), "fake/S9"),
        (("--tracker", "perfect", "--dataset", "fake/S1", "--frames", "5:2"), "frame range '5:2'"),
        (("--tracker", "perfect", "--dataset", "fake/S1", "--frames", "x"), "frame range 'x'"),
        (("--tracker", "perfect", "--dataset", "fake/S1", "--frames", "20:30"), "fake/S1 has 10 frames"),
        (("--tracker", "sonar-only", "--dataset", "fake/S1"), "no selected tracker reads the modality"),
    ],
)
def test_replay_refuses_bad_inputs_with_a_clear_error(replay, args: tuple[str, ...], message: str) -> None:
    result = replay(*args)
    assert result.exit_code == 2
    assert "Error:" in result.output and message in result.output
    assert "Traceback" not in result.output


def test_replay_refuses_a_modality_without_a_view(replay, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(benchmark.replay.views, "_views", lambda: {"camera": CameraView()})
    result = replay("--tracker", "sonar-only", "--dataset", "fake/S1")
    assert result.exit_code == 2
    assert "Error: replay cannot show sonar frames yet (it shows: camera)" in result.output
    assert "Traceback" not in result.output
