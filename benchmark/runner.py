"""Running cells: one tracker on one sequence with one seed, failures isolated.

A *cell* is the unit of work of the benchmark: a registered tracker (with
its parameters), a sequence of the tracker's modality and a seed,
initialised either from the first frame's ground truth or from nothing.
:func:`run_cell` creates a fresh tracker, reads the sequence's info and
first frame, calls ``reset(info, rng, init)`` and then ``step`` once per
frame, scoring each frame as it goes with the scorer of the cell's modality
(:class:`benchmark.modality.Modality`; the camera rule is seeds/004,
section VI-C, Table V).  A frame whose observation or truth is not of the
modality's types is a data error, so trackers can rely on them.  Timing
covers ``step`` only, so frames per second compare trackers rather than
image decoders, as in the thesis' Table 5.3 (seeds/000, section 5.2.5).
A step's time is the CPU time of the thread that runs it
(:func:`time.thread_time`), with its wall time kept beside it: a worker
runs OpenCV, BLAS and numba on one native thread
(:func:`benchmark.workers.limit_native_threads`), so the thread's CPU time
is the tracker's own work, which other processes on the machine do not
stretch as they stretch the wall time.

Where the modality draws frames (:attr:`benchmark.modality.Modality.draw`),
the first frame of each run of failures (consecutive frames that are all
false or all missed) is drawn with its truth and the tracker's estimate
right after it is scored, up to :data:`MAX_PICTURES` per cell, and kept in
the result as a PNG (:class:`benchmark.results.Picture`), so that a report
shows why a number moved.  Drawing is not timed, and a drawer that fails
costs only its picture: the cell and its scores stay as they are.

A cell is identified by its dataset's identity (:mod:`benchmark.identity`),
which is known without reading a frame: all reading of the cell's data
happens in :func:`run_cell`, inside the cell's time limit.  The generator of
a cell is seeded from the seed, the CRC-32 of the tracker's name and the
dataset's fingerprint, so that a seed replays a cell bit for bit and
different cells draw independent streams.

Nothing a cell does stops the others.  Whatever a tracker raises, of any
class (``SystemExit`` and ``KeyboardInterrupt`` included), whatever invalid
estimate it returns, and any error reading a frame, turns the cell into a
result with status ``"error"`` and a message ``"ExceptionType: message
(frame k)"``; a cell that runs past its time limit gets status
``"timeout"``.  Frames scored before the failure stay in the result.  Each
phase of a cell (reading its info, creating the tracker, reset, each frame,
each read) is a :class:`benchmark.faults.Call`, and the first that fails
is the cell's ending: its message names the phase.

:func:`benchmark.executors.run_cells` runs every cell on an executor,
by default in a worker process of a local pool: a worker still busy a
grace period after the limit is killed, and one that exits or crashes
(``os._exit``, a segmentation fault) costs only its cell.
``in_process=True`` runs the cells in the calling process instead, for
debuggers and profilers: there a ``step`` that never returns cannot be
stopped, and a tracker that ends the process ends the run.  Only the
user's own Ctrl-C (:class:`~benchmark.faults.UserInterrupt`) stops a run.
"""

from __future__ import annotations

import dataclasses
import functools
import math
import signal
import threading
import time
import zlib
from collections.abc import Iterable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from typing import Any, Literal, Protocol

import numpy as np

from benchmark import shared_modules
from benchmark.closedloop.real_time import RealTime
from benchmark.drawing import encode_png
from benchmark.faults import Call, Stopped, UserInterrupt, safe_text
from benchmark.identity import DatasetIdentity
from benchmark.modality import Drawer, EstimateError, Modality
from benchmark.model import Frame, Outcome, Sequence, SequenceInfo
from benchmark.registry import TrackerEntry
from benchmark.results import CellKey, CellResult, FrameScore, Picture, Status
from benchmark.tracker import Tracker
from benchmark.training import Training
from benchmark.workers import cell_isolation

InitMode = Literal["truth", "none"]
DEFAULT_TIMEOUT_S = 600.0
"""Time limit of one cell unless the caller sets another."""

MAX_PICTURES = 6
"""Most pictures of failed frames one cell keeps."""

_FAILURES = (Outcome.FALSE, Outcome.MISSED)


@dataclass(frozen=True)
class Cell:
    """One tracker x sequence x seed, with its initialisation mode.

    Attributes
    ----------
    tracker : TrackerEntry
        The registered tracker with the parameters to run it with.
    sequence : Sequence
        The frames; must be picklable to run in a worker process.
    seed : int
        Seed of the cell's generator.
    init : {"truth", "none"}
        ``"truth"`` hands the first frame's ground truth to ``reset``.
    modality : Modality
        The modality of tracker and sequence: frame types and scorer
        (keyword only).
    training : Training or None
        For a tracker that learns: its training set, then its fitted model
        (:mod:`benchmark.training`; keyword only).
    real_time : RealTime or None
        Real-time mode and the source of the tracker's step time
        (:mod:`benchmark.closedloop.real_time`; keyword only), for a
        closed-loop sequence only; None runs the ordinary cell.
    """

    tracker: TrackerEntry
    sequence: Sequence
    seed: int
    init: InitMode = "truth"
    modality: Modality = dataclasses.field(kw_only=True)
    training: Training | None = dataclasses.field(default=None, kw_only=True)
    real_time: RealTime | None = dataclasses.field(default=None, kw_only=True)

    def __post_init__(self) -> None:
        if self.init not in ("truth", "none"):
            raise ValueError(f"init must be 'truth' or 'none', not {self.init!r}")
        if self.real_time is not None and not self.sequence.closed_loop:
            raise ValueError(f"real-time mode is for closed-loop sequences; {self.sequence!r} is open loop")
        if self.modality.name != self.tracker.modality:
            raise ValueError(
                f"tracker {self.tracker.name!r} reads {self.tracker.modality} frames, not {self.modality.name} frames"
            )

    @functools.cached_property
    def identity(self) -> DatasetIdentity:
        """The dataset's identity, known without reading a frame, computed once and carried to workers."""
        return self.sequence.identity

    @property
    def dataset(self) -> str:
        """The sequence's name in results."""
        return self.identity.name

    @property
    def tracker_key(self) -> str:
        """The tracker's cache key, joined by the training's key for a tracker that learns, and by a real-time mode's."""
        key = self.tracker.cache_key
        key = key if self.training is None else f"{key}+{self.training.key}"
        return key if self.real_time is None else f"{key}+{self.real_time.key}"

    @property
    def key(self) -> CellKey:
        """Identity of the computation: tracker (and training) key, dataset identity, seed, init."""
        return CellKey(self.tracker_key, self.identity.key, self.seed, self.init)

    def label(self) -> str:
        """Short human-readable name: ``tracker on dataset, seed s`` (then ``, real time (declared 17 ms)``)."""
        label = f"{self.tracker.name} on {self.dataset}, seed {self.seed}"
        return label if self.real_time is None else f"{label}, real time ({self.real_time.source})"


def cell_result(cell: Cell, status: Status, message: str = "", **fields: Any) -> CellResult:
    """A result carrying ``cell``'s identity; ``fields`` fill the rest (scores, elapsed_s, detail)."""
    identity = Call.of(lambda: (cell.identity.name, cell.identity.key), "reading the dataset's identity")
    dataset, dataset_key = identity.result if identity.ok else (safe_text(repr, cell.sequence), "")
    values: dict[str, Any] = {"scores": (), "elapsed_s": 0.0, **fields}
    return CellResult(
        tracker=cell.tracker.name,
        tracker_version=cell.tracker.version,
        tracker_key=cell.tracker_key,
        params=dataclasses.asdict(cell.tracker.params),
        training="" if cell.training is None else cell.training.name,
        real_time="" if cell.real_time is None else cell.real_time.source,
        deterministic=bool(getattr(cell.tracker.tracker_class, "deterministic", False)),
        dataset=dataset,
        dataset_key=dataset_key,
        modality=cell.modality.name,
        seed=cell.seed,
        init=cell.init,
        status=status,
        message=message,
        error_columns=cell.modality.error_columns,
        **values,
    )


def cell_rng(seed: int, tracker_name: str, dataset: DatasetIdentity) -> np.random.Generator:
    """The generator of a cell.

    Seeded with ``[seed, crc32(tracker_name), dataset.seed_material]``, so
    the same cell gives the same stream in any process, the same data under
    another path gives the same stream, and different cells get independent
    streams.
    """
    return np.random.default_rng([seed, zlib.crc32(tracker_name.encode()), dataset.seed_material])


GLOBAL_STREAM = 0x676C6F62
"""Extra seed word of the stream :func:`seed_global_generators` draws from, so that it is not the cell generator's."""


def seed_global_generators(seed: int, tracker_name: str, dataset: DatasetIdentity) -> None:
    """Seed numpy's and Python's global generators (and OpenCV's, when loaded) for a cell.

    A tracker should draw only from the generator it is given
    (``trackbench check`` fails one that does not); one that draws from a
    global generator anyway then still gives the same numbers for the same
    cell in any process and any order, and other numbers for another seed,
    instead of whatever state its worker process inherited.
    """
    words = np.random.SeedSequence([seed, zlib.crc32(tracker_name.encode()), dataset.seed_material, GLOBAL_STREAM])
    shared_modules.seed_global_generators(words.generate_state(4))


STOP_SIGNALS = (signal.SIGINT, signal.SIGTERM)
"""The signals that stop a run the way the user's Ctrl-C does: what finished is kept and published."""


@contextmanager
def sigint_is_user_interrupt() -> Iterator[None]:
    """While the block runs, Ctrl-C and ``SIGTERM`` raise :class:`UserInterrupt` (main thread only)."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return

    def interrupt(signum: int, frame: object) -> None:
        raise UserInterrupt(signum)

    previous = {signum: signal.signal(signum, interrupt) for signum in STOP_SIGNALS}
    try:
        yield
    finally:
        for signum, handler in previous.items():
            signal.signal(signum, handler)


def _picture(draw: Drawer, frame: Frame, estimate: Any, outcome: Outcome) -> Picture | None:
    """The frame drawn with ``estimate`` as a PNG, or None when drawing or encoding it fails: never worth a cell."""
    drawn = Call.of(lambda: Picture(int(frame.index), str(outcome), encode_png(draw(frame, estimate))), "drawing")
    return drawn.result


class StepObserver(Protocol):
    """Called after each frame is stepped, timed and scored, outside the step's timing.

    An observer may read the tracker (its belief, its window), never change
    it, so a cell observed gives the estimates of a cell run without one.
    What it raises ends the cell as the tracker's faults do, in the phase
    ``observing frame k``.
    """

    def __call__(self, tracker: Tracker, frame: Frame, estimate: Any, score: FrameScore) -> None: ...


def run_cell(
    cell: Cell, timeout_s: float | None = None, *, observer: StepObserver | None = None, until: int | None = None
) -> CellResult:
    """Run one cell and score every frame; never raises for the cell's own faults.

    Parameters
    ----------
    cell : Cell
        Tracker, sequence, seed and initialisation mode.
    timeout_s : float, optional
        Time limit of the cell, checked between frames: once exceeded, the
        cell stops with status ``"timeout"`` and keeps the frames so far.
        A ``step`` or a read that never returns cannot be stopped here;
        :func:`benchmark.executors.run_cells` kills the worker running it.
    observer : StepObserver, optional
        Called after every frame with the tracker, the frame, the estimate
        and its score (:mod:`benchmark.replay` records a cell this way).
    until : int, optional
        Stop before frame ``until``, as if the sequence ended there.

    Returns
    -------
    CellResult
        Status ``"ok"`` with all frames scored, or ``"error"`` /
        ``"timeout"`` with the frames scored before; with the pictures of
        the first frame of each run of false or missed frames (a run ends
        where the outcome changes), at most :data:`MAX_PICTURES`.  On a
        closed-loop sequence each frame's score also holds the vehicle's
        values that steering after it gave
        (:meth:`benchmark.model.Sequence.steer`); in real-time mode the
        steering is told how long the tracker was busy with the frame
        (:class:`~benchmark.closedloop.real_time.StepClock`), and the
        frames that arrived meanwhile are neither stepped nor scored.

    References
    ----------
    seeds/004, section VI-C and Table V (per-frame outcome);
    seeds/000, section 5.2.5 (speed as time per frame).

    Notes
    -----
    What the cell changes in its process (working folder, environment,
    processes started) is undone when it ends (:func:`benchmark.workers.cell_isolation`).
    """
    with cell_isolation():
        return _run_cell(cell, timeout_s, observer, until)


@dataclass
class _Progress:
    """What a cell has done so far, kept however it ends."""

    scores: list[FrameScore] = dataclasses.field(default_factory=list)
    pictures: list[Picture] = dataclasses.field(default_factory=list)
    read_s: float = 0.0
    previous: Outcome | None = None


def _run_cell(cell: Cell, timeout_s: float | None, observer: StepObserver | None, until: int | None) -> CellResult:
    """:func:`run_cell`'s work."""
    started = time.perf_counter()
    deadline = math.inf if timeout_s is None else started + timeout_s
    progress = _Progress()
    ended = Call.of(lambda: _play(cell, timeout_s, deadline, progress, observer, until), "before frame 0")
    return cell_result(
        cell,
        ended.status,
        ended.message,
        scores=tuple(progress.scores),
        elapsed_s=time.perf_counter() - started,
        read_s=progress.read_s,
        detail=ended.detail,
        pictures=tuple(progress.pictures),
    )


def _play(
    cell: Cell,
    timeout_s: float | None,
    deadline: float,
    progress: _Progress,
    observer: StepObserver | None,
    until: int | None,
) -> None:
    """Create the tracker, reset it and step it over the frames, each phase a :class:`~benchmark.faults.Call`.

    Raises
    ------
    benchmark.faults.Stopped
        With the phase that failed, or the time limit that stopped the cell.
    """
    modality = cell.modality
    info = Call.of(lambda: cell.sequence.info, "reading the sequence's info").value()
    tracker = Call.of(lambda: _fresh_tracker(cell), "creating the tracker").value()
    training = cell.training
    if training is not None:
        adopting = f"adopting the model trained on {training.name}"
        Call.of(lambda: tracker.use_model(training.load()), adopting).value()  # type: ignore[attr-defined]
    frames: Iterator[Frame] | None = None

    def read(index: int) -> Frame | None:
        nonlocal frames
        if frames is None:
            frames = iter(cell.sequence.frames())
        tick = time.perf_counter()
        frame = next(frames, None)
        progress.read_s += time.perf_counter() - tick
        if frame is None and index == 0:
            raise ValueError(f"sequence {info.name!r} has no frames")
        if frame is not None:
            modality.check_frame(frame, f"sequence {info.name!r}, frame {frame.index}")
        return frame

    def reading(index: int) -> Frame | None:
        return Call.of(lambda: read(index), f"reading frame {index}", index).value()

    frame = reading(0)
    assert frame is not None  # read(0) raises instead
    rng = cell_rng(cell.seed, cell.tracker.name, cell.identity)
    init = frame.truth if cell.init == "truth" else None
    Call.of(lambda: tracker.reset(info, rng, init=init), "reset, frame 0", 0).value()
    clock = None if cell.real_time is None else cell.real_time.clock()
    while True:
        index = frame.index
        estimate = Call.of(lambda: _step(cell, tracker, frame, info, progress), f"frame {index}", index).value()
        if cell.sequence.closed_loop:
            busy_s = 0.0 if clock is None else clock.busy_s(progress.scores[-1].step_s)
            steering = f"steering after frame {index}"
            loop = Call.of(lambda: cell.sequence.steer(estimate, busy_s), steering, index).value()
            if loop is not None:
                progress.scores[-1] = dataclasses.replace(progress.scores[-1], loop=loop)
        if observer is not None:
            score = progress.scores[-1]
            Call.of(lambda: observer(tracker, frame, estimate, score), f"observing frame {index}", index).value()
        if until is not None and frame.index + 1 >= until:
            return
        following = reading(frame.index + 1)
        if following is None:
            return
        if time.perf_counter() > deadline:
            note = f"exceeded the {timeout_s:g} s limit after {len(progress.scores)} frames"
            raise Stopped(Call.timed_out(f"frame {following.index}", note, following.index))
        frame = following


def _fresh_tracker(cell: Cell) -> Tracker:
    """A new instance of the cell's tracker, the global generators seeded for the cell first."""
    seed_global_generators(cell.seed, cell.tracker.name, cell.identity)
    return cell.tracker.create()


def _step(cell: Cell, tracker: Tracker, frame: Frame, info: SequenceInfo, progress: _Progress) -> Any:
    """Step ``tracker`` over ``frame``, score its estimate, draw the frame if it starts a run of failures; the estimate.

    The step is timed twice: by the CPU time of this thread
    (:func:`time.thread_time`), which is the tracker's work because the
    worker runs its native libraries on this one thread
    (:mod:`benchmark.workers`), and by the wall clock, which also counts the
    time the thread waited for a core other processes held.
    """
    modality = cell.modality
    tick, cpu_tick = time.perf_counter(), time.thread_time()
    estimate = tracker.step(frame)
    step_s, wall_s = time.thread_time() - cpu_tick, time.perf_counter() - tick
    try:
        modality.check_estimate(estimate)
    except EstimateError as exc:
        raise EstimateError(f"tracker {cell.tracker.name!r} returned an invalid estimate: {exc}") from exc
    scorer = modality.scorer
    outcome, errors = scorer.score(estimate, frame.truth, info)
    progress.scores.append(FrameScore(frame.index, outcome, dict(zip(scorer.error_columns, errors)), step_s, wall_s))
    draw = modality.draw
    wanted = outcome in _FAILURES and outcome != progress.previous and len(progress.pictures) < MAX_PICTURES
    if wanted and draw is not None:
        picture = _picture(draw, frame, estimate, outcome)
        if picture is not None:
            progress.pictures.append(picture)
    progress.previous = outcome
    return estimate
