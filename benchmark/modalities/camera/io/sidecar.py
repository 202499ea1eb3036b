"""What a camera sequence on disk knows about itself: the optional sidecar beside it.

An image sequence file (``conventions.md`` section 2) lists images and
their ground truth and nothing else, and it stays exactly the thesis'
format.  What a tracker may also need (seeds/004: the camera's focal length,
the pipe's diameter and the mounting tilt, eq. 3 and section V; the frame
interval ``tau`` and the vehicle's speeds of eq. 7) comes from a TOML file
beside the data, its *sidecar*: the sequence's path with its suffix
replaced by ``.toml`` (``S.txt`` -> ``S.toml``, ``V.mp4`` -> ``V.toml``), and
for an image folder ``DIR/`` the file ``DIR.toml`` beside the folder::

    frame_interval_s = 0.04
    [camera]
    focal_px = 800.0          # f / delta_x of eq. 3, > 0
    pipe_diameter_m = 0.3     # > 0
    tilt_deg = 30.0           # the mount tilt phi_0, in (-90, 90) degrees
    [navigation]
    file = "S.nav.csv"        # relative to the sidecar

Every key is optional, but ``[camera]`` holds all three or none.  The
navigation is either a CSV file with the header
``frame,lateral_mps,vertical_mps,frontal_mps`` and one row per frame index
(a frame without a row has no navigation), or the same speeds as columns
inside the table (``lateral_mps = [...]``, ``vertical_mps = [...]``,
``frontal_mps = [...]``, one value per frame).  The speeds are
:class:`~benchmark.modalities.camera.model.VehicleSpeeds`, in m/s, in the
vehicle frame of seeds/004 eq. (7).

The tables are declared as pydantic dataclasses in the vocabulary of scene
specs (:mod:`benchmark.scenes.spec`), so a key the format does not know, a
value of the wrong type or out of its range is one
:class:`~benchmark.errors.DataError` naming the sidecar, the key's path and
the rule; a malformed CSV row names the CSV file and its line.

The sidecar is part of what the data is: its bytes and the navigation
file's enter the sequence's fingerprint (:meth:`Sidecar.fingerprint_of`),
so an edited sidecar is another dataset to ``--resume``, while a sequence
without one keeps the fingerprint it always had.  :func:`write_sidecar` and
:func:`write_navigation_file` write the format (``trackbench import``).
"""

from __future__ import annotations

import hashlib
import json
import math
import os
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Annotated, Any

import pydantic
from annotated_types import Ge, Interval

from benchmark.errors import DataError
from benchmark.files import atomic_writer, write_text_atomically
from benchmark.identity import digest
from benchmark.io import read_regular_file
from benchmark.modalities.camera.model import CameraCalibration, VehicleSpeeds
from benchmark.scenes.spec import SPEC_CONFIG, Finite, Name, Positive
from benchmark.sidecar import number_text, read_frame_csv, read_toml_table, sidecar_path

NAVIGATION_COLUMNS = ("frame", "lateral_mps", "vertical_mps", "frontal_mps")
"""The header of a navigation CSV file, in this order."""

Tilt = Annotated[Finite, Interval(gt=-90, lt=90)]
"""A mounting tilt in degrees, within ``(-90, 90)``."""


@pydantic.dataclasses.dataclass(frozen=True, config=SPEC_CONFIG)
class CameraTable:
    """The ``[camera]`` table: what :class:`~benchmark.modalities.camera.model.CameraCalibration` holds, tilt in degrees."""

    focal_px: Positive
    pipe_diameter_m: Positive
    tilt_deg: Tilt

    def calibration(self) -> CameraCalibration:
        """The calibration, the tilt turned into radians as ``CameraCalibration.nominal_tilt`` takes it."""
        return CameraCalibration(self.focal_px, self.pipe_diameter_m, math.radians(self.tilt_deg))


@pydantic.dataclasses.dataclass(frozen=True, config=SPEC_CONFIG)
class NavigationTable:
    """The ``[navigation]`` table: a CSV file, or one column of speeds per axis."""

    file: Name | None = None
    lateral_mps: tuple[Finite, ...] | None = None
    vertical_mps: tuple[Finite, ...] | None = None
    frontal_mps: tuple[Finite, ...] | None = None

    def __post_init__(self) -> None:
        columns = self.columns()
        given = [name for name, column in columns.items() if column is not None]
        if self.file is not None and given:
            raise ValueError(f"give either file or the columns, not both (columns given: {', '.join(given)})")
        if self.file is None and len(given) != len(columns):
            raise ValueError(f"give file, or all of {', '.join(columns)}")
        lengths = {len(column) for column in columns.values() if column is not None}
        if len(lengths) > 1:
            counts = ", ".join(f"{name} {len(column)}" for name, column in columns.items() if column is not None)
            raise ValueError(f"the columns must be equally long, got {counts}")

    def columns(self) -> dict[str, tuple[float, ...] | None]:
        """The speed columns by key, None where not given."""
        return {"lateral_mps": self.lateral_mps, "vertical_mps": self.vertical_mps, "frontal_mps": self.frontal_mps}


@pydantic.dataclasses.dataclass(frozen=True, config=SPEC_CONFIG)
class SidecarTable:
    """A whole sidecar file."""

    frame_interval_s: Positive | None = None
    camera: CameraTable | None = None
    navigation: NavigationTable | None = None


@pydantic.dataclasses.dataclass(frozen=True)
class NavigationRow:
    """One data row of a navigation CSV file; CSV text is converted by type."""

    frame: Annotated[int, Ge(0)]
    lateral_mps: pydantic.FiniteFloat
    vertical_mps: pydantic.FiniteFloat
    frontal_mps: pydantic.FiniteFloat

    def speeds(self) -> VehicleSpeeds:
        return VehicleSpeeds(self.lateral_mps, self.vertical_mps, self.frontal_mps)


_REMEDIES: dict[str, str] = {
    "calibration": "camera calibration: add focal_px, pipe_diameter_m, tilt_deg under [camera] in {path}",
    "frame_interval_s": "frame interval: add frame_interval_s (s) at the top of {path}",
}
"""The :class:`~benchmark.model.SequenceInfo` fields a sidecar gives, with the line that adds each."""


@dataclass(frozen=True)
class Sidecar:
    """What a sidecar told about its sequence; :data:`NO_SIDECAR` where there is none.

    Attributes
    ----------
    path : pathlib.Path
        Where the sidecar is, or would be.
    frame_interval_s : float or None
        Time between frames in s.
    calibration : CameraCalibration or None
        The camera and the pipe, the tilt in radians.
    navigation : Mapping
        Frame index to :class:`~benchmark.modalities.camera.model.VehicleSpeeds`;
        a frame not in it has no navigation.
    content_digest : str or None
        A digest of the sidecar's bytes and of its navigation file's; None
        without a sidecar.
    """

    path: Path
    frame_interval_s: float | None = None
    calibration: CameraCalibration | None = None
    navigation: Mapping[int, VehicleSpeeds] = field(default_factory=dict)
    content_digest: str | None = None

    def fingerprint_of(self, fingerprint: str) -> str:
        """The fingerprint of the sequence with this sidecar: ``fingerprint`` itself when there is no sidecar."""
        return fingerprint if self.content_digest is None else digest(fingerprint, "sidecar", self.content_digest)

    def lacks(self, needs: Iterable[str], given: Mapping[str, Any]) -> dict[str, str]:
        """Of the :class:`~benchmark.model.SequenceInfo` fields ``needs``, those a sidecar would give but nothing does.

        Parameters
        ----------
        needs : iterable of str
            Field names a tracker needs.
        given : Mapping
            The values the sequence has for the fields a sidecar gives
            (a video's frame interval may come from its container).

        Returns
        -------
        dict
            Field name to what is missing and the line that adds it (see
            :meth:`benchmark.model.Sequence.lacks`).
        """
        return {
            need: _REMEDIES[need].format(path=self.path)
            for need in needs
            if need in _REMEDIES and given.get(need) is None
        }


def read_sidecar(path: str | os.PathLike[str], n_frames: int | None = None) -> Sidecar:
    """Read the sidecar of the sequence at ``path``, if it has one.

    Parameters
    ----------
    path : str or path-like
        The sequence: an image sequence file, a video, an image folder.
    n_frames : int, optional
        The sequence's frame count where it is certain: the navigation's
        columns must then have one value per frame, and a CSV row no frame
        index beyond it.

    Returns
    -------
    Sidecar
        What it says; an empty :class:`Sidecar` when there is no sidecar
        file (or the sequence file is itself named ``*.toml``).

    Raises
    ------
    DataError
        Naming the sidecar and the key: not valid TOML, an unknown key, a
        value of the wrong type or out of its range, a missing or
        unreadable navigation file; naming the navigation file and the
        line: a wrong header, a malformed row, a frame index twice or
        beyond the sequence.
    """
    where = sidecar_path(path)
    if not where.exists() or where.absolute() == Path(path).absolute():
        return Sidecar(where)
    table, content = read_toml_table(where, SidecarTable)
    hashes = [hashlib.sha256(content).hexdigest()]
    navigation: dict[int, VehicleSpeeds] = {}
    if table.navigation is not None:
        navigation, navigation_bytes = _navigation(where, table.navigation, n_frames)
        hashes.append(hashlib.sha256(navigation_bytes).hexdigest())
    return Sidecar(
        path=where,
        frame_interval_s=table.frame_interval_s,
        calibration=table.camera.calibration() if table.camera is not None else None,
        navigation=navigation,
        content_digest=digest(hashes),
    )


def _navigation(where: Path, table: NavigationTable, n_frames: int | None) -> tuple[dict[int, VehicleSpeeds], bytes]:
    """The speeds by frame index of a ``[navigation]`` table, and the bytes they were read from (for the digest)."""
    if table.file is None:
        lateral, vertical, frontal = (column or () for column in table.columns().values())
        if n_frames is not None and len(lateral) != n_frames:
            raise DataError(
                f"{where}: navigation: the columns hold {len(lateral)} values, but the sequence has {n_frames} frames"
            )
        speeds = {index: VehicleSpeeds(*values) for index, values in enumerate(zip(lateral, vertical, frontal))}
        return speeds, b""
    file = where.parent / table.file
    try:
        content = read_regular_file(file, "navigation file")
    except DataError as exc:
        raise DataError(f"{where}: navigation.file: {exc}") from None
    return read_navigation_csv(file, content, n_frames), content


def read_navigation_csv(file: Path, content: bytes, n_frames: int | None = None) -> dict[int, VehicleSpeeds]:
    """The speeds by frame index in the bytes ``content`` of the navigation CSV file ``file``.

    Raises
    ------
    DataError
        Naming the file and the line: not UTF-8 text, a header other than
        :data:`NAVIGATION_COLUMNS`, a row of another length, a value that
        is not a finite number or a frame index that is not an integer
        >= 0, a frame index twice or (with ``n_frames``) beyond the sequence.
    """
    rows = read_frame_csv(file, content, NavigationRow, NAVIGATION_COLUMNS, n_frames)
    return {frame: row.speeds() for frame, row in rows.items()}


def write_sidecar(
    sequence_file: Path,
    *,
    frame_interval_s: float | None = None,
    camera: CameraTable | None = None,
    navigation_file: str | None = None,
) -> Path:
    """Write the sidecar of ``sequence_file`` with the parts given.

    Parameters
    ----------
    sequence_file : pathlib.Path
        The image sequence file the sidecar belongs to.
    frame_interval_s : float, optional
        Time between frames in s.
    camera : CameraTable, optional
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
        lines.append(f"frame_interval_s = {number_text(frame_interval_s)}")
    if camera is not None:
        lines += [
            "[camera]",
            f"focal_px = {number_text(camera.focal_px)}",
            f"pipe_diameter_m = {number_text(camera.pipe_diameter_m)}",
            f"tilt_deg = {number_text(camera.tilt_deg)}",
        ]
    if navigation_file is not None:
        # A JSON string is a valid TOML basic string: the same escapes.
        lines += ["[navigation]", f"file = {json.dumps(navigation_file, ensure_ascii=False)}"]
    return write_text_atomically(sidecar_path(sequence_file), "".join(f"{line}\n" for line in lines), "sidecar")


def write_navigation_file(path: Path, speeds: Iterable[VehicleSpeeds]) -> Path:
    """Write one row of vehicle speeds per frame, from frame 0, under the header :data:`NAVIGATION_COLUMNS`.

    Raises
    ------
    DataError
        If the file cannot be written, naming it.

    References
    ----------
    seeds/004 eq. (7): ``(s_x, s_y, s_z)`` are the lateral, vertical and frontal speeds.
    """
    with atomic_writer(path, "navigation file") as handle:
        handle.write(",".join(NAVIGATION_COLUMNS) + "\n")
        for frame, speed in enumerate(speeds):
            values = ",".join(number_text(v) for v in (speed.lateral, speed.vertical, speed.frontal))
            handle.write(f"{frame},{values}\n")
    return path
