"""The sidecar of an image sequence file: frame interval, camera calibration and navigation file.

The image sequence file of the thesis holds the cable state and the image
of each frame, nothing else (``conventions.md`` section 2).  What a camera
tracker may also use goes into a TOML file beside it, the sequence file's
path with the suffix ``.toml`` (``S.txt`` -> ``S.toml``)::

    frame_interval_s = 0.04
    [camera]
    focal_px = 800.0
    pipe_diameter_m = 0.3
    tilt_deg = 30.0
    [navigation]
    file = "S.nav.csv"

Every part is optional.  The navigation file is relative to the sidecar: a
CSV file with the header ``frame,lateral_mps,vertical_mps,frontal_mps`` and
one row per frame, the :class:`~benchmark.modalities.camera.model.VehicleSpeeds`
of seeds/004 eq. (7).  This module writes the format; the camera readers
read it.
"""

from __future__ import annotations

import json
import math
from collections.abc import Iterable
from pathlib import Path

import pydantic

from benchmark.files import atomic_writer, write_text_atomically
from benchmark.modalities.camera.model import VehicleSpeeds
from benchmark.parameters import Positive

NAVIGATION_HEADER = "frame,lateral_mps,vertical_mps,frontal_mps"
"""The header row of a navigation file."""


@pydantic.dataclasses.dataclass(frozen=True)
class SidecarCamera:
    """The ``[camera]`` table, in the file's units: :class:`~benchmark.modalities.camera.model.CameraCalibration`.

    The fields are those of the calibration, the mounting tilt in degrees
    (``tilt_deg``) where the calibration holds radians (``nominal_tilt``);
    each is checked when the table is made.
    """

    focal_px: Positive
    pipe_diameter_m: Positive
    tilt_deg: pydantic.FiniteFloat


def sidecar_path(sequence_file: Path) -> Path:
    """Where the sidecar of ``sequence_file`` lives: the same path with the suffix ``.toml``."""
    return sequence_file.with_suffix(".toml")


def _number_text(value: float) -> str:
    # repr is the shortest text that reads back as the same float; valid TOML and CSV for finite values.
    if not math.isfinite(value):
        raise ValueError(f"{value!r} cannot be written to a sidecar")
    return repr(float(value))


def write_sidecar(
    sequence_file: Path,
    *,
    frame_interval_s: float | None = None,
    camera: SidecarCamera | None = None,
    navigation_file: str | None = None,
) -> Path:
    """Write the sidecar of ``sequence_file`` with the parts given.

    Parameters
    ----------
    sequence_file : pathlib.Path
        The image sequence file the sidecar belongs to.
    frame_interval_s : float, optional
        Time between frames in s.
    camera : SidecarCamera, optional
        The ``[camera]`` table.
    navigation_file : str, optional
        Name of the navigation file, relative to the sidecar.

    Returns
    -------
    pathlib.Path
        The sidecar, :func:`sidecar_path` of ``sequence_file``.

    Raises
    ------
    DataError
        If the file cannot be written, naming it.
    """
    lines = []
    if frame_interval_s is not None:
        lines.append(f"frame_interval_s = {_number_text(frame_interval_s)}")
    if camera is not None:
        lines += [
            "[camera]",
            f"focal_px = {_number_text(camera.focal_px)}",
            f"pipe_diameter_m = {_number_text(camera.pipe_diameter_m)}",
            f"tilt_deg = {_number_text(camera.tilt_deg)}",
        ]
    if navigation_file is not None:
        # A JSON string is a valid TOML basic string: the same escapes.
        lines += ["[navigation]", f"file = {json.dumps(navigation_file, ensure_ascii=False)}"]
    return write_text_atomically(sidecar_path(sequence_file), "".join(f"{line}\n" for line in lines), "sidecar")


def write_navigation_file(path: Path, speeds: Iterable[VehicleSpeeds]) -> Path:
    """Write one row of vehicle speeds per frame, from frame 0, under :data:`NAVIGATION_HEADER`.

    Raises
    ------
    DataError
        If the file cannot be written, naming it.

    References
    ----------
    seeds/004 eq. (7): ``(s_x, s_y, s_z)`` are the lateral, vertical and frontal speeds.
    """
    with atomic_writer(path, "navigation file") as handle:
        handle.write(NAVIGATION_HEADER + "\n")
        for frame, speed in enumerate(speeds):
            values = ",".join(_number_text(v) for v in (speed.lateral, speed.vertical, speed.frontal))
            handle.write(f"{frame},{values}\n")
    return path
