"""The Foresti EKF on an image sequence file: its calibration, frame interval and speeds come from the sidecar."""

from __future__ import annotations

import math
from collections.abc import Iterator
from pathlib import Path

import numpy as np
import pytest
from trackbench_foresti.measurement import PipeCamera, border_abscissae, border_lines
from trackbench_foresti.motion import advance
from trackbench_foresti.tracker import ForestiEkfTracker

from benchmark.modalities.camera.geometry import cable_from_borders
from benchmark.modalities.camera.io.export import export_camera_sequence
from benchmark.modalities.camera.io.sequence_file import ImageSequenceFile
from benchmark.modalities.camera.modality import CAMERA
from benchmark.modalities.camera.model import CameraCalibration, CameraTruth, VehicleSpeeds
from benchmark.model import Frame, Sequence, SequenceInfo
from benchmark.registry import TrackerEntry
from benchmark.runner import Cell, run_cell
from benchmark.selection import unmet_needs

N_FRAMES = 5
TILT_DEG = 50.0
SPEEDS = (0.3, 0.0, 1.0)


class Drawn(Sequence):
    """A pipe drawn from a camera moving at :data:`SPEEDS`, with the calibration and speeds it was drawn with."""

    def __init__(self, draw) -> None:
        self.draw = draw
        self.camera = PipeCamera(380.0, draw.SIZE, 0.3, math.radians(TILT_DEG), 0.04)

    @property
    def info(self) -> SequenceInfo:
        calibration = CameraCalibration(380.0, 0.3, math.radians(TILT_DEG))
        return SequenceInfo("drawn", "camera", N_FRAMES, self.draw.SIZE, 0.04, calibration)

    def frames(self) -> Iterator[Frame]:
        state = np.array((0.15, 1.8, math.radians(3.0), math.radians(52.0)))
        for index in range(N_FRAMES):
            cable = cable_from_borders(*border_lines(border_abscissae(state, self.camera), self.draw.SIZE))
            image = self.draw.pipe(cable, contrast=-60.0, seed=index)
            yield Frame(index, image, CameraTruth(cable), VehicleSpeeds(*SPEEDS), time_s=0.04 * index)
            state = advance(state, np.array(SPEEDS), self.camera)


def estimates(sequence: Sequence) -> list[object]:
    tracker = ForestiEkfTracker()
    tracker.reset(sequence.info, np.random.default_rng(0))
    return [tracker.step(frame) for frame in sequence.frames()]


@pytest.fixture(scope="module")
def exported(draw, tmp_path_factory) -> tuple[Drawn, Path]:
    drawn = Drawn(draw)
    return drawn, export_camera_sequence(drawn, tmp_path_factory.mktemp("exported"), "S")


def write_sidecar(path: Path, navigation: bool = True) -> None:
    columns = "\n".join(f"{key} = {[speed] * N_FRAMES}" for key, speed in zip(
        ("lateral_mps", "vertical_mps", "frontal_mps"), SPEEDS, strict=True
    ))
    text = f"frame_interval_s = 0.04\n[camera]\nfocal_px = 380\npipe_diameter_m = 0.3\ntilt_deg = {TILT_DEG}\n"
    path.with_suffix(".toml").write_text(text + (f"[navigation]\n{columns}\n" if navigation else ""))


def test_the_ekf_on_a_sequence_file_with_a_sidecar_tracks_as_on_the_sequence_it_was_exported_from(exported):
    drawn, path = exported
    write_sidecar(path)
    from_file = ImageSequenceFile(path)
    assert estimates(from_file) == estimates(drawn)
    write_sidecar(path, navigation=False)
    assert estimates(ImageSequenceFile(path)) != estimates(drawn)  # the speeds of eq. (7) do count


def test_the_ekf_runs_as_a_cell_on_a_sequence_file_with_a_sidecar_and_is_refused_without(exported):
    _, path = exported
    entry = TrackerEntry("foresti_ekf", ForestiEkfTracker, ForestiEkfTracker.make_params())
    path.with_suffix(".toml").unlink(missing_ok=True)
    bare = Cell(entry, ImageSequenceFile(path), 0, "none", modality=CAMERA)
    runnable, problems = unmet_needs([bare])
    sidecar = path.with_suffix(".toml")
    assert runnable == []
    assert problems == [
        f"foresti_ekf cannot run on {path}: it needs camera calibration: "
        f"add focal_px, pipe_diameter_m, tilt_deg under [camera] in {sidecar}",
        f"foresti_ekf cannot run on {path}: it needs frame interval: add frame_interval_s (s) at the top of {sidecar}",
    ]
    write_sidecar(path)
    cell = Cell(entry, ImageSequenceFile(path), 0, "none", modality=CAMERA)
    assert unmet_needs([cell]) == ([cell], [])
    result = run_cell(cell)
    assert result.status == "ok" and len(result.scores) == N_FRAMES


def test_an_export_carries_its_sidecar_so_the_ekf_runs_on_it_as_on_the_sequence(draw, tmp_path):
    drawn = Drawn(draw)
    path = export_camera_sequence(drawn, tmp_path, "S")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["S", "S.nav.csv", "S.toml", "S.txt"]
    from_file = ImageSequenceFile(path)
    assert from_file.info.calibration == drawn.info.calibration
    assert from_file.info.frame_interval_s == drawn.info.frame_interval_s
    assert [frame.navigation for frame in from_file.frames()] == [frame.navigation for frame in drawn.frames()]
    assert estimates(from_file) == estimates(drawn)
