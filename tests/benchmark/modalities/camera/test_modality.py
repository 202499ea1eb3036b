"""The camera modality as it registers: its types, scorer, readers, exporter and scene kind."""

from pathlib import Path

import cv2
import numpy as np
import pytest

from benchmark.errors import DataError
from benchmark.io import open_sequence
from benchmark.modalities.camera import modality
from benchmark.modalities.camera.io.image_folder import ImageFolder
from benchmark.modalities.camera.io.sequence_file import ImageSequenceFile
from benchmark.modalities.camera.model import CableState, CameraTruth
from benchmark.modalities.camera.scenes.scene import CameraScene
from benchmark.modalities.camera.scoring import CameraScorer
from benchmark.registry import Registry


def test_it_registers_itself_through_its_hook() -> None:
    registry = Registry()
    modality.trackbench_register_modalities(registry)
    assert registry.modalities == {"camera": modality.CAMERA}
    assert set(registry.scene_kinds) == {"camera", "camera-route"}


def test_it_declares_grey_images_cable_truths_and_cable_states() -> None:
    camera = modality.CAMERA
    assert (camera.observation_type, camera.truth_type, camera.estimate_type) == (np.ndarray, CameraTruth, CableState)
    assert isinstance(camera.scorer, CameraScorer)
    assert camera.scene_kinds["camera"] == CameraScene.from_dict


def test_its_readers_open_folders_videos_and_any_other_file_as_a_sequence_file(tmp_path: Path) -> None:
    folder = tmp_path / "frames"
    folder.mkdir()
    assert cv2.imwrite(str(folder / "a.png"), np.zeros((4, 6), np.uint8))
    listing = tmp_path / "run.seq"
    listing.write_text("1 0 10 0 # frames/a.png\n")
    video = tmp_path / "clip.AVI"
    video.write_bytes(b"not a video")
    assert isinstance(open_sequence(folder, [modality.CAMERA]), ImageFolder)
    assert isinstance(open_sequence(listing, [modality.CAMERA]), ImageSequenceFile)
    with pytest.raises(DataError, match="clip.AVI: cannot open video"):
        open_sequence(video, [modality.CAMERA])
