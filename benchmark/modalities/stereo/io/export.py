"""Export a stereo sequence of image pairs as a stereo folder (:mod:`benchmark.modalities.stereo.io.folder`).

For a stem ``stem`` it writes::

    out/<stem>/left/frame_00000.png    lossless PNG, the left image
    out/<stem>/right/frame_00000.png   the right image
    out/<stem>/navigation.csv          CH's navigation, frames that have it
    out/<stem>/targets.csv             the truth, frames that have it
    out/<stem>.toml                    frame interval and [camera]

Numbers are written as the shortest text that reads back as the same float,
so a rendered ``stereo-images`` sequence read back gives the same frames,
truth, navigation and calibration bit for bit.  It is the stereo modality's
exporter (``trackbench make-dataset``); a sequence of simulated
measurements (the ``stereo`` suites) has no images and is refused.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Iterable
from pathlib import Path

import cv2
import numpy as np

from benchmark.errors import DataError
from benchmark.files import atomic_writer, make_folder, write_bytes_atomically, write_text_atomically
from benchmark.modalities.stereo.io.folder import (
    NAVIGATION_COLUMNS,
    NAVIGATION_FILE,
    SIDES,
    TARGET_COLUMNS,
    TARGET_FILE,
)
from benchmark.modalities.stereo.model import ChaseNavigation, StereoCalibration, StereoTruth
from benchmark.model import Frame, Sequence
from benchmark.sidecar import number_text, sidecar_path


def _png(image: object, where: str) -> bytes:
    array = np.asarray(image)
    if array.dtype != np.uint8 or array.ndim != 3 or array.shape[2] != 3 or array.size == 0:
        raise DataError(f"{where}expected uint8 BGR images (H, W, 3), got {array.dtype} {array.shape}")
    ok, encoded = cv2.imencode(".png", array)
    if not ok:
        raise DataError(f"{where}cannot encode the image as PNG")
    return encoded.tobytes()


def _pair(frame: Frame, where: str) -> tuple[object, object]:
    observation = frame.observation
    if not (isinstance(observation, tuple | list) and len(observation) == 2):
        raise DataError(
            f"{where}the observation is a {type(observation).__name__}, not an image pair (left, right); "
            "only stereo sequences of images can be exported"
        )
    return observation[0], observation[1]


def _navigation_row(navigation: object) -> tuple[float, ...] | None:
    if not isinstance(navigation, ChaseNavigation):
        return None
    return (*navigation.position_m, navigation.heading)


def _target_row(truth: object) -> tuple[float, ...] | None:
    if not isinstance(truth, StereoTruth):
        return None
    return (*truth.target.position_m, *truth.target.velocity_mps, *truth.chase_position_m, truth.chase_heading)


def _write_csv(path: Path, columns: tuple[str, ...], rows: Iterable[tuple[int, tuple[float, ...]]]) -> None:
    with atomic_writer(path, "CSV file") as handle:
        handle.write(",".join(columns) + "\n")
        for frame, values in rows:
            handle.write(",".join([str(frame), *(number_text(value) for value in values)]) + "\n")


def _sidecar_text(frame_interval_s: float | None, calibration: object) -> str:
    lines = [] if frame_interval_s is None else [f"frame_interval_s = {number_text(frame_interval_s)}"]
    if isinstance(calibration, StereoCalibration):
        lines.append("[camera]")
        for key, value in dataclasses.asdict(calibration).items():
            lines.append(f"{key} = {value if isinstance(value, int) else number_text(value)}")
    return "".join(f"{line}\n" for line in lines)


def export_stereo_sequence(sequence: Sequence, out: Path, stem: str) -> Path:
    """Write a stereo sequence of image pairs as a stereo folder ``out/<stem>`` with its sidecar ``out/<stem>.toml``.

    Parameters
    ----------
    sequence : Sequence
        A stereo sequence whose observations are pairs of ``uint8`` BGR images.
    out : pathlib.Path
        Folder to write into; created if missing.
    stem : str
        Name of the stereo folder and of its sidecar.

    Returns
    -------
    pathlib.Path
        The stereo folder, which :func:`benchmark.io.open_sequence` opens.

    Raises
    ------
    DataError
        If an observation is not an image pair of ``uint8`` BGR images, the
        sequence has no frames, or a file cannot be written, naming it.

    References
    ----------
    seeds/002, section 4.1 (image pairs) and eq. (15) (the calibration).
    """
    info = sequence.info
    folder = make_folder(make_folder(out) / stem)
    sides = [make_folder(folder / side) for side in SIDES]
    navigation: list[tuple[int, tuple[float, ...]]] = []
    targets: list[tuple[int, tuple[float, ...]]] = []
    count = -1
    for count, frame in enumerate(sequence.frames()):
        where = f"{info.name}: frame {frame.index}: "
        for side, image in zip(sides, _pair(frame, where), strict=True):
            write_bytes_atomically(side / f"frame_{count:05d}.png", _png(image, where), "image")
        for rows, row in ((navigation, _navigation_row(frame.navigation)), (targets, _target_row(frame.truth))):
            if row is not None:
                rows.append((count, row))
    if count < 0:
        raise DataError(f"{info.name}: the sequence has no frames to export")
    _write_csv(folder / NAVIGATION_FILE, NAVIGATION_COLUMNS, navigation)
    _write_csv(folder / TARGET_FILE, TARGET_COLUMNS, targets)
    write_text_atomically(sidecar_path(folder), _sidecar_text(info.frame_interval_s, info.calibration), "sidecar")
    return folder
