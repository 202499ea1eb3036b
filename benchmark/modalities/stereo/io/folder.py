"""A stereo folder on disk: left and right images, CH's navigation and TG's truth, calibration beside it.

A user's stereo pairs, so that the stereo trackers run on them, lie in a
folder ``DIR/``::

    DIR/left/0001.png        the left image of each frame
    DIR/right/0001.png       the right image, under the same name
    DIR/navigation.csv       optional: CH's GPS and compass per frame
    DIR/targets.csv          optional: the truth per frame
    DIR.toml                 the sidecar, beside the folder

Frames are the image names of ``left/`` in natural order (``2.png`` before
``10.png``); ``right/`` must hold the same names.  Each frame's observation
is the pair ``(left, right)`` of ``uint8`` BGR images ``(H, W, 3)``,
exactly what a rendered ``stereo-images`` sequence holds
(:mod:`benchmark.modalities.stereo.scenes.images`), so the trackers' image
front end (:mod:`benchmark.modalities.stereo.frontend`) measures them.

The sidecar ``DIR.toml`` (:func:`benchmark.sidecar.sidecar_path`, the
camera's rule) holds the frame interval and the stereo camera in the
vocabulary of a ``stereo-images`` suite's ``[camera]`` table
(:class:`~benchmark.modalities.stereo.scenes.spec.StereoCameraSpec`; seeds/002,
Tables 3-4 and eq. 15)::

    frame_interval_s = 0.1
    [camera]
    focal_px = 140.8
    baseline_m = 0.12
    width_px = 320               # the images' width
    principal_left_px = 159.5    # C_y; omitted: the image centre
    principal_right_px = 159.5   # C_y*
    range_limit_m = 16.0
    correlation_accuracy_px = 0.11

A key left out of ``[camera]`` takes the value a suite file would (seeds/002,
Table 4); without ``[camera]`` the sequence has no calibration and the
stereo trackers say so before they run.  The CSV files have the headers
:data:`NAVIGATION_COLUMNS` and :data:`TARGET_COLUMNS`, one row per frame
index from 0; positions North-East in m, velocities in m/s, headings in rad
clockwise from north (``conventions.md``; seeds/002, eq. 10 and Fig. 3).  A
frame without a navigation row has no navigation (a tracker that measures
the target there stops with an error naming the frame), and one without a
target row no truth: it is not scored.

Images are decoded one pair at a time while frames are produced.  The
folder's identity hashes the sidecar and both CSV files and takes the
names, sizes and modification times of the images.  Every problem is a
:class:`~benchmark.errors.DataError` naming the file and, for the sidecar,
the key's path, for a CSV file the line.
"""

from __future__ import annotations

import hashlib
import os
from collections.abc import Iterable, Iterator
from pathlib import Path
from typing import Annotated, Any

import cv2
import numpy as np
import pydantic
from annotated_types import Ge

from benchmark.errors import DataError
from benchmark.identity import DatasetIdentity, digest, file_fingerprint, resolved_source
from benchmark.io import read_regular_file
from benchmark.modalities.camera.io.image_folder import natural_key
from benchmark.modalities.camera.io.images import IMAGE_EXTENSIONS, is_image_name
from benchmark.modalities.stereo.model import (
    ChaseNavigation,
    StereoFrame,
    StereoTruth,
    TargetEstimate,
)
from benchmark.modalities.stereo.scenes.spec import StereoCameraSpec
from benchmark.model import Frame, Sequence, SequenceInfo
from benchmark.scenes.spec import SPEC_CONFIG, Positive
from benchmark.sidecar import read_frame_csv, read_toml_table, sidecar_path

SIDES = ("left", "right")
"""The sub-folders of a stereo folder, which tell it apart from a plain image folder."""

NAVIGATION_FILE, TARGET_FILE = "navigation.csv", "targets.csv"
"""The optional CSV files inside a stereo folder."""

NAVIGATION_COLUMNS = ("frame", "north_m", "east_m", "heading_rad")
"""The header of ``navigation.csv``: CH's GPS position and compass heading (:class:`ChaseNavigation`)."""

TARGET_COLUMNS = (
    "frame",
    "north_m",
    "east_m",
    "north_mps",
    "east_mps",
    "chase_north_m",
    "chase_east_m",
    "chase_heading_rad",
)
"""The header of ``targets.csv``: TG's position and velocity, CH's true pose (:class:`StereoTruth`)."""

FrameIndex = Annotated[int, Ge(0)]


@pydantic.dataclasses.dataclass(frozen=True, config=SPEC_CONFIG)
class StereoSidecarTable:
    """A stereo folder's sidecar: frame interval in s and the ``[camera]`` table of a suite file."""

    frame_interval_s: Positive | None = None
    camera: StereoCameraSpec | None = None


@pydantic.dataclasses.dataclass(frozen=True)
class NavigationRow:
    """One row of ``navigation.csv``; CSV text is converted by type."""

    frame: FrameIndex
    north_m: pydantic.FiniteFloat
    east_m: pydantic.FiniteFloat
    heading_rad: pydantic.FiniteFloat

    def navigation(self) -> ChaseNavigation:
        return ChaseNavigation(position_m=(self.north_m, self.east_m), heading=self.heading_rad)


@pydantic.dataclasses.dataclass(frozen=True)
class TargetRow:
    """One row of ``targets.csv``; CSV text is converted by type."""

    frame: FrameIndex
    north_m: pydantic.FiniteFloat
    east_m: pydantic.FiniteFloat
    north_mps: pydantic.FiniteFloat
    east_mps: pydantic.FiniteFloat
    chase_north_m: pydantic.FiniteFloat
    chase_east_m: pydantic.FiniteFloat
    chase_heading_rad: pydantic.FiniteFloat

    def truth(self) -> StereoTruth:
        target = TargetEstimate((self.north_m, self.east_m), (self.north_mps, self.east_mps))
        return StereoTruth(target, (self.chase_north_m, self.chase_east_m), self.chase_heading_rad)


def read_bgr(path: Path, where: str) -> np.ndarray:
    """An image file as ``uint8`` BGR ``(H, W, 3)``; grey images are converted.

    Raises
    ------
    DataError
        Prefixed by ``where``: the file is missing, unreadable or not an
        image OpenCV decodes to 8 bits.
    """
    data = np.frombuffer(read_regular_file(path, "image"), dtype=np.uint8)
    try:
        image = cv2.imdecode(data, cv2.IMREAD_COLOR) if data.size else None
    except cv2.error:
        image = None
    if image is None or image.dtype != np.uint8:
        raise DataError(f"{where}cannot decode image {path}: corrupt or not an 8-bit image OpenCV reads")
    return image


class StereoFolder(Sequence):
    """The image pairs of a stereo folder, with its sidecar's calibration and its CSV files' navigation and truth.

    Parameters
    ----------
    path : str or path-like
        The folder ``DIR``.  ``info.name`` is this path as given.

    Raises
    ------
    DataError
        When made: the folder or ``left/`` is missing, ``left/`` holds no
        image, an image of ``left/`` has no partner in ``right/`` (or the
        other way round), the sidecar or a CSV file is malformed; later,
        while iterating, for a corrupt image, a pair of two sizes, a frame
        of another size than the first, or images whose width is not the
        calibration's ``width_px``.

    References
    ----------
    seeds/002, section 4.1 (the field system's image pairs) and eq. (15).
    """

    def __init__(self, path: str | os.PathLike[str]) -> None:
        folder = Path(path)
        self._name = os.fspath(path)
        self._folder = folder
        names = _pair_names(folder)
        self._pairs = tuple(tuple(folder / side / name for side in SIDES) for name in names)
        n_frames = len(names)
        self._sidecar_path = sidecar_path(folder)
        table, sidecar_bytes = (
            read_toml_table(self._sidecar_path, StereoSidecarTable)
            if self._sidecar_path.exists()
            else (StereoSidecarTable(), b"")
        )
        self._frame_interval_s = table.frame_interval_s
        self._camera = table.camera
        self._calibration = table.camera.calibration() if table.camera is not None else None
        navigation, navigation_bytes = _frame_csv(folder / NAVIGATION_FILE, NavigationRow, NAVIGATION_COLUMNS, n_frames)
        targets, target_bytes = _frame_csv(folder / TARGET_FILE, TargetRow, TARGET_COLUMNS, n_frames)
        self._navigation = {frame: row.navigation() for frame, row in navigation.items()}
        self._truth = {frame: row.truth() for frame, row in targets.items()}
        self._frame_size: tuple[int, int] | None = None
        images = [image for pair in self._pairs for image in pair]
        # The folder's own size and mtime change with any file added to it; its images are its content.
        own = file_fingerprint(folder, content=b"", named=images)
        parts = (sidecar_bytes, navigation_bytes, target_bytes)
        fingerprint = digest(own, *(hashlib.sha256(part).hexdigest() for part in parts))
        self._identity = DatasetIdentity(self._name, "stereo", source=resolved_source(folder), fingerprint=fingerprint)

    @property
    def identity(self) -> DatasetIdentity:
        """The folder resolved, and the fingerprint of its images, sidecar and CSV files as when it was opened."""
        return self._identity

    @property
    def info(self) -> SequenceInfo:
        """Describe the sequence; reads the first pair once to learn the frame size."""
        if self._frame_size is None:
            self._frame_size = _size(self._pair(0)[0])
        return SequenceInfo(
            name=self._name,
            modality="stereo",
            n_frames=len(self._pairs),
            frame_size=self._frame_size,
            frame_interval_s=self._frame_interval_s,
            calibration=self._calibration,
            extra={"source": str(self._folder)},
        )

    def lacks(self, needs: Iterable[str]) -> dict[str, str]:
        """What a tracker needs that the sidecar would give and does not, with the line to add; no image is read."""
        remedies = {
            "calibration": (self._calibration, f"stereo calibration: add a [camera] table to {self._sidecar_path}"),
            "frame_interval_s": (
                self._frame_interval_s,
                f"frame interval: add frame_interval_s (s) at the top of {self._sidecar_path}",
            ),
        }
        return {need: remedies[need][1] for need in needs if need in remedies and remedies[need][0] is None}

    def _pair(self, index: int) -> tuple[np.ndarray, np.ndarray]:
        where = f"{self._name}: frame {index}: "
        left, right = (read_bgr(path, where) for path in self._pairs[index])
        if left.shape != right.shape:
            raise DataError(
                f"{where}the right image {self._pairs[index][1]} is {_size_text(right)} px, "
                f"but the left image is {_size_text(left)} px"
            )
        if self._camera is not None and left.shape[1] != self._camera.width_px:
            raise DataError(
                f"{self._sidecar_path}: camera.width_px: is {self._camera.width_px}, "
                f"but the images of {self._name} are {left.shape[1]} px wide ({self._pairs[index][0]})"
            )
        return left, right

    def frames(self) -> Iterator[StereoFrame]:
        """Yield each frame: the image pair, its truth or None, CH's navigation or None.

        Raises
        ------
        DataError
            For a missing or corrupt image, a pair of two sizes, a frame of
            another size than the first, or a width other than the
            calibration's, naming the image.
        """
        interval = self._frame_interval_s
        for index in range(len(self._pairs)):
            pair = self._pair(index)
            size = _size(pair[0])
            if self._frame_size is None:
                self._frame_size = size
            elif size != self._frame_size:
                raise DataError(
                    f"{self._name}: frame {index}: image {self._pairs[index][0]} is {size[0]}x{size[1]} px, "
                    f"but the sequence's frames are {self._frame_size[0]}x{self._frame_size[1]} px"
                )
            yield Frame(
                index=index,
                observation=pair,
                truth=self._truth.get(index),
                navigation=self._navigation.get(index),
                time_s=index * interval if interval is not None else float(index),
            )

    def __len__(self) -> int:
        return len(self._pairs)

    def __repr__(self) -> str:
        return f"<{type(self).__name__} {self._name!r}>"


def _size(image: np.ndarray) -> tuple[int, int]:
    return int(image.shape[1]), int(image.shape[0])


def _size_text(image: np.ndarray) -> str:
    width, height = _size(image)
    return f"{width}x{height}"


def _image_names(folder: Path) -> list[str]:
    try:
        return [entry.name for entry in folder.iterdir() if is_image_name(entry) and entry.is_file()]
    except OSError as exc:
        raise DataError(f"{folder}: cannot list image folder: {exc.strerror or exc}") from None


def _pair_names(folder: Path) -> list[str]:
    """The image names of ``left/``, in natural order, each with its partner in ``right/``."""
    if not folder.is_dir():
        raise DataError(f"{folder}: no such stereo folder")
    for side in SIDES:
        if not (folder / side).is_dir():
            raise DataError(f"{folder / side}: missing; a stereo folder holds the folders {' and '.join(SIDES)}")
    left, right = (set(_image_names(folder / side)) for side in SIDES)
    if not left:
        endings = " ".join(sorted(IMAGE_EXTENSIONS))
        raise DataError(f"{folder / 'left'}: no image files in folder (looked for {endings})")
    for name in sorted(left ^ right, key=natural_key):
        has, lacks = ("left", "right") if name in left else ("right", "left")
        raise DataError(f"{folder / lacks / name}: missing; the {lacks} image of {folder / has / name}")
    return sorted(left, key=natural_key)


def _frame_csv(
    file: Path, row_type: type[Any], columns: tuple[str, ...], n_frames: int
) -> tuple[dict[int, Any], bytes]:
    """The rows by frame of an optional CSV file of the folder, and its bytes (empty without the file)."""
    if not file.exists():
        return {}, b""
    content = read_regular_file(file, "CSV file")
    return read_frame_csv(file, content, row_type, columns, n_frames), content
