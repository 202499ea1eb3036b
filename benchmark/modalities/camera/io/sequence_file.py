"""Image sequence files: the thesis' plain-text list of labelled frames.

The format is fixed by ``conventions.md`` section 2 and is the one the
thesis' tools read and write (seeds/000, section 4.7.3 and appendix B)::

    # CableDistance CableAngle CableWidth CableSkew # Filename
    3.5 -0.082 21.5 0.043 # frames/S1_000.png
    nan nan nan nan # frames/S1_001.png

One data row per frame: the cable state ``d alpha w beta`` (px, rad, px,
rad), a ``#``, and the image's path.  Everything after the first ``#`` of a
data row is the path, so a path may contain spaces and further ``#``
characters; a relative path is relative to the folder of the sequence file.
Lines whose first non-blank character is ``#`` are comments and blank lines
are skipped.  A frame without ground truth writes ``nan`` for all four
numbers and is read as :data:`benchmark.modalities.camera.model.UNKNOWN_CABLE`.

Reading is strict about the shape of a row and lenient about its values:
a row must hold four finite numbers or four ``nan``, but a negative skew or
a non-positive width is kept as written, since other tools may write them.
Every error names the file and the line.

:func:`read_sequence_file` and :func:`write_sequence_file` move rows between
text and :class:`SequenceRow` objects; :class:`ImageSequenceFile` turns a
file into a lazy, picklable :class:`~benchmark.model.Sequence`.
"""

from __future__ import annotations

import math
import os
from collections.abc import Iterable
from dataclasses import dataclass
from pathlib import Path

from benchmark.errors import DataError
from benchmark.files import atomic_writer, resolved
from benchmark.io import read_regular_file
from benchmark.modalities.camera.io.image_list import ImageListSequence
from benchmark.modalities.camera.io.sidecar import read_sidecar
from benchmark.modalities.camera.model import UNKNOWN_CABLE, CableState

MAX_LINES = 1_000_000
"""Most lines an image sequence file may hold: 11 hours of video at 25 frames a second."""

HEADER = "# CableDistance CableAngle CableWidth CableSkew # Filename"
"""The header comment the thesis' tools write first (seeds/000, section 4.7.3)."""


@dataclass(frozen=True, slots=True)
class SequenceRow:
    """One data row of an image sequence file.

    Attributes
    ----------
    cable : CableState
        Ground truth ``(d, alpha, w, beta)``; :data:`UNKNOWN_CABLE` for a
        ``nan`` row.
    image : pathlib.Path
        The image, as an absolute path.
    line : int
        Line number of the row in its file, from 1.
    """

    cable: CableState
    image: Path
    line: int


def _parse_number(token: str) -> float | None:
    try:
        return float(token)
    except ValueError:
        return None


def _parse_row(text: str, folder: Path, where: str, line: int) -> SequenceRow:
    numbers_text, hash_sign, path_text = text.partition("#")
    if not hash_sign:
        raise DataError(f"{where}no '#' between the four numbers and the image file name")
    path_text = path_text.strip()
    if not path_text:
        raise DataError(f"{where}no image file name after '#'")
    tokens = numbers_text.split()
    if len(tokens) != 4:
        raise DataError(f"{where}expected 4 numbers (d alpha w beta) before '#', found {len(tokens)}")
    values = []
    for name, token in zip(("d", "alpha", "w", "beta"), tokens, strict=True):
        value = _parse_number(token)
        if value is None:
            raise DataError(f"{where}{name} = {token!r} is not a number")
        if math.isinf(value):
            raise DataError(f"{where}{name} = {token!r} is infinite; write nan for unknown values")
        values.append(value)
    n_nan = sum(math.isnan(v) for v in values)
    if n_nan == 4:
        cable = UNKNOWN_CABLE
    elif n_nan:
        raise DataError(f"{where}some numbers are nan and some are not; an unlabelled frame writes nan for all four")
    else:
        cable = CableState(*values)
    image = Path(path_text)
    if not image.is_absolute():
        image = folder / image
    try:
        image = resolved(image)
    except DataError as exc:
        raise DataError(f"{where}invalid image path {path_text!r}: {exc}") from None
    return SequenceRow(cable=cable, image=image, line=line)


def read_sequence_file(path: str | os.PathLike[str]) -> list[SequenceRow]:
    """Parse an image sequence file; images are not opened.

    Parameters
    ----------
    path : str or path-like
        The sequence file.  Relative image paths in it are resolved against
        its folder.

    Returns
    -------
    list of SequenceRow
        The data rows in file order, at least one.

    Raises
    ------
    DataError
        If the file is missing, not a regular file or unreadable, holds no
        data row or more than :data:`MAX_LINES` lines, or a row is malformed (wrong count of numbers, a word that
        is not a number, an infinite value, ``nan`` mixed with numbers, no
        ``#``, no file name).  The message starts with ``path:line:``.

    References
    ----------
    seeds/000, section 4.7.3; ``conventions.md`` section 2.
    """
    file = Path(path)
    return _parse(file, read_regular_file(file, "image sequence file"))


def _parse(file: Path, content: bytes) -> list[SequenceRow]:
    """The data rows of the bytes ``content`` of the image sequence file ``file``."""
    lines = content.count(b"\n") + (not content.endswith(b"\n"))
    if lines > MAX_LINES:
        raise DataError(
            f"{file}: {lines:,} lines, more than the {MAX_LINES:,} an image sequence file may hold; split it"
        )
    try:
        text = content.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        raise DataError(f"{file}: not a UTF-8 text file ({exc.reason} at byte {exc.start})") from None
    folder = file.absolute().parent
    rows = []
    for number, line in enumerate(text.splitlines(), start=1):
        stripped = line.strip()
        if not stripped or stripped.startswith("#"):
            continue
        rows.append(_parse_row(stripped, folder, f"{file}:{number}: ", number))
    if not rows:
        raise DataError(f"{file}: no data rows (expected lines 'd alpha w beta # image')")
    return rows


def _format_number(value: float) -> str:
    # repr is the shortest text that parses back to the same float.
    return "nan" if math.isnan(value) else repr(float(value))


def _path_text(image: str | os.PathLike[str], folder: Path, where: str) -> str:
    path = Path(image)
    if path.is_absolute():
        try:
            path = path.resolve().relative_to(folder)
        except ValueError:
            pass
    text = path.as_posix()
    if not text or text == ".":
        raise DataError(f"{where}empty image path")
    if text.splitlines() != [text]:
        raise DataError(f"{where}image path {text!r} contains a line break")
    if text != text.strip():
        raise DataError(f"{where}image path {text!r} starts or ends with white space, which the format strips")
    return text


def _format_row(cable: CableState, image: str | os.PathLike[str], folder: Path, where: str) -> str:
    values = (cable.d, cable.alpha, cable.w, cable.beta)
    if any(math.isinf(v) for v in values):
        raise DataError(f"{where}cable state {values} has an infinite value")
    n_nan = sum(math.isnan(v) for v in values)
    if 0 < n_nan < 4:
        raise DataError(f"{where}cable state {values} mixes nan and numbers; use UNKNOWN_CABLE for unlabelled frames")
    numbers = " ".join(_format_number(v) for v in values)
    return f"{numbers} # {_path_text(image, folder, where)}\n"


def write_sequence_file(
    path: str | os.PathLike[str], rows: Iterable[tuple[CableState, str | os.PathLike[str]]]
) -> None:
    """Write an image sequence file that the thesis' tools and :func:`read_sequence_file` read.

    The file starts with :data:`HEADER`.  Numbers are written in the
    shortest form that reads back as the same float, ``nan`` for an
    unlabelled frame.  An absolute image path inside the file's folder is
    written relative to it; other absolute paths stay absolute.  A relative
    image path is taken to be relative to the file's folder already and is
    written as given.  Paths use ``/`` separators.

    The rows are consumed one at a time, so they may come from a generator
    that produces the images as it goes.  The file appears only once every
    row is written: it is assembled under a temporary name and renamed.

    Parameters
    ----------
    path : str or path-like
        The sequence file to write; its folder must exist.
    rows : iterable of (CableState, str or path-like)
        Ground truth and image path per frame, in frame order.

    Raises
    ------
    DataError
        If a state has an infinite value or mixes ``nan`` with numbers, if an
        image path cannot be written in the format (empty, a line break,
        white space at either end), or if the file cannot be written.  The
        message names the file and the row (from 1).

    References
    ----------
    seeds/000, section 4.7.3; ``conventions.md`` section 2.
    """
    file = Path(path)
    folder = file.absolute().parent.resolve()
    with atomic_writer(file, "image sequence file") as handle:
        handle.write(HEADER + "\n")
        for number, (cable, image) in enumerate(rows, start=1):
            handle.write(_format_row(cable, image, folder, f"{file}: row {number}: "))


class ImageSequenceFile(ImageListSequence):
    """A camera sequence read from an image sequence file.

    The text file is parsed when the object is made, so a malformed row
    fails at once; images are decoded only while frames are produced
    (:class:`~benchmark.modalities.camera.io.image_list.ImageListSequence`).  The object holds
    the path and the parsed rows and pickles cheaply.  Its identity hashes
    the file's bytes as read here, with the size and modification time of
    each image it lists.

    Parameters
    ----------
    path : str or path-like
        The sequence file.  ``info.name`` is this path as given.
    frame_interval_s : float, optional
        Time between frames in s.  The format has no time stamps; without
        this or a sidecar's, ``time_s`` counts frames and
        ``info.frame_interval_s`` is None.

    The file's sidecar ``S.toml`` beside ``S.txt``, where there is one,
    gives the calibration, the frame interval and each frame's navigation
    (:mod:`benchmark.modalities.camera.io.sidecar`).

    Raises
    ------
    DataError
        As :func:`read_sequence_file` (a FIFO or a device is refused
        unopened) and :func:`~benchmark.modalities.camera.io.sidecar.read_sidecar`; later, while iterating, for a missing, corrupt or
        differently sized image, naming the image and the line of the
        sequence file it is listed on.

    References
    ----------
    seeds/000, section 4.7.3; ``conventions.md`` section 2.
    """

    def __init__(self, path: str | os.PathLike[str], *, frame_interval_s: float | None = None) -> None:
        self._path = Path(path)
        content = read_regular_file(self._path, "image sequence file")
        self._rows: tuple[SequenceRow, ...] = tuple(_parse(self._path, content))
        super().__init__(
            name=os.fspath(path),
            source=self._path,
            images=(row.image for row in self._rows),
            cables=(row.cable for row in self._rows),
            frame_interval_s=frame_interval_s,
            content=content,
            sidecar=read_sidecar(self._path, n_frames=len(self._rows)),
        )

    @property
    def path(self) -> Path:
        """The sequence file."""
        return self._path

    @property
    def rows(self) -> tuple[SequenceRow, ...]:
        """The parsed data rows."""
        return self._rows

    def _where(self, index: int) -> str:
        return f"{self._path}:{self._rows[index].line}: "
