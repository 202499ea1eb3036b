"""Opening folders, sequence files and videos for labelling, and saving with a backup."""

from __future__ import annotations

import math
from pathlib import Path

import cv2
import numpy as np
import pytest

from benchmark.errors import DataError
from benchmark.modalities.camera.io.sequence_file import read_sequence_file, write_sequence_file
from benchmark.modalities.camera.labeller.document import open_document
from benchmark.modalities.camera.model import UNKNOWN_CABLE, CableState

from .conftest import N_FRAMES, SIZE


def test_a_folder_is_saved_beside_itself_with_relative_paths(image_folder: Path) -> None:
    document = open_document(image_folder)
    assert document.output == image_folder.with_name("frames.txt")
    assert document.size == SIZE
    assert [state.is_known for state in document.states] == [False] * N_FRAMES
    states = [CableState(1.5, 0.1, 12.0, 0.02)] + [UNKNOWN_CABLE] * (N_FRAMES - 1)
    document.save(states)
    lines = document.output.read_text().splitlines()
    assert lines[1] == "1.5 0.1 12.0 0.02 # frames/frame0.png"
    assert lines[2] == "nan nan nan nan # frames/frame1.png"
    assert not document.backup.exists()


def test_saving_again_keeps_the_previous_file_as_backup(image_folder: Path) -> None:
    document = open_document(image_folder)
    first = [CableState(float(i), 0.0, 10.0, 0.0) for i in range(N_FRAMES)]
    document.save(first)
    saved = document.output.read_bytes()
    revision = document.save([UNKNOWN_CABLE] * N_FRAMES)
    assert document.output.with_name("frames.txt.bak").read_bytes() == saved
    assert revision == document.revision != ""
    assert all(not row.cable.is_known for row in read_sequence_file(document.output))


def test_a_sequence_file_is_labelled_in_place_and_saved_unchanged(image_folder: Path) -> None:
    file = image_folder.parent / "S.txt"
    cables = [CableState(0.5 * i, -0.01 * i, 20.0, 0.01) if i % 2 else UNKNOWN_CABLE for i in range(N_FRAMES)]
    write_sequence_file(file, zip(cables, sorted(image_folder.iterdir()), strict=True))
    before = file.read_bytes()
    document = open_document(file)
    assert document.output == file.absolute()
    assert [s.as_array().tolist() if s.is_known else None for s in document.states] == [
        c.as_array().tolist() if c.is_known else None for c in cables
    ]
    document.save(document.states)
    assert file.read_bytes() == before == document.backup.read_bytes()


def test_a_folder_whose_sequence_file_exists_is_refused(image_folder: Path) -> None:
    image_folder.with_name("frames.txt").write_text("")
    with pytest.raises(DataError, match=r"frames\.txt: exists already"):
        open_document(image_folder)


def write_video(path: Path, n_frames: int) -> Path:
    """A grey MJPG video of ``n_frames`` frames of :data:`SIZE`."""
    writer = cv2.VideoWriter(str(path), cv2.VideoWriter_fourcc(*"MJPG"), 10.0, SIZE, isColor=False)
    for index in range(n_frames):
        writer.write(np.full((SIZE[1], SIZE[0]), 50 * index, np.uint8))
    writer.release()
    return path


def test_a_video_is_written_out_as_frames_and_an_unlabelled_sequence_file(tmp_path: Path) -> None:
    video = write_video(tmp_path / "clip.avi", 3)
    document = open_document(video)
    assert document.output == tmp_path / "clip.txt"
    assert [image.relative_to(tmp_path).as_posix() for image in document.images] == [
        f"clip/frame_{i:05d}.png" for i in range(3)
    ]
    assert all(math.isnan(row.cable.d) for row in read_sequence_file(document.output))


def test_the_wrong_number_of_states_is_not_saved(image_folder: Path) -> None:
    document = open_document(image_folder)
    with pytest.raises(DataError, match="2 states for 6 frames"):
        document.save([UNKNOWN_CABLE] * 2)
    assert not document.output.exists()


def test_what_the_camera_readers_cannot_open_is_an_error_naming_it(tmp_path: Path) -> None:
    with pytest.raises(DataError, match="missing"):
        open_document(tmp_path / "missing")


def test_a_sequence_file_saved_elsewhere_goes_to_a_new_file_only(image_folder: Path, tmp_path: Path) -> None:
    file = tmp_path / "S.txt"
    write_sequence_file(file, ((UNKNOWN_CABLE, image) for image in sorted(image_folder.iterdir())))
    assert open_document(file, tmp_path / "T.txt").output == tmp_path / "T.txt"
    assert open_document(file, file).output == file
    (tmp_path / "U.txt").write_text("someone's labels")
    with pytest.raises(DataError, match=r"U\.txt: exists already"):
        open_document(file, tmp_path / "U.txt")


def test_an_output_in_a_missing_folder_is_refused(image_folder: Path, tmp_path: Path) -> None:
    with pytest.raises(DataError, match="no such folder"):
        open_document(image_folder, tmp_path / "nowhere" / "S.txt")


def test_a_video_whose_frame_folder_exists_is_refused(tmp_path: Path) -> None:
    video = write_video(tmp_path / "clip.avi", 1)
    (tmp_path / "clip").mkdir()
    with pytest.raises(DataError, match="clip: exists already"):
        open_document(video)
    assert not (tmp_path / "clip.txt").exists()
