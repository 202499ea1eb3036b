"""The subjects ``trackbench speed`` times, chosen by name and made ready: frames read, model trained.

A subject is a registered tracker with at least one declared bound, or a
core component a plugin declares with its own ``ours`` workload.  Its
frames come from the dataset its bounds name, through the frame cache
(:class:`benchmark.frame_cache.FrameCache`), so a sequence is rendered once
for every command and run.  A tracker that learns is fitted in process on
the training split its dataset's suite names, as a run would plan and fit
it (:func:`benchmark.selection.plan_training`,
:func:`benchmark.training.fit_model`), and the model is kept in the frame
cache's folder for the next time.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Iterable
from pathlib import Path
from typing import Any

import numpy as np

from benchmark.files import make_folder
from benchmark.frame_cache import FrameCache
from benchmark.registry import Registry, TrackerEntry
from benchmark.selection import SelectionError, make_cells, plan_training, select_sequences
from benchmark.speed.bounds import BoundContext, SpeedBounds, Workload, WorkloadFactory
from benchmark.speed.measure import Subject, read_frames
from benchmark.text import printable
from benchmark.training import fit_model, learns


def chosen_subjects(bounds: SpeedBounds, names: Iterable[str]) -> list[str]:
    """The subjects named, in the order named, or all in alphabetical order (not the plugins' load order), checked.

    Raises
    ------
    SelectionError
        For a name no plugin declared a speed bound for, listing those it did.
    """
    known = sorted(bounds.subjects, key=str.casefold)
    wanted = list(dict.fromkeys(names)) or known
    unknown = [name for name in wanted if name not in known]
    if unknown:
        listed = ", ".join(printable(name) for name in known) or "none"
        raise SelectionError(
            f"no speed bound is declared for {', '.join(repr(printable(n)) for n in unknown)}; "
            f"subjects with a bound: {listed}"
        )
    return wanted


class TrackerWorkload:
    """A registered tracker as a workload: a fresh instance on every reset, its model adopted."""

    def __init__(self, entry: TrackerEntry, model: Any = None) -> None:
        self.entry = entry
        self.model = model
        self.tracker: Any = None

    def reset(self, info: Any, rng: np.random.Generator, init: Any = None) -> None:
        self.tracker = self.entry.create()
        if self.model is not None:
            self.tracker.use_model(self.model)
        self.tracker.reset(info, rng, init=init)

    def step(self, frame: Any) -> Any:
        return self.tracker.step(frame)


MODELS = "models"
"""The folder of the frame cache that keeps the models ``trackbench speed`` fitted, by training key."""


def _trained_model(registry: Registry, entry: TrackerEntry, sequence: Any, cache: FrameCache) -> Any:
    """The model a run would give ``entry`` for ``sequence``; None for a tracker that does not learn.

    It is fitted as a run fits it (:func:`benchmark.training.fit_model`:
    the planned training set, the same seed) and kept in the frame cache's
    :data:`MODELS` folder under its training key, which changes with the
    tracker's code, parameters and training sequences.
    """
    if not learns(entry):
        return None
    (cell,) = plan_training(registry, make_cells([entry], [sequence], [0], "truth", registry.modalities))
    training = cell.training
    if training is None or training.error:
        reason = training.error if training is not None else "no training planned"
        raise SelectionError(f"cannot train {entry.name!r} for {sequence.identity.name}: {reason}")
    path = make_folder(cache.folder / MODELS) / f"{training.key}.model"
    if not path.is_file():
        record = fit_model(entry, [cache.wrap(seq) for seq in training.sequences], training.key, training.seed)
        partial = path.with_suffix(".tmp")
        partial.write_bytes(record)
        partial.replace(path)
    return dataclasses.replace(training, model_path=path).load()


def prepare_subject(registry: Registry, bounds: SpeedBounds, name: str, frames: int, cache: Path | None) -> Subject:
    """Subject ``name`` ready to time: the first ``frames`` frames of its dataset in memory, its model fitted.

    Raises
    ------
    SelectionError
        If its dataset or tracker is not registered, or its tracker cannot be trained.
    """
    declared = bounds.of(name)
    first = declared[0]
    (sequence,) = select_sequences(registry, (), (first.dataset,))
    frame_cache = FrameCache(cache)
    sequence_in_cache = frame_cache.wrap(sequence)
    info = sequence_in_cache.info
    ours: WorkloadFactory
    if first.ours is None:
        if name not in registry.trackers:
            raise SelectionError(
                f"speed bounds name tracker {name!r}, which is not registered (is its plugin disabled?)"
            )
        entry = registry.trackers[name]
        model = _trained_model(registry, entry, sequence, frame_cache)
        context = BoundContext(entry.params, info, model)

        def ours(context: BoundContext) -> Workload:
            return TrackerWorkload(entry, model)

    else:
        context = BoundContext(None, info)
        ours = first.ours
    held = read_frames(sequence_in_cache.frames(), frames)
    if not held:
        raise SelectionError(f"sequence {first.dataset!r} has no frames")
    return Subject(
        name,
        first.dataset,
        held,
        held[0].truth,
        context,
        ours,
        tuple(declared),
        sequence.identity.seed_material,
    )
