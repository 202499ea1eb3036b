"""Datasets on disk: open any file or folder a modality reads, export a sequence in its modality's form.

Researchers bring their own labelled sequences: an image sequence file in
the thesis' format (seeds/000, section 4.7.3; ``conventions.md``
section 2), a folder of images, a video, a swath file of sonar pings.
Each modality declares the :class:`~benchmark.modality.Reader` objects that
open its files (by suffix, or any folder); :func:`open_sequence` picks the
one a path calls for, which is how ``trackbench run --dataset PATH`` reads
a dataset made anywhere else.  In the other direction,
:func:`export_sequence` writes any sequence with its modality's exporter
(``trackbench make-dataset``), so that it can be used elsewhere and read
back with :func:`open_sequence`.

A path no reader claims, or a file its reader rejects, raises
:class:`~benchmark.errors.DataError` naming the file.
"""

from __future__ import annotations

import os
import re
from collections.abc import Iterable, Mapping
from pathlib import Path

from benchmark.errors import DataError
from benchmark.modality import ANY_FILE, Modality, Reader
from benchmark.model import Sequence

_SEPARATORS = re.compile(r"[/\\]")


def _choose_reader(target: Path, readers: list[Reader]) -> Reader | None:
    if target.is_dir():
        return next((reader for reader in readers if reader.folders), None)
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
        If nothing exists at ``path``, no reader takes it, or the reader
        chosen for it rejects it.

    References
    ----------
    seeds/000, section 4.7.3; ``conventions.md`` section 2.
    """
    readers = [reader for modality in modalities for reader in modality.readers]
    expected = ", ".join(reader.description for reader in readers) or "no readers are registered"
    target = Path(path)
    if not target.exists():
        raise DataError(f"{target}: no such dataset (expected {expected})")
    reader = _choose_reader(target, readers)
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
