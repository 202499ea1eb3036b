"""Single image files: grey decoding, lossless PNG writing, and errors naming the file."""

from __future__ import annotations

import cv2
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis.extra import numpy as hnp

from benchmark.errors import DataError
from benchmark.modalities.camera.io.images import is_image_name, read_grey, size_of, write_png


@settings(max_examples=25, deadline=None)
@given(hnp.arrays(np.uint8, hnp.array_shapes(min_dims=2, max_dims=2, min_side=1, max_side=9)))
def test_png_round_trip_is_lossless(tmp_path_factory, image):
    path = tmp_path_factory.mktemp("png") / "x.png"
    write_png(path, image)
    assert np.array_equal(read_grey(path), image)


def test_size_is_width_then_height():
    assert size_of(np.zeros((3, 5), dtype=np.uint8)) == (5, 3)


def test_sixteen_bit_images_read_as_eight_bit_grey(tmp_path):
    deep = np.full((4, 6), 40000, dtype=np.uint16)
    assert cv2.imwrite(str(tmp_path / "deep.png"), deep)
    image = read_grey(tmp_path / "deep.png")
    assert image.dtype == np.uint8
    assert image.shape == (4, 6)


@pytest.mark.parametrize("kind", ["missing", "folder", "empty", "garbage"])
def test_unreadable_images_are_named_with_the_prefix(tmp_path, kind):
    path = tmp_path / "pic.png"
    if kind == "folder":
        path.mkdir()
    elif kind == "empty":
        path.write_bytes(b"")
    elif kind == "garbage":
        path.write_bytes(b"\x00\x01garbage" * 20)
    with pytest.raises(DataError, match=r"^seq.txt:7: .*pic.png"):
        read_grey(path, where="seq.txt:7: ")


@pytest.mark.parametrize(
    "image",
    [np.zeros((3, 4), dtype=np.float32), np.zeros((3, 4, 3), dtype=np.uint8), np.zeros((0, 4), dtype=np.uint8)],
)
def test_write_png_rejects_non_grey_images(tmp_path, image):
    with pytest.raises(DataError, match="frame 3: .*uint8 grey"):
        write_png(tmp_path / "x.png", image, where="frame 3: ")
    assert not (tmp_path / "x.png").exists()


def test_write_png_names_an_unwritable_file(tmp_path):
    with pytest.raises(DataError, match="no folder"):
        write_png(tmp_path / "no folder" / "x.png", np.zeros((2, 2), dtype=np.uint8))


def test_image_names_match_any_letter_case(tmp_path):
    assert is_image_name(tmp_path / "S1_000.DIB")
    assert is_image_name(tmp_path / "a.JpEg")
    assert not is_image_name(tmp_path / "a.txt")
    assert not is_image_name(tmp_path / "png")
