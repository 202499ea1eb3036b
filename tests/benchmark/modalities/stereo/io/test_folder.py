"""Stereo folders: left/ and right/ image pairs, a sidecar beside them, navigation and truth in CSV files."""

from __future__ import annotations

import pickle
import shutil
from pathlib import Path

import cv2
import numpy as np
import pytest

from benchmark.errors import DataError
from benchmark.io import open_sequence
from benchmark.modalities.camera.io.image_folder import ImageFolder
from benchmark.modalities.camera.modality import CAMERA
from benchmark.modalities.stereo.io.export import export_stereo_sequence
from benchmark.modalities.stereo.io.folder import StereoFolder
from benchmark.modalities.stereo.model import ChaseNavigation, StereoCalibration, StereoTruth, TargetEstimate
from benchmark.modalities.stereo.modality import STEREO
from benchmark.modalities.stereo.scenes.images import StereoImageScene
from benchmark.modalities.stereo.scenes.scene import StereoScene

TINY = {"name": "stereo-images/tiny", "n_frames": 3, "camera": {"width_px": 64}, "render": {"height_px": 48}}


@pytest.fixture(scope="module")
def exported(tmp_path_factory) -> Path:
    """A tiny rendered sequence written once as a stereo folder; tests copy it before changing it."""
    return export_stereo_sequence(StereoImageScene.from_dict(TINY), tmp_path_factory.mktemp("stereo"), "tiny")


@pytest.fixture
def folder(exported, tmp_path) -> Path:
    shutil.copytree(exported, tmp_path / "tiny")
    shutil.copy(exported.parent / "tiny.toml", tmp_path / "tiny.toml")
    return tmp_path / "tiny"


def write_pair(folder: Path, name: str, width: int = 8, height: int = 6) -> None:
    for side in ("left", "right"):
        (folder / side).mkdir(parents=True, exist_ok=True)
        cv2.imwrite(str(folder / side / name), np.full((height, width, 3), 90, np.uint8))


def test_the_exporter_writes_pairs_csv_files_and_a_sidecar_beside_the_folder(exported):
    assert sorted(p.name for p in (exported / "left").iterdir()) == [f"frame_0000{k}.png" for k in range(3)]
    assert sorted(p.name for p in (exported / "right").iterdir()) == [f"frame_0000{k}.png" for k in range(3)]
    sidecar = (exported.parent / "tiny.toml").read_text()
    assert sidecar.startswith("frame_interval_s = 0.2\n[camera]\nfocal_px = 140.8\n")
    assert "width_px = 64\n" in sidecar and "principal_left_px = 31.5\n" in sidecar
    assert (exported / "targets.csv").read_text().splitlines()[:2] == [
        "frame,north_m,east_m,north_mps,east_mps,chase_north_m,chase_east_m,chase_heading_rad",
        "0,8.0,0.0,2.0,0.0,0.0,0.0,0.0",
    ]


def test_a_rendered_sequence_reads_back_bit_for_bit(exported):
    scene = StereoImageScene.from_dict(TINY)
    read = open_sequence(exported, [CAMERA, STEREO])
    assert isinstance(read, StereoFolder)
    assert read.info.calibration == scene.info.calibration
    assert (read.info.n_frames, read.info.frame_size, read.info.frame_interval_s) == (3, (64, 48), 0.2)
    for rendered, back in zip(scene.frames(), read.frames(), strict=True):
        left, right = back.observation
        assert left.dtype == np.uint8 and left.shape == (48, 64, 3)
        assert np.array_equal(left, rendered.observation[0]) and np.array_equal(right, rendered.observation[1])
        assert (back.truth, back.navigation, back.time_s) == (rendered.truth, rendered.navigation, rendered.time_s)


def test_a_stereo_folder_is_told_apart_from_an_image_folder(exported):
    assert isinstance(open_sequence(exported, [CAMERA, STEREO]), StereoFolder)
    assert isinstance(open_sequence(exported, [STEREO, CAMERA]), StereoFolder)
    assert isinstance(open_sequence(exported / "left", [CAMERA, STEREO]), ImageFolder)


def test_frames_without_a_row_have_no_truth_or_navigation_and_csv_files_are_optional(tmp_path):
    folder = tmp_path / "pairs"
    for name in ("10.png", "2.png"):
        write_pair(folder, name)
    (folder / "targets.csv").write_text(
        "frame,north_m,east_m,north_mps,east_mps,chase_north_m,chase_east_m,chase_heading_rad\n"
        "1,5,1,0.5,0,0,0,0.25\n"
    )
    sequence = StereoFolder(folder)
    frames = list(sequence.frames())
    assert [frame.truth for frame in frames] == [
        None,
        StereoTruth(TargetEstimate((5.0, 1.0), (0.5, 0.0)), (0.0, 0.0), 0.25),
    ]
    assert [frame.navigation for frame in frames] == [None, None]
    assert [frame.time_s for frame in frames] == [0.0, 1.0]
    assert sequence.info.calibration is None and sequence.info.frame_interval_s is None
    lacks = sequence.lacks(("calibration", "frame_interval_s"))
    assert lacks["calibration"] == f"stereo calibration: add a [camera] table to {tmp_path.resolve() / 'pairs.toml'}"
    assert lacks["frame_interval_s"].startswith("frame interval: add frame_interval_s (s) at the top of ")


def test_navigation_rows_and_a_partial_camera_table_are_read(tmp_path):
    folder = tmp_path / "pairs"
    write_pair(folder, "a.png")
    (folder / "navigation.csv").write_text("frame,north_m,east_m,heading_rad\n0, 1.5 ,-2,0.1\n")
    (tmp_path / "pairs.toml").write_text("frame_interval_s = 0.5\n[camera]\nwidth_px = 8\nfocal_px = 100\n")
    sequence = StereoFolder(folder)
    assert next(iter(sequence.frames())).navigation == ChaseNavigation((1.5, -2.0), 0.1)
    assert sequence.info.calibration == StereoCalibration(100.0, 0.12, 3.5, 3.5, 8, 16.0, 0.11)
    assert sequence.lacks(("calibration", "frame_interval_s")) == {}


def test_the_identity_follows_the_sidecar_and_the_csv_files_and_survives_pickling(folder):
    before = StereoFolder(folder)
    assert pickle.loads(pickle.dumps(before)).identity == before.identity
    (folder / "targets.csv").write_text((folder / "targets.csv").read_text() + "\n")
    after_csv = StereoFolder(folder)
    assert after_csv.identity.fingerprint != before.identity.fingerprint
    sidecar = folder.parent / "tiny.toml"
    sidecar.write_text(sidecar.read_text().replace("0.2", "0.25", 1))
    assert StereoFolder(folder).identity.fingerprint != after_csv.identity.fingerprint


@pytest.mark.parametrize(
    ("change", "message"),
    [
        (
            lambda f: (f / "right" / "frame_00001.png").unlink(),
            r"tiny/right/frame_00001.png: missing; the right image of .*tiny/left/frame_00001.png",
        ),
        (
            lambda f: shutil.rmtree(f / "right"),
            r"tiny/right: missing; a stereo folder holds the folders left and right",
        ),
        (
            lambda f: (f / "targets.csv").write_text((f / "targets.csv").read_text() + "3,1,2,3\n"),
            r"tiny/targets.csv:5: expected 8 values",
        ),
        (
            lambda f: (f / "navigation.csv").write_text("frame,north_m,east_m,heading_rad\n0,1,x,0\n"),
            r"tiny/navigation.csv:2: .*east_m",
        ),
        (
            lambda f: (f / "navigation.csv").write_text("frame,north_m,east_m,heading_rad\n7,1,1,0\n"),
            r"tiny/navigation.csv:2: frame 7 is beyond the sequence's 3 frames",
        ),
        (
            lambda f: (f / "navigation.csv").write_text("frame,x_m,y_m,heading_rad\n"),
            r"tiny/navigation.csv:1: expected the header 'frame,north_m,east_m,heading_rad'",
        ),
        (
            lambda f: (f.parent / "tiny.toml").write_text("[camera]\nfocal_mm = 4\n"),
            r"tiny.toml: camera: unknown key .focal_mm.",
        ),
        (lambda f: (f.parent / "tiny.toml").write_text("frame_interval_s = -1\n"), r"tiny.toml.*frame_interval_s"),
    ],
)
def test_bad_folders_are_refused_when_opened_naming_the_file_and_line_or_key(folder, change, message):
    change(folder)
    with pytest.raises(DataError, match=message):
        StereoFolder(folder)


@pytest.mark.parametrize(
    ("change", "message"),
    [
        (
            lambda f: write_pair(f, "frame_00001.png", width=64, height=40),
            r"frame 1: image .*tiny/left/frame_00001.png is 64x40 px, but the sequence's frames are 64x48 px",
        ),
        (
            lambda f: cv2.imwrite(str(f / "right" / "frame_00000.png"), np.zeros((48, 60, 3), np.uint8)),
            r"frame 0: the right image .*tiny/right/frame_00000.png is 60x48 px, but the left image is 64x48 px",
        ),
        (
            lambda f: (f / "left" / "frame_00002.png").write_bytes(b"not a png"),
            r"cannot decode image .*frame_00002.png",
        ),
        (
            lambda f: (f.parent / "tiny.toml").write_text("[camera]\nwidth_px = 320\n"),
            r"tiny.toml: camera.width_px: is 320, but the images of .*tiny are 64 px wide",
        ),
    ],
)
def test_bad_images_are_refused_while_reading_naming_the_image(folder, change, message):
    change(folder)
    sequence = StereoFolder(folder)
    with pytest.raises(DataError, match=message):
        list(sequence.frames())


def test_only_image_pairs_are_exported(tmp_path):
    scene = StereoScene.from_dict({"name": "stereo/demo", "n_frames": 2})
    message = r"stereo/demo: frame 0: the observation is a StereoMeasurement, not an image pair"
    with pytest.raises(DataError, match=message):
        export_stereo_sequence(scene, tmp_path, "demo")
