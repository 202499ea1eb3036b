"""The pictures' JPEG files: shrunk to the page's width keeping their shape, a clear error for what cannot be encoded."""

from __future__ import annotations

import cv2
import numpy as np
import pytest

from benchmark.errors import DataError
from benchmark.replay.jpeg import encode_jpeg, shrunk_to_width


def test_a_wide_image_is_shrunk_to_the_width_keeping_its_shape_and_a_narrow_one_is_kept() -> None:
    wide = np.zeros((300, 640, 3), np.uint8)
    assert shrunk_to_width(wide, 480).shape == (225, 480, 3)
    narrow = np.zeros((48, 64), np.uint8)
    assert shrunk_to_width(narrow, 480) is narrow


def test_an_image_encodes_as_a_jpeg_of_its_size() -> None:
    image = np.tile(np.arange(64, dtype=np.uint8), (48, 1))
    decoded = cv2.imdecode(np.frombuffer(encode_jpeg(image, "frame 2"), np.uint8), cv2.IMREAD_GRAYSCALE)
    assert decoded.shape == (48, 64) and np.abs(decoded.astype(int) - image).max() < 8


def test_an_image_that_cannot_be_encoded_is_refused_naming_it() -> None:
    with pytest.raises(DataError, match=r"frame 2: its image, a uint8 array of shape \(4, 4, 5\), cannot be encoded"):
        encode_jpeg(np.zeros((4, 4, 5), np.uint8), "frame 2")
