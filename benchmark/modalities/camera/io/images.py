"""Reading and writing single camera images.

A camera frame is a ``uint8`` grey image of shape ``(H, W)`` (see
:class:`benchmark.model.Frame`).  Files are read through OpenCV, so any format
it decodes is accepted, including the BMP/DIB images the thesis' sequences
were stored in (seeds/000, section 4.7.3; ``conventions.md`` section 2).
Colour images are converted to grey on reading.

Bytes are read with Python and decoded in memory, which keeps two failures
apart that :func:`cv2.imread` would merge: a file that is not there and a file
that is there but is not an image.  Each raises a
:class:`~benchmark.errors.DataError` naming the file.
"""

from __future__ import annotations

from pathlib import Path

import cv2
import numpy as np

from benchmark.errors import DataError

IMAGE_EXTENSIONS: frozenset[str] = frozenset(
    {".png", ".jpg", ".jpeg", ".bmp", ".dib", ".tif", ".tiff", ".pgm", ".pbm", ".pnm", ".ppm", ".webp"}
)
"""File name endings (lower case) of the image formats OpenCV reads."""


def is_image_name(path: Path) -> bool:
    """Whether a file name ends in one of :data:`IMAGE_EXTENSIONS` (any letter case)."""
    return path.suffix.lower() in IMAGE_EXTENSIONS


def read_grey(path: Path, *, where: str = "") -> np.ndarray:
    """Read an image file as a ``uint8`` grey image of shape ``(H, W)``.

    Parameters
    ----------
    path : pathlib.Path
        The image file; any format OpenCV decodes.
    where : str, optional
        Prefix for error messages that locates the image in its source, e.g.
        ``"seq.txt:12: "``.

    Returns
    -------
    numpy.ndarray
        The grey image; colour images are converted, deeper images are
        scaled to 8 bits by OpenCV.

    Raises
    ------
    DataError
        If the file does not exist, cannot be read, or is not an image
        OpenCV can decode.

    References
    ----------
    seeds/000, section 4.7.3; ``conventions.md`` section 2.
    """
    try:
        data = np.fromfile(path, dtype=np.uint8)
    except FileNotFoundError:
        raise DataError(f"{where}image {path} does not exist") from None
    except OSError as exc:
        raise DataError(f"{where}cannot read image {path}: {exc.strerror or exc}") from None
    image = None
    if data.size:
        try:
            image = cv2.imdecode(data, cv2.IMREAD_GRAYSCALE)
        except cv2.error:
            image = None
    if image is None or image.ndim != 2 or image.size == 0:
        raise DataError(f"{where}cannot decode image {path}: corrupt or not an image format OpenCV reads")
    if image.dtype != np.uint8:
        raise DataError(f"{where}image {path} decodes to {image.dtype}, not 8-bit grey")
    return image


def write_png(path: Path, image: np.ndarray, *, where: str = "") -> None:
    """Write a ``uint8`` grey image as a lossless PNG file.

    Parameters
    ----------
    path : pathlib.Path
        Destination; its folder must exist.
    image : numpy.ndarray
        ``uint8`` array of shape ``(H, W)``.
    where : str, optional
        Prefix for error messages that names the frame being written.

    Raises
    ------
    DataError
        If the image is not a grey ``uint8`` image or the file cannot be
        encoded or written.
    """
    array = np.asarray(image)
    if array.dtype != np.uint8 or array.ndim != 2 or array.size == 0:
        raise DataError(
            f"{where}cannot write {path}: expected a uint8 grey image (H, W), got {array.dtype} {array.shape}"
        )
    try:
        ok, encoded = cv2.imencode(".png", array)
    except cv2.error as exc:
        raise DataError(f"{where}cannot encode {path} as PNG: {exc}") from None
    if not ok:
        raise DataError(f"{where}cannot encode {path} as PNG")
    try:
        path.write_bytes(encoded.tobytes())
    except OSError as exc:
        raise DataError(f"{where}cannot write {path}: {exc.strerror or exc}") from None


def size_of(image: np.ndarray) -> tuple[int, int]:
    """The ``(W, H)`` of an image of shape ``(H, W)``."""
    height, width = image.shape[:2]
    return int(width), int(height)
