"""A camera sequence backed by a list of image files.

Image sequence files (:mod:`benchmark.modalities.camera.io.sequence_file`) and image folders
(:mod:`benchmark.modalities.camera.io.image_folder`) are both a list of image paths with a
ground-truth cable state per image; they differ only in where the list comes
from.  :class:`ImageListSequence` holds that list and turns it into frames:
one image is decoded at a time, only while the frame is being produced, so
the object itself stays small and picklable and a sequence of any length
streams in constant memory.

Every image of a sequence must have the size of the first one; the first
image is read once to fill :attr:`SequenceInfo.frame_size` and its size is
cached.  The files carry no time stamps: a frame's ``time_s`` is its index
times ``frame_interval_s`` when one is given, and otherwise the index itself
(time counted in frames).

The sequence's :attr:`~ImageListSequence.identity` is fixed when it is made,
from the list's source and the size and modification time of every image
(:func:`benchmark.identity.file_fingerprint`): no image is opened for it,
so that naming a sequence never blocks on an image, and a copy sent to a
worker process keeps it.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Iterator
from pathlib import Path
from typing import Any

import numpy as np

from benchmark.errors import DataError
from benchmark.identity import DatasetIdentity, file_fingerprint, resolved_source
from benchmark.modalities.camera.io.images import read_grey, size_of
from benchmark.modalities.camera.io.sidecar import Sidecar, sidecar_path
from benchmark.modalities.camera.model import CableState, CameraTruth
from benchmark.model import Frame, Sequence, SequenceInfo


def check_frame_interval(frame_interval_s: float | None) -> float | None:
    """Validate an optional frame interval: ``None`` or a finite number > 0 (in s)."""
    if frame_interval_s is None:
        return None
    value = float(frame_interval_s)
    if not (math.isfinite(value) and value > 0):
        raise ValueError(f"frame_interval_s must be a finite number > 0, got {frame_interval_s!r}")
    return value


class ImageListSequence(Sequence):
    """Camera frames decoded one at a time from a list of image files.

    Parameters
    ----------
    name : str
        The sequence's name in results.
    source : pathlib.Path
        The file or folder the list was read from; reported in
        ``info.extra["source"]``.
    images : iterable of pathlib.Path
        Absolute image paths, in frame order.
    cables : iterable of CableState
        Ground truth per image (:data:`benchmark.modalities.camera.model.UNKNOWN_CABLE` where
        unlabelled), as many as ``images``.
    frame_interval_s : float, optional
        Time between frames in s, where the caller knows it.
    content : bytes, optional
        The bytes of ``source`` where it is a file the caller has read (an
        image sequence file); its identity hashes them.  Without them the
        size and modification time of ``source`` stand in.
    sidecar : Sidecar, optional
        What the sequence's sidecar says (:mod:`benchmark.modalities.camera.io.sidecar`):
        its calibration and navigation, and its frame interval where
        ``frame_interval_s`` is not given; it enters the identity.

    References
    ----------
    seeds/000, section 4.7.3 (image sequences as a tracker's input).
    """

    def __init__(
        self,
        name: str,
        source: Path,
        images: Iterable[Path],
        cables: Iterable[CableState],
        frame_interval_s: float | None = None,
        *,
        content: bytes | None = None,
        sidecar: Sidecar | None = None,
    ) -> None:
        self._name = name
        self._source = source
        self._images: tuple[Path, ...] = tuple(images)
        self._cables: tuple[CableState, ...] = tuple(cables)
        if len(self._images) != len(self._cables):
            raise ValueError(f"{len(self._images)} images but {len(self._cables)} cable states")
        self._sidecar = sidecar if sidecar is not None else Sidecar(sidecar_path(source))
        if frame_interval_s is None:
            frame_interval_s = self._sidecar.frame_interval_s
        self._frame_interval_s = check_frame_interval(frame_interval_s)
        self._frame_size: tuple[int, int] | None = None
        fingerprint = file_fingerprint(source, content=content, named=self._images)
        self._identity = DatasetIdentity(
            name, "camera", source=resolved_source(source), fingerprint=self._sidecar.fingerprint_of(fingerprint)
        )

    def _where(self, index: int) -> str:
        """Prefix for error messages about frame ``index``; subclasses add their location."""
        return f"{self._name}: frame {index}: "

    def _read(self, index: int) -> np.ndarray:
        return read_grey(self._images[index], where=self._where(index))

    @property
    def images(self) -> tuple[Path, ...]:
        """The image paths, in frame order."""
        return self._images

    @property
    def identity(self) -> DatasetIdentity:
        """The source resolved and the fingerprint of its content and images, as when the sequence was made."""
        return self._identity

    @property
    def info(self) -> SequenceInfo:
        """Describe the sequence; reads the first image once to learn the frame size."""
        if self._frame_size is None and self._images:
            self._frame_size = size_of(self._read(0))
        return SequenceInfo(
            name=self._name,
            modality="camera",
            n_frames=len(self._images),
            frame_size=self._frame_size,
            frame_interval_s=self._frame_interval_s,
            calibration=self._sidecar.calibration,
            extra={"source": str(self._source)},
        )

    def lacks(self, needs: Iterable[str]) -> dict[str, str]:
        """What a tracker needs that the sidecar would give and nothing does, with the line to add; no image is read."""
        given: dict[str, Any] = {"calibration": self._sidecar.calibration, "frame_interval_s": self._frame_interval_s}
        return self._sidecar.lacks(needs, given)

    def frames(self) -> Iterator[Frame]:
        """Yield the frames in order, decoding one image per frame.

        Raises
        ------
        DataError
            When an image is missing, cannot be decoded, or differs in size
            from the first image; the message names the image.
        """
        interval = self._frame_interval_s
        navigation = self._sidecar.navigation
        for index, (path, cable) in enumerate(zip(self._images, self._cables, strict=True)):
            image = self._read(index)
            size = size_of(image)
            if self._frame_size is None:
                self._frame_size = size
            elif size != self._frame_size:
                width, height = self._frame_size
                raise DataError(
                    f"{self._where(index)}image {path} is {size[0]}x{size[1]} px, "
                    f"but the sequence's frames are {width}x{height} px"
                )
            time_s = index * interval if interval is not None else float(index)
            truth = CameraTruth(cable=cable)
            yield Frame(index=index, observation=image, truth=truth, navigation=navigation.get(index), time_s=time_s)

    def __len__(self) -> int:
        return len(self._images)

    def __repr__(self) -> str:
        return f"<{type(self).__name__} {self._name!r}>"
