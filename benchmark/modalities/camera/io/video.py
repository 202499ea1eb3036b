"""A video file as an unlabelled camera sequence.

The thesis' test sequences are underwater videos recorded at camera rate
(25-30 Hz, seeds/000, section 5.1).  :class:`VideoFile` streams the frames of
any video OpenCV's :class:`cv2.VideoCapture` decodes, one at a time, each
converted to a ``uint8`` grey image.  A video has no ground truth: every
frame's truth is :data:`benchmark.modalities.camera.model.UNKNOWN_CABLE`.

The file is opened once when the object is made, to check that a first frame
decodes and to read the frame size, the frame rate and the container's frame
count; each call to :meth:`VideoFile.frames` opens it again.  The object
holds only the path and these numbers, so it pickles cheaply.  Its identity
is the resolved path and the file's size and modification time, taken then.
"""

from __future__ import annotations

import math
import os
from collections.abc import Iterable, Iterator
from pathlib import Path

import cv2
import numpy as np

from benchmark.errors import DataError
from benchmark.identity import DatasetIdentity, file_fingerprint, resolved_source
from benchmark.modalities.camera.io.images import size_of
from benchmark.modalities.camera.io.sidecar import read_sidecar
from benchmark.modalities.camera.model import UNKNOWN_CABLE, CameraTruth
from benchmark.model import Frame, Sequence, SequenceInfo

VIDEO_EXTENSIONS: frozenset[str] = frozenset({".avi", ".mp4", ".mkv", ".mov", ".mpg", ".mpeg", ".m4v", ".wmv"})
"""File name endings (lower case) that :func:`benchmark.io.open_sequence` opens as video."""


def to_grey(image: np.ndarray) -> np.ndarray:
    """Convert a decoded video frame (grey, BGR or BGRA) to a ``uint8`` grey image."""
    if image.ndim == 2:
        grey = image
    elif image.shape[2] == 1:
        grey = image[:, :, 0]
    elif image.shape[2] == 4:
        grey = cv2.cvtColor(image, cv2.COLOR_BGRA2GRAY)
    else:
        grey = cv2.cvtColor(image, cv2.COLOR_BGR2GRAY)
    if grey.dtype != np.uint8:
        grey = cv2.convertScaleAbs(grey, alpha=255.0 / float(np.iinfo(grey.dtype).max))
    return np.ascontiguousarray(grey)


def check_grey_image(image: object) -> None:
    """Raise ValueError unless ``image`` is a 2-D ``uint8`` array, as :func:`grey_image` returns, naming what it is."""
    if not isinstance(image, np.ndarray) or image.dtype != np.uint8 or image.ndim != 2 or image.size == 0:
        dtype, shape = getattr(image, "dtype", type(image).__name__), getattr(image, "shape", None)
        raise ValueError(f"expected a non-empty uint8 grey image of shape (H, W), got {dtype} of shape {shape}")


def grey_image(observation: object, min_size_px: int = 1) -> np.ndarray:
    """A camera observation as the ``uint8`` grey image of shape ``(H, W)`` that camera trackers read.

    A 2-D ``uint8`` array is returned as it is; ``(H, W, 1)``, ``(H, W, 3)``
    (BGR) and ``(H, W, 4)`` (BGRA) ``uint8`` arrays and 2-D ``uint16`` ones
    are converted with :func:`to_grey`.

    Raises
    ------
    ValueError
        For anything else (not an array, another dtype, floating-point or
        NaN pixels, another shape, an image smaller than ``min_size_px`` on
        a side), naming what it got.
    """
    if not isinstance(observation, np.ndarray):
        raise ValueError(f"expected a grey image as a numpy array, got {type(observation).__name__}")
    image = observation
    if image.dtype.kind == "f" and not np.all(np.isfinite(image)):
        raise ValueError(f"image of dtype {image.dtype} holds NaN or infinite pixels")
    colour = image.dtype == np.uint8 and image.ndim == 3 and image.shape[2] in (1, 3, 4)
    if image.size and (colour or (image.dtype == np.uint16 and image.ndim == 2)):
        image = to_grey(image)
    if image.dtype == np.uint8 and image.ndim == 2 and min(image.shape) < max(min_size_px, 1):
        raise ValueError(f"image of shape {image.shape} is smaller than {max(min_size_px, 1)} px on a side")
    check_grey_image(image)
    return image


def grey_frame(observation: object, where: str, min_size_px: int = 1) -> np.ndarray:
    """:func:`grey_image` for a tracker's ``step``: what it cannot read is a DataError naming ``where``.

    ``where`` names the tracker and the frame, e.g. ``"texture: frame 7"``.
    """
    try:
        return grey_image(observation, min_size_px)
    except ValueError as exc:
        raise DataError(f"{where}: {exc}") from exc


def _open(path: Path) -> cv2.VideoCapture:
    if not path.is_file():
        raise DataError(f"{path}: no such video file")
    capture = cv2.VideoCapture(os.fspath(path))
    if not capture.isOpened():
        capture.release()
        raise DataError(f"{path}: cannot open video (corrupt or a format OpenCV cannot decode)")
    return capture


class VideoFile(Sequence):
    """The frames of a video file, in grey, without ground truth.

    Parameters
    ----------
    path : str or path-like
        The video.  ``info.name`` is this path as given.

    Attributes
    ----------
    info.n_frames
        The container's frame count, or None where it does not say; some
        containers only estimate it.
    info.frame_interval_s
        The sidecar's ``frame_interval_s``, else ``1 / fps`` from the
        container, or None where neither says.
    info.calibration
        The sidecar's camera calibration, or None.

    The sidecar ``V.toml`` beside ``V.mp4``, where there is one, gives the
    calibration, the frame interval (the user's word over a container's,
    which may be wrong) and each frame's navigation
    (:mod:`benchmark.modalities.camera.io.sidecar`); it is part of the
    identity.

    Raises
    ------
    DataError
        If the file is missing, cannot be opened, or no frame decodes, or
        the sidecar is malformed (naming it and the key); later, if a frame has a different size than the first.

    References
    ----------
    seeds/000, section 5.1 and appendix A (video sequences as test data).
    """

    def __init__(self, path: str | os.PathLike[str]) -> None:
        self._name = os.fspath(path)
        self._path = Path(path).absolute()
        capture = _open(self._path)
        try:
            ok, first = capture.read()
            if not ok or first is None:
                raise DataError(f"{self._name}: no frame of the video can be decoded")
            count = capture.get(cv2.CAP_PROP_FRAME_COUNT)
            fps = capture.get(cv2.CAP_PROP_FPS)
        finally:
            capture.release()
        self._frame_size = size_of(first)
        self._n_frames = int(round(count)) if math.isfinite(count) and count > 0 else None
        # The container's count is an estimate for some formats: navigation columns are not held to it.
        self._sidecar = read_sidecar(path)
        container_interval = 1.0 / fps if math.isfinite(fps) and fps > 0 else None
        self._frame_interval_s = self._sidecar.frame_interval_s or container_interval
        fingerprint = self._sidecar.fingerprint_of(file_fingerprint(self._path))
        self._identity = DatasetIdentity(self._name, "camera", source=resolved_source(self._path), fingerprint=fingerprint)

    @property
    def path(self) -> Path:
        """The video file, absolute."""
        return self._path

    @property
    def identity(self) -> DatasetIdentity:
        """The video's resolved path, and its size and modification time when it was opened."""
        return self._identity

    @property
    def info(self) -> SequenceInfo:
        """Describe the video from what its container reports."""
        return SequenceInfo(
            name=self._name,
            modality="camera",
            n_frames=self._n_frames,
            frame_size=self._frame_size,
            frame_interval_s=self._frame_interval_s,
            calibration=self._sidecar.calibration,
            extra={"source": self._name},
        )

    def lacks(self, needs: Iterable[str]) -> dict[str, str]:
        """What a tracker needs that neither the sidecar nor the container gives, with the line to add."""
        given = {"calibration": self._sidecar.calibration, "frame_interval_s": self._frame_interval_s}
        return self._sidecar.lacks(needs, given)

    def frames(self) -> Iterator[Frame]:
        """Decode and yield the frames in order; ``time_s`` is index times the frame interval.

        Without a frame rate from the container, ``time_s`` counts frames.
        """
        capture = _open(self._path)
        interval = self._frame_interval_s
        truth = CameraTruth(cable=UNKNOWN_CABLE)
        navigation = self._sidecar.navigation
        try:
            index = 0
            while True:
                ok, image = capture.read()
                if not ok or image is None:
                    return
                grey = to_grey(image)
                if size_of(grey) != self._frame_size:
                    raise DataError(
                        f"{self._name}: frame {index} is {grey.shape[1]}x{grey.shape[0]} px, "
                        f"but the video's frames are {self._frame_size[0]}x{self._frame_size[1]} px"
                    )
                time_s = index * interval if interval is not None else float(index)
                yield Frame(index=index, observation=grey, truth=truth, navigation=navigation.get(index), time_s=time_s)
                index += 1
        finally:
            capture.release()

    def __repr__(self) -> str:
        return f"<VideoFile {self._name!r}>"
