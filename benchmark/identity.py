"""What a dataset is, known without reading its frames: the identity cells are keyed and seeded by.

A cell is stored, resumed and seeded by the identity of its dataset, not by
the name the user typed.  A :class:`DatasetIdentity` has two parts:

``source``
    Where the data comes from: the resolved path of a file or folder, or
    the generator (module, class and the version of the distribution that
    ships it) of a simulated sequence.
``fingerprint``
    What the data is: a digest of a simulated sequence's spec, or of a
    dataset file's bytes together with the size and modification time of
    every file it names (:func:`file_fingerprint`).  Files a dataset names,
    such as images, are only ``stat``-ed here, never opened, so that all
    reading of frames happens inside a cell's time limit.

``--resume`` matches on :attr:`DatasetIdentity.key`, a digest of both: an
edited file or a new generator version is run again, and ``seq.txt`` and
``../dir/seq.txt`` naming the same file are one dataset.  A cell's random
stream is seeded from the fingerprint alone, so that a dataset copied
elsewhere with its modification times (``cp -p``, ``rsync -t``), or a
simulated sequence under a new version of its generator, replays with the
same stream.
"""

from __future__ import annotations

import dataclasses
import enum
import hashlib
import importlib.metadata
import json
import math
import os
import sys
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from functools import cache
from pathlib import Path, PurePath
from typing import Any

import numpy as np

from benchmark.files import resolved

DIGEST_CHARS = 32
"""Hex characters kept of a SHA-256 digest (128 bits)."""

OMIT_AT_DEFAULT = {"identity": "omit-at-default"}
"""Metadata of a dataclass field added later: left out of digests while it holds its default.

A field that a spec gains with a default that keeps the old behaviour
(``field(default=None, metadata=OMIT_AT_DEFAULT)``) leaves the digest of
every spec written before it unchanged.
"""


@dataclass(frozen=True)
class DatasetIdentity:
    """What a sequence is, known without reading a frame.

    Attributes
    ----------
    name : str
        The name shown in results: ``suite/sequence`` or the path as typed.
    modality : str
        The registered modality of the frames.
    source : str
        Where the data comes from: a resolved path, or a generator and its version.
    fingerprint : str
        A digest of what the data is (spec, or file bytes and file stats).
    """

    name: str
    modality: str
    source: str
    fingerprint: str

    @property
    def key(self) -> str:
        """The digest of source and fingerprint that ``--resume`` matches on."""
        return digest(self.source, self.fingerprint)

    @property
    def seed_material(self) -> int:
        """The fingerprint as an integer, one of the words seeding a cell's generator."""
        return int(self.fingerprint[:16], 16)

    def renamed(self, name: str) -> DatasetIdentity:
        """The same dataset shown under another name."""
        return dataclasses.replace(self, name=name)


def _canonical(value: Any) -> Any:
    """``value`` as plain JSON data with a single spelling for each value."""
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        fields = {
            field.name: _canonical(getattr(value, field.name))
            for field in dataclasses.fields(value)
            if not _omitted(field, getattr(value, field.name))
        }
        return {"__type__": type(value).__qualname__, **fields}
    if isinstance(value, enum.Enum):
        return _canonical(value.value)
    if isinstance(value, bool | int | str) or value is None:
        return value
    if isinstance(value, float | np.floating):
        return repr(float(value)) if not math.isfinite(value) else float(value)
    if isinstance(value, np.integer | np.bool_):
        return value.item()
    if isinstance(value, np.ndarray):
        return {"__array__": str(value.dtype), "shape": list(value.shape), "data": _canonical(value.tolist())}
    if isinstance(value, Mapping):
        return {str(key): _canonical(item) for key, item in sorted(value.items(), key=lambda kv: str(kv[0]))}
    if isinstance(value, PurePath):
        return value.as_posix()
    if isinstance(value, set | frozenset):
        return sorted((_canonical(item) for item in value), key=repr)
    if isinstance(value, Iterable):
        return [_canonical(item) for item in value]
    return repr(value)


def _omitted(field: dataclasses.Field[Any], value: Any) -> bool:
    """Whether a field marked :data:`OMIT_AT_DEFAULT` holds its default, and so stays out of a digest."""
    if field.metadata.get("identity") != OMIT_AT_DEFAULT["identity"]:
        return False
    if field.default is not dataclasses.MISSING:
        return bool(value == field.default)
    return field.default_factory is not dataclasses.MISSING and bool(value == field.default_factory())


def digest(*parts: Any) -> str:
    """A SHA-256 digest (:data:`DIGEST_CHARS` hex characters) of plain data: numbers, text, dataclasses, arrays.

    Equal values give equal digests in any process and on any machine:
    mappings are sorted by key, floats written exactly, dataclasses by
    their fields, arrays by dtype, shape and values.
    """
    text = json.dumps(_canonical(parts), sort_keys=True, separators=(",", ":"), allow_nan=False)
    return hashlib.sha256(text.encode()).hexdigest()[:DIGEST_CHARS]


def _stat_entry(path: Path) -> list[Any]:
    try:
        stat = os.stat(path)
    except OSError as exc:
        return [path.name, "unreadable", type(exc).__name__]
    return [path.name, stat.st_size, stat.st_mtime_ns]


def file_fingerprint(path: str | os.PathLike[str], content: bytes | None = None, named: Iterable[Path] = ()) -> str:
    """The fingerprint of a dataset file and of the files it names.

    Parameters
    ----------
    path : str or path-like
        The dataset file (or folder), as opened.
    content : bytes, optional
        The file's bytes where the reader has read them anyway; hashed in
        full.  Without them the file's size and modification time stand in.
    named : iterable of pathlib.Path
        The files it names (images of a sequence file or a folder): their
        names, sizes and modification times (ns) enter the fingerprint; a
        file that cannot be ``stat``-ed enters as such, so that it counts
        once it appears.  None of them is opened.

    Returns
    -------
    str
        A digest (:func:`digest`).
    """
    own = hashlib.sha256(content).hexdigest() if content is not None else _stat_entry(Path(path))[1:]
    return digest(own, [_stat_entry(Path(item)) for item in named])


def resolved_source(path: str | os.PathLike[str]) -> str:
    """The source of a dataset on disk: its absolute path with links and ``..`` resolved."""
    return resolved(path).as_posix()


@cache
def code_digest(module: str) -> str:
    """A digest of every ``.py`` file of the top-level package of ``module`` (or of the module alone), once per process.

    Part of the key of cached frames (a renderer edited without a version
    bump is not served from the cache) and of a tracker's cache key (a
    tracker edited without a version bump is run again on ``--resume``).
    """
    package = sys.modules.get(module.partition(".")[0])
    folders = [Path(folder) for folder in getattr(package, "__path__", [])]
    files = sorted((path.relative_to(folder).as_posix(), path) for folder in folders for path in folder.rglob("*.py"))
    if not files:
        own = getattr(sys.modules.get(module), "__file__", None)
        files = [(Path(own).name, Path(own))] if own else []
    hasher = hashlib.sha256()
    for name, path in files:
        hasher.update(name.encode())
        hasher.update(path.read_bytes())
    return hasher.hexdigest()


@cache
def _distribution_versions() -> dict[str, str]:
    versions: dict[str, str] = {}
    for package, names in importlib.metadata.packages_distributions().items():
        for name in names:
            try:
                versions.setdefault(package, f"{name} {importlib.metadata.version(name)}")
            except importlib.metadata.PackageNotFoundError:
                continue
    return versions


def generator_source(generator: type) -> str:
    """The source of simulated data: the generator's module and class, and the distribution shipping it.

    For trackbench's own scenes this reads, e.g.,
    ``benchmark.modalities.camera.scenes.cable.CableScene (subsea-trackbench 0.1.0)``; a
    class outside any installed distribution gives its module and class only.
    """
    top = generator.__module__.partition(".")[0]
    version = _distribution_versions().get(top, "no distribution")
    return f"{generator.__module__}.{generator.__qualname__} ({version})"
