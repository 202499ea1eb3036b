"""Choosing a reader for a dataset path: folder, video, or image sequence file."""

from __future__ import annotations

import cv2
import numpy as np
import pytest

from benchmark.errors import DataError
from benchmark.io import ImageFolder, ImageSequenceFile, VideoFile, open_sequence


def test_a_folder_opens_as_image_folder(tmp_path, make_image):
    make_image(tmp_path / "a.png")
    assert isinstance(open_sequence(tmp_path), ImageFolder)
    assert isinstance(open_sequence(str(tmp_path)), ImageFolder)


@pytest.mark.parametrize("name", ["clip.avi", "CLIP.AVI"])
def test_a_video_name_opens_as_video(tmp_path, name):
    path = tmp_path / name
    writer = cv2.VideoWriter(str(path), cv2.VideoWriter_fourcc(*"MJPG"), 5.0, (16, 8), True)
    if not writer.isOpened():
        pytest.skip("this OpenCV build cannot write MJPG into .avi")
    writer.write(np.zeros((8, 16, 3), dtype=np.uint8))
    writer.release()
    assert isinstance(open_sequence(path), VideoFile)


@pytest.mark.parametrize("name", ["seq.txt", "S1.seq", "labels", "ground truth.dat"])
def test_any_other_file_opens_as_image_sequence_file(tmp_path, name):
    path = tmp_path / name
    path.write_text("1 0 20 0 # a.png\n", encoding="utf-8")
    sequence = open_sequence(path)
    assert isinstance(sequence, ImageSequenceFile)
    assert [row.line for row in sequence.rows] == [1]
    assert sequence.rows[0].image == (tmp_path / "a.png").resolve()


def test_a_missing_path_is_named(tmp_path):
    with pytest.raises(DataError, match="no_such_dataset"):
        open_sequence(tmp_path / "no_such_dataset")


def test_a_malformed_file_is_reported_by_its_reader(tmp_path):
    path = tmp_path / "clip.mkv.txt"
    path.write_text("this is not a row\n", encoding="utf-8")
    with pytest.raises(DataError, match="clip.mkv.txt:1:"):
        open_sequence(path)
