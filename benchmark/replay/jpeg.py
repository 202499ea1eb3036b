"""The frames' pictures as JPEG files: one quality for every view, images shrunk to the page's width."""

from __future__ import annotations

import cv2
import numpy as np

from benchmark.errors import DataError

JPEG_QUALITY = 70
"""OpenCV's JPEG quality (0-100) of the pictures."""


def encode_jpeg(image: np.ndarray, what: str) -> bytes:
    """``image`` (grey or BGR ``uint8``) as a JPEG file of quality :data:`JPEG_QUALITY`.

    Raises
    ------
    DataError
        When OpenCV cannot encode it, naming ``what`` (the frame) and the image's shape.
    """
    try:
        ok, encoded = cv2.imencode(".jpg", image, [cv2.IMWRITE_JPEG_QUALITY, JPEG_QUALITY])
    except cv2.error:
        ok = False
    if not ok:
        raise DataError(f"{what}: its image, a {image.dtype} array of shape {image.shape}, cannot be encoded as JPEG")
    return encoded.tobytes()


def shrunk_to_width(image: np.ndarray, width: int) -> np.ndarray:
    """``image`` downscaled (OpenCV's area interpolation) to ``width`` px wide if it is wider; as it is otherwise."""
    height, wide = image.shape[:2]
    if wide <= width:
        return image
    return cv2.resize(image, (width, max(1, round(height * width / wide))), interpolation=cv2.INTER_AREA)
