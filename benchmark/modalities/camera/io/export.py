"""Export a camera sequence in the thesis' on-disk form: PNG images plus an image sequence file.

:func:`export_camera_sequence` turns any camera
:class:`~benchmark.model.Sequence` (a rendered synthetic scene, a video,
another sequence file) into the thesis' on-disk form (seeds/000, section
4.7.3; ``conventions.md`` section 2), so that a sequence made here can be
labelled, inspected or tracked with other tools, and read back with
:func:`benchmark.io.open_sequence`.  For a file stem ``stem`` it writes::

    out_dir/<stem>.txt                 the sequence file
    out_dir/<stem>/frame_00000.png     one lossless PNG per frame
    out_dir/<stem>/frame_00001.png
    ...

with the image paths in the sequence file relative to ``out_dir``, and,
where the sequence knows them, its sidecar (:mod:`benchmark.modalities.camera.io.sidecar`)::

    out_dir/<stem>.toml                frame interval and camera calibration
    out_dir/<stem>.nav.csv             the vehicle's speeds, when every frame has them

so that a tracker that needs them (``foresti_ekf``) runs on the export as on
the sequence.  Frames are written as they are produced, one in memory at a
time; the sequence file appears only once every image is written, its
sidecar after it.  It is the camera
modality's exporter (``trackbench make-dataset``, :func:`benchmark.io.export_sequence`).
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from pathlib import Path

from benchmark.errors import DataError
from benchmark.files import make_folder
from benchmark.modalities.camera.io.images import size_of, write_png
from benchmark.modalities.camera.io.sequence_file import write_sequence_file
from benchmark.modalities.camera.io.sidecar import CameraTable, write_navigation_file, write_sidecar
from benchmark.modalities.camera.model import UNKNOWN_CABLE, CableState, CameraCalibration, CameraTruth, VehicleSpeeds
from benchmark.model import Sequence, SequenceInfo


def _truth_cable(truth: object, where: str) -> CableState:
    if truth is None:
        return UNKNOWN_CABLE
    if isinstance(truth, CameraTruth):
        return truth.cable
    raise DataError(f"{where}truth is a {type(truth).__name__}, not a CameraTruth")


def export_camera_sequence(sequence: Sequence, out: Path, stem: str) -> Path:
    """Write a camera sequence as PNG frames plus an image sequence file.

    Parameters
    ----------
    sequence : Sequence
        A camera sequence whose frames carry ``uint8`` grey images of one
        size and a :class:`~benchmark.modalities.camera.model.CameraTruth` or None.
    out : pathlib.Path
        Folder to write into; created if missing.
    stem : str
        Name of the sequence file (without ``.txt``) and of the image folder.

    Returns
    -------
    pathlib.Path
        The sequence file ``out/<stem>.txt``.

    Raises
    ------
    DataError
        If a frame is not a grey ``uint8`` image or differs in size from
        the first, a truth is not a camera truth, or a folder (``out``
        itself, say, with a file in its way) or a file cannot be created or
        written, naming it.  Errors from reading the sequence itself pass
        through.

    References
    ----------
    seeds/000, section 4.7.3; ``conventions.md`` section 2.
    """
    info = sequence.info
    image_dir = make_folder(make_folder(out) / stem)
    speeds: list[object] = []

    def rows() -> Iterator[tuple[CableState, str]]:
        first_size: tuple[int, int] | None = None
        count = -1
        for count, frame in enumerate(sequence.frames()):
            where = f"{info.name}: frame {frame.index}: "
            file_name = f"frame_{count:05d}.png"
            write_png(image_dir / file_name, frame.observation, where=where)
            size = size_of(frame.observation)
            if first_size is None:
                first_size = size
            elif size != first_size:
                width, height = first_size
                raise DataError(f"{where}image is {size[0]}x{size[1]} px, but the first frame is {width}x{height} px")
            speeds.append(frame.navigation)
            yield _truth_cable(frame.truth, where), f"{stem}/{file_name}"
        if count < 0:
            raise DataError(f"{info.name}: the sequence has no frames to export")

    sequence_path = out / f"{stem}.txt"
    write_sequence_file(sequence_path, rows())
    _write_sidecar(sequence_path, info, speeds)
    return sequence_path


def _write_sidecar(sequence_path: Path, info: SequenceInfo, speeds: list[object]) -> None:
    """The sidecar of an exported sequence: what its info and navigation hold, nothing when they hold nothing."""
    calibration = info.calibration if isinstance(info.calibration, CameraCalibration) else None
    camera = None
    if calibration is not None:
        tilt_deg = math.degrees(calibration.nominal_tilt)
        camera = CameraTable(calibration.focal_px, calibration.pipe_diameter_m, tilt_deg)
    navigation = None
    if speeds and all(isinstance(speed, VehicleSpeeds) for speed in speeds):
        navigation = write_navigation_file(sequence_path.with_suffix(".nav.csv"), speeds).name
    if camera is not None or navigation is not None or info.frame_interval_s is not None:
        write_sidecar(sequence_path, frame_interval_s=info.frame_interval_s, camera=camera, navigation_file=navigation)
