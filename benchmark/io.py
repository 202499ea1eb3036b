"""Datasets on disk: open any file or folder a modality reads, export a sequence in its modality's form.

Researchers bring their own labelled sequences: an image sequence file in
the thesis' format (seeds/000, section 4.7.3; ``conventions.md``
section 2), a folder of images, a video, a swath file of sonar pings.
Each modality declares the :class:`~benchmark.modality.Reader` objects that
open its files (by suffix, any folder, or a folder holding certain names);
:func:`open_sequence` picks the
one a path calls for, which is how ``trackbench run --dataset PATH`` reads
a dataset made anywhere else.  In the other direction,
:func:`export_sequence` writes any sequence with its modality's exporter
(``trackbench make-dataset``), so that it can be used elsewhere and read
back with :func:`open_sequence`.

A path no reader claims, a path that is neither a regular file nor a
folder (a FIFO, a device, a socket: reading one could block for ever), or a
file its reader rejects, raises :class:`~benchmark.errors.DataError` naming
the file.  Readers open their files with :func:`open_regular_file`, and
exporters create their folders with :func:`benchmark.files.make_folder`, so
that each refuses the same things with the same message.
"""

from __future__ import annotations

import os
import re
import stat
from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import BinaryIO

from benchmark.errors import DataError
from benchmark.modality import ANY_FILE, Modality, Reader
from benchmark.model import Sequence

_SEPARATORS = re.compile(r"[/\\]")

_KINDS = (
    (stat.S_ISDIR, "a folder"),
    (stat.S_ISFIFO, "a FIFO (named pipe)"),
    (stat.S_ISCHR, "a character device"),
    (stat.S_ISBLK, "a block device"),
    (stat.S_ISSOCK, "a socket"),
)


def _kind(mode: int) -> str:
    """What a file that is not a regular file is, for messages ("a FIFO (named pipe)")."""
    return next((name for test, name in _KINDS if test(mode)), "not a regular file")


def _reason(exc: OSError | ValueError) -> str:
    return getattr(exc, "strerror", None) or str(exc)


def open_regular_file(path: str | os.PathLike[str], what: str) -> BinaryIO:
    """Open a dataset file to read its bytes, refusing anything but a regular file before opening it.

    Opening a FIFO blocks until a writer appears, and a device or a socket
    may never end, so these are refused from their ``stat`` alone.

    Parameters
    ----------
    path : str or path-like
        The file.
    what : str
        What the file should be, for messages ("swath file").

    Returns
    -------
    BinaryIO
        The open file; the caller closes it.

    Raises
    ------
    DataError
        If nothing is at ``path``, it is not a regular file (a folder, a
        FIFO, a device, a socket), or it cannot be opened; naming it.
    """
    try:
        mode = os.stat(path).st_mode
        if not stat.S_ISREG(mode):
            raise DataError(f"{path}: cannot read {what}: it is {_kind(mode)}, not a regular file")
        return open(path, "rb")
    except FileNotFoundError:
        raise DataError(f"{path}: no such {what}") from None
    except (OSError, ValueError) as exc:
        raise DataError(f"{path}: cannot read {what}: {_reason(exc)}") from None


def read_regular_file(path: str | os.PathLike[str], what: str) -> bytes:
    """The bytes of a dataset file, read through :func:`open_regular_file`.

    Raises
    ------
    DataError
        As :func:`open_regular_file`, or if reading fails; naming the file.
    """
    with open_regular_file(path, what) as stream:
        try:
            return stream.read()
        except OSError as exc:
            raise DataError(f"{path}: cannot read {what}: {_reason(exc)}") from None


def _choose_reader(target: Path, is_folder: bool, readers: list[Reader]) -> Reader | None:
    if is_folder:
        # A reader that knows the folder by names in it goes before one that takes any folder.
        takers = sorted((reader for reader in readers if reader.opens_folder(target)), key=lambda r: not r.folder_holds)
        return next(iter(takers), None)
    suffix = target.suffix.lower()
    claimed = next((reader for reader in readers if suffix and suffix in reader.suffixes), None)
    return claimed or next((reader for reader in readers if ANY_FILE in reader.suffixes), None)


def open_sequence(path: str | os.PathLike[str], modalities: Iterable[Modality]) -> Sequence:
    """Open a dataset by its path with the reader of the modality that claims it.

    Parameters
    ----------
    path : str or path-like
        A folder, or a file whose suffix a reader claims (``.swaths``, a
        video's ``.avi``), or a file of any other name, which the reader
        that takes :data:`~benchmark.modality.ANY_FILE` opens (the camera's
        image sequence files: the thesis' end in ``.txt``, ``.seq`` and more).
    modalities : iterable of Modality
        The registered modalities, whose readers are tried.

    Returns
    -------
    Sequence
        The opened sequence; frames are decoded only while it is iterated.

    Raises
    ------
    DataError
        If nothing exists at ``path``, it is neither a regular file nor a
        folder (it is not opened then), no reader takes it, or the reader
        chosen for it rejects it.

    References
    ----------
    seeds/000, section 4.7.3; ``conventions.md`` section 2.
    """
    readers = [reader for modality in modalities for reader in modality.readers]
    expected = ", ".join(reader.description for reader in readers) or "no readers are registered"
    target = Path(path)
    try:
        mode = target.stat().st_mode
    except (FileNotFoundError, NotADirectoryError):
        raise DataError(f"{target}: no such dataset (expected {expected})") from None
    except (OSError, ValueError) as exc:
        raise DataError(f"{target}: cannot open dataset: {_reason(exc)}") from None
    if not (stat.S_ISREG(mode) or stat.S_ISDIR(mode)):
        raise DataError(f"{target}: it is {_kind(mode)}, neither a file nor a folder; no reader opens it")
    reader = _choose_reader(target, stat.S_ISDIR(mode), readers)
    if reader is None:
        raise DataError(f"{target}: no registered reader opens this (readers: {expected})")
    return reader.open(path)


def default_stem(name: str) -> str:
    """File stem for a sequence name: path separators become ``_`` (``suite/seq`` -> ``suite_seq``)."""
    stem = _SEPARATORS.sub("_", name)
    return stem if stem not in ("", ".", "..") else "sequence"


def export_sequence(
    sequence: Sequence,
    out_dir: str | os.PathLike[str],
    modalities: Mapping[str, Modality],
    *,
    stem: str | None = None,
) -> Path:
    """Write a sequence in its modality's on-disk form.

    Parameters
    ----------
    sequence : Sequence
        Any sequence of a registered modality that has an exporter.
    out_dir : str or path-like
        Folder to write into; created if missing.
    modalities : Mapping
        The registered modalities by name.
    stem : str, optional
        File stem of what is written (the camera writes ``<stem>.txt`` and a
        folder ``<stem>/`` of images, the sonar ``<stem>.swaths``).  Defaults
        to ``info.name`` with ``/`` replaced by ``_``.

    Returns
    -------
    pathlib.Path
        The file that :func:`open_sequence` opens again.

    Raises
    ------
    DataError
        If the sequence's modality is not registered or cannot be exported,
        or from the exporter (a frame it cannot write, a file it cannot
        create).  Errors from reading the sequence itself pass through.
    ValueError
        If ``stem`` contains a path separator or is empty.
    """
    info = sequence.info
    if stem is not None and (stem in ("", ".", "..") or _SEPARATORS.search(stem)):
        raise ValueError(f"stem must be a plain file name without path separators, got {stem!r}")
    modality = modalities.get(info.modality)
    if modality is None or modality.exporter is None:
        exportable = ", ".join(name for name, known in modalities.items() if known.exporter is not None)
        raise DataError(
            f"{info.name}: {info.modality} sequences cannot be exported (exportable: {exportable or 'none'})"
        )
    return modality.exporter(sequence, Path(out_dir), stem if stem is not None else default_stem(info.name))
