"""Image folders: every OpenCV image in a folder, in natural order, without ground truth."""

from __future__ import annotations

import pickle

import cv2
import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from benchmark.errors import DataError
from benchmark.modalities.camera.io.image_folder import ImageFolder, natural_key


@given(st.text("ab_-", max_size=4), st.integers(0, 10**6), st.integers(0, 10**6), st.sampled_from([".png", ".BMP"]))
def test_natural_key_orders_numbers_by_value(prefix, a, b, suffix):
    first, second = f"{prefix}{a}{suffix}", f"{prefix}{b}{suffix}"
    assert (natural_key(first) < natural_key(second)) == (a < b)


def test_natural_key_is_a_total_order_on_distinct_names():
    names = ["img01.png", "img1.png", "IMG1.png", "img001.png"]
    keys = [natural_key(n) for n in names]
    assert len(set(keys)) == len(names)
    assert sorted(names, key=natural_key) == sorted(reversed(names), key=natural_key)


def test_images_come_in_natural_order_and_other_files_are_skipped(tmp_path):
    names = [(10, "frame10.png"), (2, "frame2.png"), (1, "frame1.tif"), (3, "Frame3.PNG"), (4, "frame4.DIB")]
    for number, name in names:
        writable = tmp_path / (name if not name.endswith(".DIB") else "tmp.bmp")
        assert cv2.imwrite(str(writable), np.full((5, 7), number, dtype=np.uint8))
        writable.rename(tmp_path / name)
    (tmp_path / "notes.txt").write_text("not an image", encoding="utf-8")
    (tmp_path / "frame0.png").mkdir()
    folder = ImageFolder(tmp_path)
    assert [p.name for p in folder.images] == ["frame1.tif", "frame2.png", "Frame3.PNG", "frame4.DIB", "frame10.png"]
    frames = list(folder.frames())
    assert [int(f.observation[0, 0]) for f in frames] == [1, 2, 3, 4, 10]
    assert all(not f.truth.cable.is_known for f in frames)
    assert [f.time_s for f in frames] == [0.0, 1.0, 2.0, 3.0, 4.0]
    info = folder.info
    assert (info.name, info.modality, info.n_frames, info.frame_size) == (str(tmp_path), "camera", 5, (7, 5))


def test_empty_folder_is_an_error_naming_it(tmp_path):
    empty = tmp_path / "empty dir"
    empty.mkdir()
    with pytest.raises(DataError, match="empty dir"):
        ImageFolder(empty)
    (empty / "readme.txt").write_text("x", encoding="utf-8")
    with pytest.raises(DataError, match="no image files"):
        ImageFolder(empty)


def test_missing_folder_is_an_error_naming_it(tmp_path):
    with pytest.raises(DataError, match="absent"):
        ImageFolder(tmp_path / "absent")


def test_corrupt_and_differently_sized_images_are_named(tmp_path, make_image):
    make_image(tmp_path / "a1.png", 12, 8)
    make_image(tmp_path / "a2.png", 13, 8)
    with pytest.raises(DataError, match="a2.png.*13x8"):
        list(ImageFolder(tmp_path))
    (tmp_path / "a2.png").write_bytes(b"garbage" * 9)
    with pytest.raises(DataError, match="a2.png"):
        list(ImageFolder(tmp_path))


def test_folder_pickles_and_lists_once(tmp_path, make_image):
    images = [make_image(tmp_path / f"f{i}.png") for i in range(3)]
    folder = ImageFolder(tmp_path, frame_interval_s=0.5)
    make_image(tmp_path / "f9.png")
    copy = pickle.loads(pickle.dumps(folder))
    frames = list(copy.frames())
    assert len(frames) == 3
    assert all(np.array_equal(f.observation, i) for f, i in zip(frames, images, strict=True))
    assert [f.time_s for f in frames] == [0.0, 0.5, 1.0]
