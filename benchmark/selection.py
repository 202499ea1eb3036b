"""Choosing what to run: trackers, sequences, parameter overrides and cells.

A benchmark run is a set of cells, one per tracker x sequence x seed, where
the tracker reads the sequence's modality.  The user narrows the registry
with names on the command line (``--tracker``, ``--suite``, ``--dataset``),
changes parameters with ``TRACKER.KEY=VALUE`` overrides, and this module
turns those words into :class:`~benchmark.runner.Cell` objects.  Every name
it cannot resolve is an error that lists the names it knows, so a typo is
fixed from the message alone.

A ``--dataset`` is either the name of a registered sequence (``camera/S3``)
or the path of a file or folder a registered modality reads (an image
sequence file, an image folder, a video, a swath file), opened with
:func:`benchmark.io.open_sequence` and named in the results by the path as
the user wrote it.  Sequences are told apart by their identity
(:mod:`benchmark.identity`), not their names: ``seq.txt`` and
``../dir/seq.txt`` naming the same file are one dataset, run once under the
first name given.  A tracker meets a sequence when both name the same
modality; :func:`select_cells` does all of it for a :class:`Selection`.
"""

from __future__ import annotations

import dataclasses
import os
from collections import defaultdict
from collections.abc import Iterable, Iterator, Mapping
from typing import Any

from benchmark.closedloop.real_time import RealTime
from benchmark.errors import ParameterError, TrackbenchError
from benchmark.faults import Call
from benchmark.identity import DatasetIdentity
from benchmark.io import open_sequence
from benchmark.modality import Modality
from benchmark.model import Frame, Sequence, SequenceInfo
from benchmark.registry import Registry, SuiteEntry, TrackerEntry
from benchmark.runner import Cell, InitMode
from benchmark.training import Training, learns, overlap_error


MAX_CELLS = 1_000_000
"""The most cells one run makes: each is kept in memory until it ends and in the results database after."""


class SelectionError(TrackbenchError):
    """A tracker, suite or dataset name that nothing registered answers to."""


def _known(names: Iterable[str]) -> str:
    listed = ", ".join(sorted(names))
    return listed or "none"


def select_trackers(registry: Registry, names: Iterable[str] = ()) -> list[TrackerEntry]:
    """The registered trackers named, or all of them when no name is given.

    Parameters
    ----------
    registry : Registry
        The registry the plugins filled.
    names : iterable of str
        Tracker names; repeated names count once.

    Returns
    -------
    list of TrackerEntry
        In the order given, or in registration order for all.

    Raises
    ------
    SelectionError
        For a name no plugin registered, listing the known trackers.
    """
    wanted = list(dict.fromkeys(names))
    if not wanted:
        return list(registry.trackers.values())
    unknown = [name for name in wanted if name not in registry.trackers]
    if unknown:
        unavailable = "".join(f"; unavailable: {problem}" for problem in registry.problems)
        raise SelectionError(
            f"unknown tracker {', '.join(map(repr, unknown))} (known: {_known(registry.trackers)}{unavailable})"
        )
    return [registry.trackers[name] for name in wanted]


def parse_param_overrides(specs: Iterable[str]) -> dict[str, dict[str, str]]:
    """Parse ``TRACKER.KEY=VALUE`` words into ``{tracker: {key: value}}``.

    The tracker name is everything before the last dot of the left-hand
    side, so tracker names may contain dots; parameter names cannot.

    Raises
    ------
    ParameterError
        For a word without ``=`` or without a ``TRACKER.`` prefix.
    """
    overrides: dict[str, dict[str, str]] = {}
    for spec in specs:
        target, equals, value = spec.partition("=")
        tracker, dot, key = target.strip().rpartition(".")
        if not equals or not dot or not tracker or not key:
            raise ParameterError(f"--param {spec!r}: expected TRACKER.KEY=VALUE, e.g. hough.sigma=3")
        overrides.setdefault(tracker, {})[key] = value.strip()
    return overrides


def apply_param_overrides(
    entries: Iterable[TrackerEntry], overrides: Mapping[str, Mapping[str, str]]
) -> list[TrackerEntry]:
    """The entries with their parameter overrides applied.

    Parameters
    ----------
    entries : iterable of TrackerEntry
        The selected trackers.
    overrides : mapping
        ``{tracker: {parameter: value}}`` as from :func:`parse_param_overrides`;
        string values are converted to the type of the default.

    Returns
    -------
    list of TrackerEntry
        Same order; entries without overrides are returned unchanged.

    Raises
    ------
    ParameterError
        For an override of a tracker that is not selected, or of a parameter
        the tracker does not declare (the message names both).
    """
    selected = list(entries)
    names = {entry.name for entry in selected}
    stray = [name for name in overrides if name not in names]
    if stray:
        raise ParameterError(
            f"--param names tracker {', '.join(map(repr, stray))}, which is not selected "
            f"(selected: {_known(names)})"
        )
    return [entry.with_params(overrides[entry.name]) if entry.name in overrides else entry for entry in selected]


@dataclasses.dataclass(frozen=True)
class NamedSequence(Sequence):
    """A sequence shown under another name: a dataset path as the user wrote it."""

    inner: Sequence
    name: str

    @property
    def info(self) -> SequenceInfo:
        return dataclasses.replace(self.inner.info, name=self.name)

    @property
    def identity(self) -> DatasetIdentity:
        return self.inner.identity.renamed(self.name)

    def conditions(self) -> Mapping[str, Any]:
        return self.inner.conditions()

    def lacks(self, needs: Iterable[str]) -> dict[str, str]:
        return self.inner.lacks(needs)

    def frames(self) -> Iterator[Frame]:
        return self.inner.frames()


def open_dataset_path(path: str, modalities: Iterable[Modality]) -> Sequence:
    """Open a dataset file or folder with the reader of its modality, named by ``path`` as given.

    Raises
    ------
    DataError
        If nothing readable is at ``path`` (from :func:`benchmark.io.open_sequence`).
    """
    sequence = open_sequence(path, modalities)
    return sequence if sequence.identity.name == path else NamedSequence(sequence, path)


def select_sequences(registry: Registry, suites: Iterable[str] = (), datasets: Iterable[str] = ()) -> list[Sequence]:
    """The sequences of the named suites and datasets; every scored suite when none is named.

    Parameters
    ----------
    registry : Registry
        The registry the plugins filled.
    suites : iterable of str
        Suite names; each contributes all its sequences.
    datasets : iterable of str
        Registered sequence names (``suite/sequence``) or paths of files or
        folders a registered modality reads.

    Returns
    -------
    list of Sequence
        Suites first, then datasets, each dataset once (by identity, under
        the first name given).

    Raises
    ------
    SelectionError
        For a suite no plugin registered, or a dataset that is neither a
        registered sequence nor an existing path; both list the known names.
    DataError
        If an existing path cannot be read as a sequence.
    """
    suite_names = list(dict.fromkeys(suites))
    dataset_names = list(dict.fromkeys(datasets))
    if not suite_names and not dataset_names:
        suite_names = [name for name, suite in registry.suites.items() if suite.scored]
    unknown = [name for name in suite_names if name not in registry.suites]
    if unknown:
        raise SelectionError(f"unknown suite {', '.join(map(repr, unknown))} (known: {_known(registry.suites)})")
    chosen: dict[str, Sequence] = {}
    for name in suite_names:
        for sequence in registry.suites[name].sequences:
            chosen.setdefault(sequence.identity.key, sequence)
    registered = {seq.identity.name: seq for suite in registry.suites.values() for seq in suite.sequences}
    for name in dataset_names:
        if name in registered:
            sequence = registered[name]
        elif os.path.lexists(name):
            sequence = open_dataset_path(name, registry.modalities.values())
        else:
            raise SelectionError(
                f"unknown dataset {name!r}: not a registered sequence and no such file or folder "
                f"(registered: {_known(registered)})"
            )
        chosen.setdefault(sequence.identity.key, sequence)
    return list(chosen.values())


def make_cells(
    trackers: Iterable[TrackerEntry],
    sequences: Iterable[Sequence],
    seeds: Iterable[int],
    init: InitMode,
    modalities: Mapping[str, Modality],
) -> list[Cell]:
    """Every tracker x sequence x seed whose modalities match.

    Parameters
    ----------
    trackers : iterable of TrackerEntry
        Selected trackers, parameters already applied.
    sequences : iterable of Sequence
        Selected sequences.
    seeds : iterable of int
        Seeds of each (tracker, sequence) pair.
    init : {"truth", "none"}
        Initialise trackers from the first frame's ground truth, or not.
    modalities : Mapping
        The registered modalities by name; each cell carries its own.

    Returns
    -------
    list of Cell
        Ordered by tracker, then sequence, then seed.

    Raises
    ------
    SelectionError
        If no tracker reads the modality of any selected sequence, or the
        cells would be more than :data:`MAX_CELLS`.
    """
    tracker_list = list(trackers)
    sequence_list = list(sequences)
    seed_list = seeds if isinstance(seeds, range) else list(seeds)
    pairs = sum(1 for t in tracker_list for s in sequence_list if s.identity.modality == t.modality)
    if pairs * len(seed_list) > MAX_CELLS:
        raise SelectionError(
            f"{pairs:,} tracker and sequence pairs x {len(seed_list):,} seeds make more cells than one run holds "
            f"({MAX_CELLS:,}); run fewer seeds, or fewer trackers or suites at a time"
        )
    cells = [
        Cell(tracker, sequence, seed, init, modality=modalities[tracker.modality])
        for tracker in tracker_list
        for sequence in sequence_list
        if sequence.identity.modality == tracker.modality
        for seed in seed_list
    ]
    if not cells and seed_list:
        tracker_modalities = _known({f"{t.name} ({t.modality})" for t in tracker_list})
        sequence_modalities = _known({f"{s.identity.name} ({s.identity.modality})" for s in sequence_list})
        raise SelectionError(
            "nothing to run: no selected tracker reads the modality of a selected sequence "
            f"(trackers: {tracker_modalities}; sequences: {sequence_modalities})"
        )
    return cells


def unmet_needs(cells: Iterable[Cell]) -> tuple[list[Cell], list[str]]:
    """The cells whose tracker can run on their sequence, and a line for each pair that cannot.

    A tracker declares the :class:`~benchmark.model.SequenceInfo` fields
    it cannot run without (:attr:`benchmark.tracker.Tracker.needs`); each
    sequence is asked once which of them it lacks
    (:meth:`benchmark.model.Sequence.lacks`), reading no frame.  The cells
    of a pair that lacks one are dropped, every seed of it, so that they
    are reported once before the run instead of failing cell by cell.

    Returns
    -------
    tuple of (list of Cell, list of str)
        The runnable cells in their order, and one line per tracker,
        dataset and missing field, e.g. ``"foresti_ekf cannot run on
        S.txt: it needs camera calibration: add focal_px, pipe_diameter_m,
        tilt_deg under [camera] in S.toml"``.
    """
    runnable: list[Cell] = []
    lacking: dict[tuple[str, tuple[str, ...]], dict[str, str]] = {}
    problems: dict[str, None] = {}
    for cell in cells:
        needs = tuple(cell.tracker.tracker_class.needs)
        if not needs:
            runnable.append(cell)
            continue
        asked = (cell.identity.key, needs)
        if asked not in lacking:
            # A sequence that cannot say is left to its cells, which then fail reading the info with their own message.
            answer = Call.of(lambda: cell.sequence.lacks(needs), "asking what the sequence lacks")
            lacking[asked] = answer.result if answer.ok and answer.result is not None else {}
        if not lacking[asked]:
            runnable.append(cell)
        for what in lacking[asked].values():
            problems.setdefault(f"{cell.tracker.name} cannot run on {cell.dataset}: it needs {what}")
    return runnable, list(problems)


@dataclasses.dataclass(frozen=True)
class Selection:
    """What a run covers, in the words of the command line.

    Attributes
    ----------
    trackers, suites, datasets : tuple of str
        Names as ``--tracker``, ``--suite`` and ``--dataset`` give them; no
        tracker means all, no suite and no dataset means every suite.
    params : tuple of str
        ``TRACKER.KEY=VALUE`` overrides.
    seeds : int
        Seeds ``0 .. seeds - 1`` of every tracker and sequence.
    init : {"truth", "none"}
        Initialise trackers from the first frame's ground truth, or not.
    train : tuple of str
        Suites, registered sequences or sequence paths (``--train``) that
        train every tracker that learns, instead of the ``training`` suite
        each scored suite names.
    real_time : bool
        Run the closed-loop sequences in real time (``--real-time``;
        :mod:`benchmark.closedloop.real_time`).
    step_times : tuple of str
        ``TRACKER=MS`` words (``--step-time``): a tracker's declared step
        time in real time; the others' is measured.
    """

    trackers: tuple[str, ...] = ()
    suites: tuple[str, ...] = ()
    datasets: tuple[str, ...] = ()
    params: tuple[str, ...] = ()
    seeds: int = 1
    init: InitMode = "truth"
    train: tuple[str, ...] = ()
    real_time: bool = False
    step_times: tuple[str, ...] = ()


def select_cells(registry: Registry, selection: Selection) -> list[Cell]:
    """The cells a selection asks for, every name and parameter checked before any cell runs.

    Raises
    ------
    SelectionError
        For a name nothing registered answers to, or nothing to run.
    ParameterError
        For a malformed, unknown or invalid ``--param``.
    DataError
        For a dataset path that cannot be read.
    """
    overrides = parse_param_overrides(selection.params)
    entries = apply_param_overrides(select_trackers(registry, selection.trackers), overrides)
    sequences = select_sequences(registry, selection.suites, selection.datasets)
    cells = make_cells(entries, sequences, range(selection.seeds), selection.init, registry.modalities)
    if selection.step_times and not selection.real_time:
        raise ParameterError("--step-time declares a step time for --real-time runs; add --real-time")
    cells = in_real_time(cells, selection.step_times) if selection.real_time else cells
    return plan_training(registry, cells, selection.train)


def in_real_time(cells: Iterable[Cell], step_times: Iterable[str] = ()) -> list[Cell]:
    """The cells, each run in real time with its tracker's declared step time, or its measured one.

    Parameters
    ----------
    cells : iterable of Cell
        Cells of closed-loop sequences.
    step_times : iterable of str
        ``TRACKER=MS`` words: the declared step time of a selected tracker,
        in milliseconds; a tracker not named has its step time measured
        (:class:`benchmark.closedloop.real_time.StepClock`).

    Raises
    ------
    SelectionError
        If a cell's sequence is open loop: real time only means something
        where the frames depend on the estimates, so an open-loop suite is
        refused rather than run in the ordinary way under a real-time run.
    ParameterError
        For a malformed word, a step time that is not a positive number of
        milliseconds, or a tracker that is not selected.
    """
    cells = list(cells)
    open_loop = sorted({cell.dataset for cell in cells if not cell.sequence.closed_loop})
    if open_loop:
        shown = ", ".join(open_loop[:5]) + (f" and {len(open_loop) - 5} more" if len(open_loop) > 5 else "")
        raise SelectionError(
            f"--real-time runs closed-loop sequences only (such as --suite routes); open loop: {shown}"
        )
    declared: dict[str, float] = {}
    for word in step_times:
        tracker, equals, value = (part.strip() for part in word.partition("="))
        try:
            if not (equals and tracker):
                raise ValueError(word)
            declared[tracker] = RealTime(float(value)).declared_ms  # type: ignore[assignment]
        except ValueError:  # pydantic's ValidationError is one
            raise ParameterError(
                f"--step-time {word!r}: expected TRACKER=MS, MS a positive number of milliseconds, e.g. hough=17"
            ) from None
    selected = {cell.tracker.name for cell in cells}
    stray = sorted(set(declared) - selected)
    if stray:
        raise ParameterError(
            f"--step-time names tracker {', '.join(map(repr, stray))}, which is not selected "
            f"(selected: {_known(selected)})"
        )
    return [dataclasses.replace(cell, real_time=RealTime(declared.get(cell.tracker.name))) for cell in cells]


def plan_training(registry: Registry, cells: Iterable[Cell], train: Iterable[str] = ()) -> list[Cell]:
    """The cells, each of a tracker that learns with its planned :class:`~benchmark.training.Training`.

    The training set is ``train`` (suite names, registered sequence names or
    sequence paths) when given, else the ``training`` suite of the scored
    sequence's suite; only the sequences of the tracker's modality count.
    A cell that cannot be trained gets a refused training naming why (no
    training set, a set without sequences of its modality, a set holding a
    sequence the tracker is scored on), so that it ends as an error row
    while the other cells run.

    Raises
    ------
    SelectionError
        For a ``train`` word that names nothing (:func:`select_sequences`).
    DataError
        For a ``train`` path that cannot be read.
    """
    cells = list(cells)
    words = list(dict.fromkeys(train))
    given: tuple[str, list[Sequence]] | None = None
    if words:
        suites = [word for word in words if word in registry.suites]
        datasets = [word for word in words if word not in registry.suites]
        given = ", ".join(words), select_sequences(registry, suites, datasets)
    suite_of = {seq.identity.key: suite for suite in registry.suites.values() for seq in suite.sequences}
    scored: dict[str, list[Sequence]] = defaultdict(list)
    for cell in cells:
        scored[cell.tracker.cache_key].append(cell.sequence)
    planned = []
    for cell in cells:
        if learns(cell.tracker):
            cell = dataclasses.replace(cell, training=_training_of(registry, cell, given, suite_of, scored))
        planned.append(cell)
    return planned


def _training_of(
    registry: Registry,
    cell: Cell,
    given: tuple[str, list[Sequence]] | None,
    suite_of: Mapping[str, SuiteEntry],
    scored: Mapping[str, list[Sequence]],
) -> Training:
    """The training of one learning cell (see :func:`plan_training`)."""
    entry = cell.tracker
    if given is not None:
        name, sequences = given
    else:
        suite = suite_of.get(cell.identity.key)
        name = "" if suite is None or suite.training is None else suite.training
        where = f"suite {suite.name!r}" if suite is not None else f"dataset {cell.dataset!r}"
        if not name:
            return Training.refused(
                "", f"tracker {entry.name!r} learns from labelled sequences, but {where} names no training suite; "
                "give one with --train SUITE_OR_PATH"
            )
        if name not in registry.suites:
            return Training.refused(name, f"{where} names training suite {name!r}, which no plugin registered")
        sequences = list(registry.suites[name].sequences)
    mine = [sequence for sequence in sequences if sequence.identity.modality == entry.modality]
    if not mine:
        return Training.refused(name, f"training set {name!r} holds no {entry.modality} sequence")
    training = Training.plan(entry, name, mine)
    error = overlap_error(training, scored[entry.cache_key])
    return Training.refused(name, error) if error else training
