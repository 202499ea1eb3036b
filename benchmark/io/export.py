"""Export a sequence in its on-disk form: images plus a sequence file, or a swath file.

:func:`export_sequence` turns any camera :class:`~benchmark.model.Sequence`
(a rendered synthetic scene, a video, another sequence file) into the
thesis' on-disk form (seeds/000, section 4.7.3; ``conventions.md``
section 2), so that a sequence made here can be labelled, inspected or
tracked with other tools, and read back with
:func:`benchmark.io.open_sequence`.  For a sequence called ``name`` it
writes::

    out_dir/<stem>.txt                 the sequence file
    out_dir/<stem>/frame_00000.png     one lossless PNG per frame
    out_dir/<stem>/frame_00001.png
    ...

with the image paths in the sequence file relative to ``out_dir``.  Frames
are written as they are produced, one in memory at a time; the sequence
file appears only once every image is written.  A sonar sequence becomes
one swath file, ``out_dir/<stem>.swaths``
(:mod:`benchmark.io.swath_file`).
"""

from __future__ import annotations

import os
import re
from collections.abc import Iterator
from pathlib import Path

from benchmark.errors import DataError
from benchmark.io.images import size_of, write_png
from benchmark.io.sequence_file import write_sequence_file
from benchmark.io.swath_file import SWATH_SUFFIX, write_swath_file
from benchmark.model import UNKNOWN_CABLE, CableState, CameraTruth, Sequence

_SEPARATORS = re.compile(r"[/\\]")


def default_stem(name: str) -> str:
    """File stem for a sequence name: path separators become ``_`` (``suite/seq`` -> ``suite_seq``)."""
    stem = _SEPARATORS.sub("_", name)
    return stem if stem not in ("", ".", "..") else "sequence"


def _check_stem(stem: str) -> str:
    if stem in ("", ".", "..") or _SEPARATORS.search(stem):
        raise ValueError(f"stem must be a plain file name without path separators, got {stem!r}")
    return stem


def _truth_cable(truth: object, where: str) -> CableState:
    if truth is None:
        return UNKNOWN_CABLE
    if isinstance(truth, CameraTruth):
        return truth.cable
    raise DataError(f"{where}truth is a {type(truth).__name__}, not a CameraTruth")


def export_sequence(sequence: Sequence, out_dir: str | os.PathLike[str], *, stem: str | None = None) -> Path:
    """Write a camera sequence as PNG frames plus an image sequence file, a sonar sequence as a swath file.

    Parameters
    ----------
    sequence : Sequence
        A camera sequence whose frames carry ``uint8`` grey images of one
        size and a :class:`~benchmark.model.CameraTruth` (or None), or a
        sonar sequence (:func:`benchmark.io.swath_file.write_swath_file`).
    out_dir : str or path-like
        Folder to write into; created if missing.
    stem : str, optional
        Name of the sequence file (without ``.txt``) and of the image
        folder.  Defaults to ``info.name`` with ``/`` replaced by ``_``.

    Returns
    -------
    pathlib.Path
        The sequence file ``out_dir/<stem>.txt`` or swath file ``out_dir/<stem>.swaths``.

    Raises
    ------
    DataError
        If the sequence is neither a camera nor a sonar sequence, a frame is not a grey
        ``uint8`` image or differs in size from the first, a truth is not a
        camera truth, or a file cannot be written.  Errors from reading the
        sequence itself pass through.
    ValueError
        If ``stem`` contains a path separator or is empty.

    References
    ----------
    seeds/000, section 4.7.3; ``conventions.md`` section 2.
    """
    info = sequence.info
    stem = _check_stem(stem) if stem is not None else default_stem(info.name)
    out = Path(out_dir)
    if info.modality == "sonar":
        return write_swath_file(sequence, out / f"{stem}{SWATH_SUFFIX}")
    if info.modality != "camera":
        raise DataError(f"{info.name}: only camera and sonar sequences can be exported, not {info.modality}")
    image_dir = out / stem
    try:
        image_dir.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise DataError(f"{image_dir}: cannot create folder: {exc.strerror or exc}") from None

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
            yield _truth_cable(frame.truth, where), f"{stem}/{file_name}"
        if count < 0:
            raise DataError(f"{info.name}: the sequence has no frames to export")

    sequence_path = out / f"{stem}.txt"
    write_sequence_file(sequence_path, rows())
    return sequence_path
