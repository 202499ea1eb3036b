"""Shared helpers for the camera-data reader and writer tests: tiny image files."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

import cv2
import numpy as np
import pytest

ImageMaker = Callable[..., np.ndarray]


@pytest.fixture
def make_image() -> ImageMaker:
    """Write a small random grey PNG (or any OpenCV format, by the name's ending) and return its pixels."""
    rng = np.random.default_rng(20240611)

    def make(path: Path, width: int = 12, height: int = 8) -> np.ndarray:
        path.parent.mkdir(parents=True, exist_ok=True)
        image = rng.integers(0, 256, size=(height, width), dtype=np.uint8)
        assert cv2.imwrite(str(path), image)
        return image

    return make
