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
    One file per sequence, ``KEY.frames``: records of :mod:`benchmark.storage`
    (data only, never code), a header naming the key, the sequence, its
    modality and frame count, then one record per
    :class:`~benchmark.model.Frame`.  Reading one frame is one record read
    from a buffered file, so memory stays flat in the length of the
    sequence.  Reading a 320 x 240 camera frame back takes about 40 us,
    against 15-20 us for the pickles this format replaced and 2.4 ms to
    render it (``benchmarks/test_scale.py``).
    The file is written under a temporary name and renamed when complete,
    while a lock (``KEY.lock``) makes the other processes that want the same
    sequence wait for it instead of rendering it again.
Checked on every read
    Each record's checksum, the header's key against the entry's name (an
    entry copied over another's is not served under its name) and each
    frame's index.  An entry that fails is removed and the sequence rendered
    again, into the cache when it can be written, and the reader carries on
    from the frame it had reached, with a :class:`CacheWarning`
    naming the file: a damaged cache costs time, never a wrong frame.
When the cache cannot be written
    (a full disk, a read-only folder), or rendering fails part way, the
    frames are rendered and streamed as if there were no cache, so that a
    rendering error reaches the cell at the frame it concerns: the cache
    saves time, it is never a reason for a cell to fail.
"""

from __future__ import annotations

import itertools
import os
import uuid
import warnings
from collections.abc import Iterable, Iterator, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import IO, Any

import filelock

from benchmark import storage
from benchmark.errors import DataError
from benchmark.files import make_folder
from benchmark.identity import DatasetIdentity, code_digest, digest
from benchmark.model import Frame, Sequence, SequenceInfo
from benchmark.storage import StorageError

CACHE_ENV = "TRACKBENCH_CACHE"
"""Environment variable naming the cache folder, in place of the platform's default."""
FORMAT = 2
"""Version of the entry format; a new one gives new keys."""
SUFFIX = ".frames"
_HEADER_PACKAGES: storage.Packages = frozenset()


class CacheWarning(UserWarning):
    """A cache entry failed its checks and was rendered again, or a sequence's frames could not be cached."""


def default_cache_folder() -> Path:
    """The frame cache's folder: ``$TRACKBENCH_CACHE``, or ``frames`` in the platform's user cache folder."""
    named = os.environ.get(CACHE_ENV)
    if named:
        return Path(named)
    import platformdirs

    return Path(platformdirs.user_cache_dir("trackbench")) / "frames"


def _entry_header(key: str, identity: DatasetIdentity, info: SequenceInfo) -> dict[str, Any]:
    return {"format": FORMAT, "key": key, "name": identity.name, "modality": identity.modality, "frames": info.n_frames}


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
        return digest(FORMAT, sequence.identity.key, code_digest(type(sequence).__module__))

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
                    header = storage.read(handle, _HEADER_PACKAGES, str(path))
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
        """The frames of ``sequence``, rendered into the cache first unless they are there already.

        An entry that fails its checks is removed and rendered again (once;
        then the frames are rendered without the cache), and the frames
        carry on from the one reached, with a :class:`CacheWarning`.
        """
        path = self.path(key)
        served = 0
        for _ in range(2):
            if not path.is_file() and not self._render(sequence, path, key):
                break
            try:
                for frame in _read_entry(path, key, sequence, skip=served):
                    yield frame
                    served += 1
                return
            except StorageError as exc:
                warnings.warn(
                    CacheWarning(f"{exc}; the entry was removed and {sequence.identity.name} rendered again"),
                    stacklevel=2,
                )
            except OSError:
                break
        yield from itertools.islice(sequence.frames(), served, None)

    def _render(self, sequence: Sequence, path: Path, key: str) -> bool:
        """Write ``sequence`` into ``path`` unless another process did; False when the cache cannot be written."""
        try:
            make_folder(path.parent)
            with filelock.FileLock(path.with_suffix(".lock")):
                if path.is_file():
                    return True
                temporary = path.with_name(f".{path.name}.{uuid.uuid4().hex[:12]}.tmp")
                try:
                    with temporary.open("xb") as handle:
                        _write_entry(handle, sequence, key)
                    os.replace(temporary, path)
                finally:
                    temporary.unlink(missing_ok=True)
        except StorageError as exc:
            warnings.warn(CacheWarning(f"{sequence.identity.name}: frames not cached: {exc}"), stacklevel=3)
            return False
        except Exception:
            return False
        return True


def _write_entry(handle: IO[bytes], sequence: Sequence, key: str) -> None:
    """The header, then each frame as a record of its own, so that each is read back on its own."""
    storage.write(handle, _entry_header(key, sequence.identity, sequence.info), _HEADER_PACKAGES)
    packages = storage.packages_of(type(sequence))
    for frame in sequence.frames():
        storage.write(handle, frame, packages)


def _read_entry(path: Path, key: str, sequence: Sequence, skip: int = 0) -> Iterator[Frame]:
    """Stream the frames of an entry from frame ``skip`` on, checking it is ``key``'s.

    Raises
    ------
    StorageError
        Naming the file, when a record is damaged or the entry is not
        ``key``'s; the file is removed first (unless it was replaced
        meanwhile by another process).
    OSError
        When the file cannot be opened or read.
    """
    source = str(path)
    packages = storage.packages_of(type(sequence))
    with path.open("rb") as handle:
        try:
            header = _read_header(handle, key, sequence.identity.name, source)
            count = header["frames"]
            for index in itertools.count():
                if count is not None and index >= count:
                    return
                try:
                    frame = storage.read(handle, packages, source)
                except EOFError:
                    if count is None:
                        return
                    raise StorageError(f"{source}: {count} frames announced, {index} found") from None
                if not isinstance(frame, Frame) or frame.index != index:
                    raise StorageError(f"{source}: record {index + 1} is not frame {index}")
                if index >= skip:
                    yield frame
        except StorageError:
            _remove_if_same(path, os.fstat(handle.fileno()))
            raise


def _read_header(handle: IO[bytes], key: str, name: str, source: str) -> dict[str, Any]:
    try:
        header = storage.read(handle, _HEADER_PACKAGES, source)
    except EOFError:
        raise StorageError(f"{source}: empty") from None
    if not isinstance(header, dict) or header.get("format") != FORMAT or header.get("key") != key:
        found = header.get("name") if isinstance(header, dict) else None
        raise StorageError(f"{source}: the entry holds {found or 'something else'}, not {name} as its name says")
    return header


def _remove_if_same(path: Path, opened: os.stat_result) -> None:
    """Remove ``path`` if it is still the file opened (another process may have replaced it since)."""
    try:
        now = path.stat()
        if (now.st_dev, now.st_ino) == (opened.st_dev, opened.st_ino):
            path.unlink()
    except OSError:
        pass


@dataclass(frozen=True)
class CachedSequence(Sequence):
    """A sequence whose frames come from a :class:`FrameCache`; info, identity, conditions and what it lacks are the inner sequence's."""

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

    def lacks(self, needs: Iterable[str]) -> dict[str, str]:
        return self.inner.lacks(needs)

    def frames(self) -> Iterator[Frame]:
        return self.cache.frames(self.inner, self.key)

