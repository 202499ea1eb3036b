"""Render once, read many times: a frame cache on disk for simulated sequences.

A simulated sequence is a pure function of its spec and of the code that
renders it, yet every cell of a run reads it: ten camera trackers used to
render each camera sequence ten times.  A :class:`FrameCache` renders a
sequence the first time a cell reads it and keeps its frames in a folder
(``--cache DIR``, by default the platform's cache folder, see
:func:`default_cache_folder`), where every later cell, in this run or a
later one, on this process or another, reads them back.

What is cached
    Sequences whose class sets ``cache_frames`` (the simulated scenes,
    :class:`benchmark.scenes.scene.SimulatedScene`).  Sequences read from
    files are on disk already and are read as before.
The key
    A digest of the sequence's identity (:mod:`benchmark.identity`: its
    generator, the version of the distribution shipping it and its spec)
    and of the source code of the generator's top-level package, so that a
    frame rendered by an older renderer is never served, even when the
    version number did not change.
The format
    One file per sequence, ``KEY.frames``: a header (name, modality, frame
    count) and then every :class:`~benchmark.model.Frame` pickled one after
    another (protocol 5, so an image is stored as its raw bytes).  Reading
    one frame is one ``pickle.load`` from a buffered file, so memory stays
    flat in the length of the sequence.  Measured on a 320 x 240 camera
    frame, reading it back takes about 20 us against 2.4 ms to render it;
    PNG would take about 0.3 ms to decode and would not store the truth,
    the navigation data or the sonar's and stereo camera's observations.
    The file is written under a temporary name and renamed when complete,
    while a lock (``KEY.lock``) makes the other processes that want the same
    sequence wait for it instead of rendering it again.
When the cache cannot be written
    (a full disk, a read-only folder), or rendering fails part way, the
    frames are rendered and streamed as if there were no cache, so that a
    rendering error reaches the cell at the frame it concerns: the cache
    saves time, it is never a reason for a cell to fail.  An entry that cannot be read back is a
    :class:`~benchmark.errors.DataError` naming its file; the entry is
    removed, so the next run renders it again.

The cache holds pickles, like the fitted models of a results folder: it is
the user's own folder, and a file placed there by someone else would be
code run by trackbench.
"""

from __future__ import annotations

import functools
import hashlib
import os
import pickle
import sys
import uuid
from collections.abc import Iterator, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import IO, Any

import filelock

from benchmark.errors import DataError
from benchmark.files import make_folder
from benchmark.identity import DatasetIdentity, digest
from benchmark.model import Frame, Sequence, SequenceInfo

CACHE_ENV = "TRACKBENCH_CACHE"
"""Environment variable naming the cache folder, in place of the platform's default."""
FORMAT = 1
"""Version of the entry format; a new one gives new keys."""
SUFFIX = ".frames"


def default_cache_folder() -> Path:
    """The frame cache's folder: ``$TRACKBENCH_CACHE``, or ``frames`` in the platform's user cache folder."""
    named = os.environ.get(CACHE_ENV)
    if named:
        return Path(named)
    import platformdirs

    return Path(platformdirs.user_cache_dir("trackbench")) / "frames"


@functools.cache
def _package_code_digest(module: str) -> str:
    """A digest of every ``.py`` file of the top-level package of ``module`` (or of the module alone)."""
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


def _entry_header(identity: DatasetIdentity, info: SequenceInfo) -> dict[str, Any]:
    return {"format": FORMAT, "name": identity.name, "modality": identity.modality, "frames": info.n_frames}


@dataclass(frozen=True)
class CacheEntry:
    """One cached sequence, as ``trackbench cache info`` lists it."""

    path: Path
    name: str
    modality: str
    frames: int | None
    size_bytes: int


@dataclass(frozen=True)
class FrameCache:
    """A folder of rendered sequences, shared by every cell and run that reads them.

    Parameters
    ----------
    root : pathlib.Path, optional
        The folder; created when the first sequence is written.  None is
        :func:`default_cache_folder` of the process that reads the frames:
        on a cluster, each machine renders into its own cache, while a
        folder named here may be one every worker shares.
    """

    root: Path | None = None

    @property
    def folder(self) -> Path:
        """The cache's folder in this process."""
        return self.root if self.root is not None else default_cache_folder()

    def key(self, sequence: Sequence) -> str | None:
        """The key of ``sequence``'s entry, or None when its frames are not cached (read from files)."""
        if not sequence.cache_frames:
            return None
        return digest(FORMAT, sequence.identity.key, _package_code_digest(type(sequence).__module__))

    def path(self, key: str) -> Path:
        """The entry file of ``key``."""
        return self.folder / f"{key}{SUFFIX}"

    def wrap(self, sequence: Sequence) -> Sequence:
        """``sequence`` read through this cache, or ``sequence`` itself when it is not cached."""
        key = self.key(sequence)
        return sequence if key is None else CachedSequence(sequence, self, key)

    def holds(self, sequence: Sequence) -> bool:
        """Whether ``sequence``'s frames are in the cache."""
        key = self.key(sequence)
        return key is not None and self.path(key).is_file()

    def entries(self) -> list[CacheEntry]:
        """The cached sequences, by name; an entry whose header cannot be read shows as ``unreadable``."""
        found = []
        for path in sorted(self.folder.glob(f"*{SUFFIX}")) if self.folder.is_dir() else []:
            try:
                with path.open("rb") as handle:
                    header = pickle.load(handle)
                name, modality, frames = header["name"], header["modality"], header["frames"]
            except Exception:
                name, modality, frames = "unreadable", "-", None
            found.append(CacheEntry(path, name, modality, frames, path.stat().st_size))
        return sorted(found, key=lambda entry: (entry.name, entry.path.name))

    def leftovers(self) -> list[Path]:
        """Temporary files left by writers that were stopped before they finished."""
        folder = self.folder
        return sorted(folder.glob(f".*{SUFFIX}.*.tmp")) if folder.is_dir() else []

    def _locks(self) -> list[Path]:
        folder = self.folder
        return sorted(folder.glob("*.lock")) if folder.is_dir() else []

    def clear(self) -> tuple[int, int]:
        """Remove every entry, leftover and lock; return (entries removed, bytes freed).

        Raises
        ------
        DataError
            Naming a file that cannot be removed.
        """
        removed = freed = 0
        for path in [entry.path for entry in self.entries()] + self.leftovers() + self._locks():
            try:
                size = path.stat().st_size
                path.unlink()
            except FileNotFoundError:
                continue
            except OSError as exc:
                raise DataError(f"{path}: cannot remove: {exc.strerror or exc}") from None
            removed += path.suffix == SUFFIX
            freed += size
        return removed, freed

    def frames(self, sequence: Sequence, key: str) -> Iterator[Frame]:
        """The frames of ``sequence``, rendered into the cache first unless they are there already."""
        path = self.path(key)
        if not path.is_file() and not self._render(sequence, path):
            yield from sequence.frames()
            return
        yield from _read_entry(path, sequence.identity.name)

    def _render(self, sequence: Sequence, path: Path) -> bool:
        """Write ``sequence`` into ``path`` unless another process did; False when the cache cannot be written."""
        try:
            make_folder(path.parent)
            with filelock.FileLock(path.with_suffix(".lock")):
                if path.is_file():
                    return True
                temporary = path.with_name(f".{path.name}.{uuid.uuid4().hex[:12]}.tmp")
                try:
                    with temporary.open("xb") as handle:
                        _write_entry(handle, sequence)
                    os.replace(temporary, path)
                finally:
                    temporary.unlink(missing_ok=True)
        except Exception:
            return False
        return True


def _write_entry(handle: IO[bytes], sequence: Sequence) -> None:
    """The header, then each frame as a pickle of its own, so that each is read back on its own."""
    handle.write(pickle.dumps(_entry_header(sequence.identity, sequence.info), protocol=5))
    for frame in sequence.frames():
        handle.write(pickle.dumps(frame, protocol=5))


def _read_entry(path: Path, name: str) -> Iterator[Frame]:
    """Stream the frames of an entry; a damaged entry is removed and reported, naming its file."""
    try:
        handle = path.open("rb")
    except OSError as exc:
        raise DataError(f"{path}: cannot read the cached frames of {name}: {exc.strerror or exc}") from None
    with handle:
        count = None
        try:
            header = pickle.load(handle)
            count = header["frames"]
            index = 0
            while count is None or index < count:
                try:
                    frame = pickle.load(handle)
                except EOFError:
                    if count is None:
                        return
                    raise
                yield frame
                index += 1
        except (pickle.UnpicklingError, EOFError, KeyError, TypeError, AttributeError, ValueError) as exc:
            path.unlink(missing_ok=True)
            raise DataError(
                f"{path}: the cached frames of {name} are damaged ({type(exc).__name__}); "
                "the entry was removed and the next run renders it again"
            ) from None


@dataclass(frozen=True)
class CachedSequence(Sequence):
    """A sequence whose frames come from a :class:`FrameCache`; info, identity and conditions are the inner sequence's."""

    inner: Sequence
    cache: FrameCache
    key: str

    @property
    def info(self) -> SequenceInfo:
        return self.inner.info

    @property
    def identity(self) -> DatasetIdentity:
        return self.inner.identity

    def conditions(self) -> Mapping[str, Any]:
        return self.inner.conditions()

    def frames(self) -> Iterator[Frame]:
        return self.cache.frames(self.inner, self.key)

