"""The stereo EKF on a stereo folder gives what it gives on the rendered sequence the folder was written from."""

from __future__ import annotations

import numpy as np
from trackbench_stereo_ekf import StereoEkfTracker

from benchmark.io import export_sequence, open_sequence
from benchmark.modalities.camera.modality import CAMERA
from benchmark.modalities.stereo.io.export import export_stereo_sequence
from benchmark.modalities.stereo.io.folder import StereoFolder
from benchmark.modalities.stereo.modality import STEREO
from benchmark.modalities.stereo.scenes.images import StereoImageScene
from benchmark.registry import TrackerEntry
from benchmark.runner import Cell, run_cell
from benchmark.selection import unmet_needs


def test_a_rendered_sequence_and_its_exported_folder_give_the_same_estimates_and_board(tmp_path):
    modalities = {"camera": CAMERA, "stereo": STEREO}
    scene = StereoImageScene.from_dict(
        {"name": "stereo-images/tiny", "n_frames": 4, "camera": {"width_px": 64}, "render": {"height_px": 48}}
    )
    folder = open_sequence(export_sequence(scene, tmp_path, modalities), modalities.values())
    assert isinstance(folder, StereoFolder)
    entry = TrackerEntry("stereo_ekf", StereoEkfTracker, StereoEkfTracker.make_params())

    def estimates(sequence):
        tracker = entry.create()
        tracker.reset(sequence.info, np.random.default_rng(0), next(iter(sequence.frames())).truth)
        return [tracker.step(frame) for frame in sequence.frames()]

    rendered = estimates(scene)
    assert sum(estimate is not None for estimate in rendered) >= 3
    assert estimates(folder) == rendered
    on_scene, on_folder = (run_cell(Cell(entry, sequence, 0, modality=STEREO)) for sequence in (scene, folder))
    assert on_scene.status == on_folder.status == "ok"
    columns = [column for column in on_scene.frames.columns if column not in ("step_ms", "wall_ms")]
    assert on_folder.frames[columns].equals(on_scene.frames[columns])
    assert on_folder.summary()["correct_pct"] == on_scene.summary()["correct_pct"]


def test_a_stereo_folder_without_a_sidecar_is_refused_before_any_cell_with_the_line_to_add(tmp_path):
    scene = StereoImageScene.from_dict(
        {"name": "stereo-images/tiny", "n_frames": 2, "camera": {"width_px": 64}, "render": {"height_px": 48}}
    )
    folder = export_stereo_sequence(scene, tmp_path, "tiny")
    sidecar = tmp_path.resolve() / "tiny.toml"
    sidecar.unlink()
    entry = TrackerEntry("stereo_ekf", StereoEkfTracker, StereoEkfTracker.make_params())
    bare = Cell(entry, StereoFolder(folder), 0, modality=STEREO)
    runnable, problems = unmet_needs([bare])
    assert runnable == []
    assert problems == [
        f"stereo_ekf cannot run on {folder}: it needs stereo calibration: add a [camera] table to {sidecar}",
        f"stereo_ekf cannot run on {folder}: it needs frame interval: add frame_interval_s (s) at the top of {sidecar}",
    ]
    sidecar.write_text("frame_interval_s = 0.2\n[camera]\nwidth_px = 64\n")
    cell = Cell(entry, StereoFolder(folder), 0, modality=STEREO)
    assert unmet_needs([cell]) == ([cell], [])
