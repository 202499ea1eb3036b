"""Writing files so that a reader never sees half of one, and folders with errors that name them.

Every file trackbench publishes (boards, tables, sequence files) is written
under a unique temporary name in its own folder and renamed over the target
only once complete: a run killed mid-write, or a second process reading at
the same moment, sees the old file or the new one, never a mixture.  Every
folder trackbench writes into is made by :func:`make_folder`, so a file in
the way or a missing permission is one ``DataError`` naming the folder.
"""

from __future__ import annotations

import os
import uuid
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

from benchmark.errors import DataError


@contextmanager
def atomic_writer(path: str | os.PathLike[str], what: str = "file", binary: bool = False) -> Iterator[Any]:
    """A handle whose content replaces ``path`` when the block ends without error.

    Parameters
    ----------
    path : str or path-like
        The file to write; its folder must exist.
    what : str
        What the file is, for error messages ("leaderboard", "image sequence file").
    binary : bool
        A bytes handle instead of a text one.

    Yields
    ------
    TextIO or BinaryIO
        Text: UTF-8, ``\\n`` line ends.

    Raises
    ------
    DataError
        If the file cannot be created or written, naming it.  On any error
        the temporary file is removed and ``path`` is left as it was.
    """
    target = Path(path)
    temporary = target.with_name(f".{target.name}.{uuid.uuid4().hex[:12]}.tmp")
    try:
        handle = temporary.open("xb") if binary else temporary.open("x", encoding="utf-8", newline="\n")
    except OSError as exc:
        raise DataError(f"{target}: cannot write {what}: {exc.strerror or exc}") from None
    try:
        with handle:
            yield handle
        os.replace(temporary, target)
    except OSError as exc:
        temporary.unlink(missing_ok=True)
        raise DataError(f"{target}: cannot write {what}: {exc.strerror or exc}") from None
    except BaseException:
        temporary.unlink(missing_ok=True)
        raise


def write_text_atomically(path: str | os.PathLike[str], text: str, what: str = "file") -> Path:
    """Write ``text`` to ``path`` through :func:`atomic_writer`; return the path."""
    with atomic_writer(path, what) as handle:
        handle.write(text)
    return Path(path)


def write_bytes_atomically(path: str | os.PathLike[str], data: bytes, what: str = "file") -> Path:
    """Write ``data`` to ``path`` through :func:`atomic_writer`; return the path."""
    with atomic_writer(path, what, binary=True) as handle:
        handle.write(data)
    return Path(path)


def make_folder(path: str | os.PathLike[str]) -> Path:
    """Create a folder to write into, with its parents, unless it exists; return it.

    Raises
    ------
    DataError
        If it cannot be created (a file is in the way, no permission), naming it.
    """
    folder = Path(path)
    try:
        folder.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise DataError(f"{folder}: cannot create folder: {exc.strerror or exc}") from None
    return folder


def resolved(path: str | os.PathLike[str]) -> Path:
    """``path`` made absolute, with links and ``..`` resolved.

    Raises
    ------
    DataError
        If a link cannot be followed (a loop of links, no permission), naming the path.
    """
    try:
        return Path(path).resolve()
    except RuntimeError:  # Python before 3.13 reports a loop of links so
        raise DataError(f"{path}: a loop of symbolic links") from None
    except (OSError, ValueError) as exc:
        raise DataError(f"{path}: cannot follow its links: {getattr(exc, 'strerror', None) or exc}") from None
