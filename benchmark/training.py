"""Training the trackers that learn, once per run, on sequences the run does not score.

A tracker that learns (:class:`benchmark.tracker.Learns`, e.g. ``texture``)
is fitted before its cells run.  Its training set is what ``trackbench run
--train`` names (suites, registered sequences or sequence files made
elsewhere), or else the ``training`` suite of the scored sequence's suite
(``camera`` and ``camera-clutter`` name ``camera-train``: S1-S7 drawn with
other seeds).  Selection plans a :class:`Training` per learning cell
(:func:`benchmark.selection.select_cells`); the harness then calls
:func:`fit_models` on the cells left to run, which

* refuses a training set that shares a sequence (by identity, not by name)
  with the sequences the tracker is scored on, so that training never sees
  a scored frame;
* fits each (tracker version and parameters, training set) once, in a
  worker process under the cells' time limit, seeded by that pair, and
  stores the model as ``OUT/models/TRACKER-KEY.model``, written
  atomically: a record of :mod:`benchmark.storage` (data only, never
  code; so a model is built of the values a record may hold), naming the
  tracker and the key.  A model already there is reused when it passes
  those checks: ``--resume`` does not retrain, and neither does a second
  run into the same folder; a damaged or foreign one is removed and
  fitted again;
* hands every cell the stored model's path, or the reason training failed.

Each cell's fresh tracker adopts the model (:meth:`Training.load`, cached
once per process) before ``reset``; a cell whose training failed is an
error row like any other, its message naming the training set.  The
training set is part of a cell's identity (:attr:`Training.key` joins the
tracker's cache key) and its name is shown on the board's ``training``
column.
"""

from __future__ import annotations

import dataclasses
import functools
import hashlib
import time
import zlib
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from benchmark import storage
from benchmark.errors import TrackbenchError
from benchmark.files import make_folder, write_bytes_atomically
from benchmark.model import Sequence as FrameSequence
from benchmark.registry import TrackerEntry

MODELS_FOLDER = "models"
"""Folder of the results folder that holds the fitted models."""
MODEL_SUFFIX = ".model"


class TrainingError(TrackbenchError):
    """A learning tracker could not be trained: no training set, an overlap with the scored data, a failed fit."""


def learns(entry: TrackerEntry) -> bool:
    """Whether the tracker defines ``fit`` and ``use_model`` (:class:`benchmark.tracker.Learns`)."""
    cls = entry.tracker_class
    return callable(getattr(cls, "fit", None)) and callable(getattr(cls, "use_model", None))


@dataclass(frozen=True)
class Training:
    """The training of one learning tracker on one training set, as its cells carry it.

    Attributes
    ----------
    name : str
        The training set as the board shows it: a suite name, or the
        ``--train`` words joined by ``", "``.
    key : str
        Hash of the tracker's cache key and the training sequences'
        identities: the model's name on disk and part of the cells' identity.
    sequences : tuple of Sequence
        The training sequences, until the model is fitted (then empty, so
        that cells do not carry them to the workers).
    model_path : pathlib.Path or None
        The stored model, once fitted.
    error : str
        Why the tracker cannot be trained; its cells end in this error.
    packages : frozenset of str
        Where the model's types may come from (:func:`benchmark.storage.packages_of` the tracker's class).
    seed : int
        Seeds the fit with the tracker's name (:func:`fit_model`).
    """

    name: str
    key: str
    sequences: tuple[FrameSequence, ...] = ()
    model_path: Path | None = None
    error: str = ""
    packages: storage.Packages = frozenset()
    seed: int = 0

    @classmethod
    def plan(cls, entry: TrackerEntry, name: str, sequences: Iterable[FrameSequence]) -> Training:
        """The training of ``entry`` on ``sequences``, keyed by the tracker (its code too) and the sequences' identities.

        The fit's seed comes from the same without the code: an edit of the
        tracker fits its model again, with the same generator.
        """
        items = tuple(sequences)
        identities = sorted(sequence.identity.key for sequence in items)

        def hashed(tracker_key: str) -> str:
            return hashlib.sha256("\n".join([tracker_key, *identities]).encode()).hexdigest()[:16]

        seed = int(hashed(entry.params_key)[:15], 16)
        return cls(name, hashed(entry.cache_key), items, packages=storage.packages_of(entry.tracker_class), seed=seed)

    @classmethod
    def refused(cls, name: str, error: str) -> Training:
        """A training that cannot happen, for the reason ``error``."""
        return cls(name, "untrained-" + hashlib.sha256(error.encode()).hexdigest()[:8], error=error)

    def load(self) -> Any:
        """The fitted model.

        Raises
        ------
        TrainingError
            With the reason training failed, or if the stored model cannot be read, naming its file.
        """
        if self.error:
            raise TrainingError(self.error)
        if self.model_path is None:
            raise TrainingError(f"the model of training set {self.name!r} was never fitted")
        try:
            stat = self.model_path.stat()
        except OSError as exc:
            raise TrainingError(f"{self.model_path}: cannot read the fitted model: {exc.strerror or exc}") from None
        version = (stat.st_dev, stat.st_ino, stat.st_size, stat.st_mtime_ns)
        return _read_model(str(self.model_path), version, self.key, self.packages)


@functools.lru_cache(maxsize=4)
def _read_model(path: str, version: tuple[int, ...], key: str, packages: storage.Packages) -> Any:
    """The model stored in ``path`` for training ``key``, read once per process and version of the file.

    Raises
    ------
    TrainingError
        Naming the file, when it cannot be read, is damaged, or holds another training's model.
    """
    try:
        with open(path, "rb") as handle:
            stored = storage.loads(handle.read(), packages, path)
    except OSError as exc:
        raise TrainingError(f"{path}: cannot read the fitted model: {exc.strerror or exc}") from None
    except storage.StorageError as exc:
        raise TrainingError(f"cannot read the fitted model: {exc}") from None
    if not isinstance(stored, dict) or stored.get("key") != key:
        raise TrainingError(f"{path}: not the model of training {key}")
    return stored["model"]


def overlap_error(training: Training, scored: Iterable[FrameSequence]) -> str:
    """The error for a training set that holds a scored sequence, or ``""`` when it holds none."""
    inside = {sequence.identity.key for sequence in training.sequences}
    shared = sorted({sequence.identity.name for sequence in scored if sequence.identity.key in inside})
    if not shared:
        return ""
    return (
        f"training set {training.name!r} holds sequence(s) this run scores: {', '.join(shared)}; "
        "train on other sequences (--train)"
    )


def fit_model(entry: TrackerEntry, sequences: Sequence[FrameSequence], key: str, seed: int) -> bytes:
    """Fit a fresh tracker on ``sequences`` and return its model as a record (:mod:`benchmark.storage`).

    The generator is seeded by the tracker's name and ``seed``
    (:attr:`Training.seed`), so the same tracker on the same training set
    fits the same model; ``key`` names the training in the record.

    Raises
    ------
    benchmark.storage.StorageError
        If the model holds a value a record cannot.
    """
    rng = np.random.default_rng([zlib.crc32(entry.name.encode()), seed])
    model = entry.create().fit(list(sequences), rng)  # type: ignore[attr-defined]
    stored = {"tracker": entry.name, "key": key, "model": model}
    return storage.dumps(stored, storage.packages_of(entry.tracker_class))


Runner = Callable[[Callable[..., bytes], tuple[Any, ...], float | None], bytes]
"""Runs ``function(*args)`` under a time limit (in a worker process, or in this one) and returns its result."""


def fit_models(
    cells: Sequence[Any],
    out: Path,
    run: Runner,
    timeout_s: float | None = None,
    log: Callable[[str], None] = lambda line: None,
) -> list[Any]:
    """The cells with every planned training fitted (or reused) and replaced by its stored model.

    Parameters
    ----------
    cells : sequence of Cell
        Cells to run; those whose ``training`` is planned get a model.
    out : pathlib.Path
        The results folder; models go to ``out/models``.
    run : callable
        Runs the fit (:func:`benchmark.runner.run_isolated`).
    timeout_s : float, optional
        Time limit of each fit.
    log : callable
        Receives a line per training set fitted, reused or failed.

    Returns
    -------
    list of Cell
        In the same order; each cell's ``training`` now has a ``model_path``
        or an ``error``.
    """
    fitted: dict[str, Training] = {}
    result = []
    for cell in cells:
        training = cell.training
        if training is not None and not training.error and training.model_path is None:
            if training.key not in fitted:
                fitted[training.key] = _fit_once(cell.tracker, training, out, run, timeout_s, log)
            cell = dataclasses.replace(cell, training=fitted[training.key])
        result.append(cell)
    return result


def _fit_once(
    entry: TrackerEntry,
    training: Training,
    out: Path,
    run: Runner,
    timeout_s: float | None,
    log: Callable[[str], None],
) -> Training:
    """Fit ``entry`` on ``training`` unless its model is stored already; the training the cells carry."""
    path = out / MODELS_FOLDER / f"{entry.name}-{training.key}{MODEL_SUFFIX}"
    what = f"{entry.name} on {training.name} ({len(training.sequences)} sequences)"
    if path.is_file():
        stored = dataclasses.replace(training, sequences=(), model_path=path)
        try:
            stored.load()
        except TrainingError as exc:
            log(f"training: {what}: {exc}; fitting it again")
            path.unlink(missing_ok=True)
        else:
            log(f"training: {what}: reusing {path}")
            return stored
    log(f"training: {what}: fitting")
    started = time.perf_counter()
    try:
        model = run(fit_model, (entry, training.sequences, training.key, training.seed), timeout_s)
        write_bytes_atomically(make_folder(path.parent) / path.name, model, "fitted model")
    except Exception as exc:
        message = f"training on {training.name} failed: {type(exc).__name__}: {' '.join(str(exc).split())}"
        log(f"training: {what}: {message}")
        return dataclasses.replace(training, sequences=(), error=message)
    log(f"training: {what}: fitted in {time.perf_counter() - started:.1f} s, stored as {path}")
    return dataclasses.replace(training, sequences=(), model_path=path)
