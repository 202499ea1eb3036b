"""What every modality's sidecar shares: where it lies, how it is read, and its per-frame CSV tables.

A sequence on disk may carry what its own format has no place for in a
TOML file beside it, its *sidecar*: the sequence's path with its suffix
replaced by ``.toml``, and for a folder ``DIR/`` the file ``DIR.toml``
beside the folder (:func:`sidecar_path`).  Each modality declares the
tables of its sidecar as pydantic dataclasses in the vocabulary of scene
specs (:mod:`benchmark.scenes.spec`), and per-frame data as CSV files with
a fixed header whose first column is the frame index.  This module reads
both, so that every problem is one :class:`~benchmark.errors.DataError`
naming the file and the key's path or the CSV line:

* :func:`read_toml_table`: a TOML file validated as a table class;
* :func:`read_frame_csv`: rows of a per-frame CSV file by frame index;
* :func:`number_text`: a float as the shortest text that reads back the same.

The camera sidecar (:mod:`benchmark.modalities.camera.io.sidecar`) and the
stereo folder (:mod:`benchmark.modalities.stereo.io.folder`) are built on it.
"""

from __future__ import annotations

import csv
import io
import math
import os
import tomllib
from pathlib import Path
from typing import Any, TypeVar

from benchmark.errors import DataError
from benchmark.io import read_regular_file
from benchmark.scenes.spec import validate_table

Row = TypeVar("Row")


def sidecar_path(path: str | os.PathLike[str]) -> Path:
    """Where the sidecar of the sequence at ``path`` is: suffix replaced by ``.toml``; ``DIR.toml`` beside a folder."""
    target = Path(path)
    if target.is_dir():
        folder = target.absolute().resolve()
        return folder.parent / f"{folder.name}.toml"
    return target.with_suffix(".toml")


def read_toml_table(where: Path, kind: type[Row]) -> tuple[Row, bytes]:
    """The TOML file ``where`` validated as the table class ``kind``, and the bytes it was read from.

    Raises
    ------
    DataError
        Naming the file: missing or not a regular file, not valid UTF-8
        TOML; naming the file and the key's path: an unknown key, a value of
        the wrong type or out of its range.
    """
    content = read_regular_file(where, "sidecar")
    try:
        data = tomllib.loads(content.decode("utf-8-sig"))
    except (UnicodeDecodeError, tomllib.TOMLDecodeError) as exc:
        raise DataError(f"{where}: not a valid TOML sidecar: {exc}") from None
    return validate_table(kind, data, str(where)), content


def read_frame_csv(
    file: Path, content: bytes, row_type: type[Row], columns: tuple[str, ...], n_frames: int | None = None
) -> dict[int, Row]:
    """The rows by frame index in the bytes ``content`` of the CSV file ``file``.

    Parameters
    ----------
    file : pathlib.Path
        The CSV file, for messages.
    content : bytes
        Its bytes.
    row_type : type
        A pydantic dataclass with the fields ``columns`` (the first,
        ``frame``, an integer >= 0) that converts CSV text by type.
    columns : tuple of str
        The header, in this order.
    n_frames : int, optional
        The sequence's frame count, which no frame index may reach.

    Raises
    ------
    DataError
        Naming the file and the line: not UTF-8 text, a header other than
        ``columns``, a row of another length, a value ``row_type`` refuses,
        a frame index twice or (with ``n_frames``) beyond the sequence.
    """
    try:
        text = content.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        raise DataError(f"{file}: not a UTF-8 text file ({exc.reason} at byte {exc.start})") from None
    lines = [(number, row) for number, row in enumerate(csv.reader(io.StringIO(text)), start=1) if any(row)]
    header = ",".join(columns)
    if not lines or [cell.strip() for cell in lines[0][1]] != list(columns):
        found = ",".join(lines[0][1]) if lines else "nothing"
        raise DataError(f"{file}:{lines[0][0] if lines else 1}: expected the header {header!r}, found {found!r}")
    rows: dict[int, Any] = {}
    for number, row in lines[1:]:
        at = f"{file}:{number}"
        if len(row) != len(columns):
            raise DataError(f"{at}: expected {len(columns)} values ({header}), found {len(row)}")
        parsed = validate_table(row_type, dict(zip(columns, (cell.strip() for cell in row), strict=True)), at)
        if parsed.frame in rows:
            raise DataError(f"{at}: frame {parsed.frame} is listed twice")
        if n_frames is not None and parsed.frame >= n_frames:
            raise DataError(f"{at}: frame {parsed.frame} is beyond the sequence's {n_frames} frames")
        rows[parsed.frame] = parsed
    return rows


def number_text(value: float) -> str:
    """``value`` as the shortest text that reads back as the same float (TOML and CSV); ``ValueError`` unless finite."""
    if not math.isfinite(value):
        raise ValueError(f"{value!r} cannot be written to a sidecar")
    return repr(float(value))
