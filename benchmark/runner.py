"""Running cells: one tracker on one sequence with one seed, failures isolated.

A *cell* is the unit of work of the benchmark: a registered tracker (with
its parameters), a sequence of the tracker's modality and a seed,
initialised either from the first frame's ground truth or from nothing.
:func:`run_cell` creates a fresh tracker, reads the first frame, calls
``reset(info, rng, init)`` and then ``step`` once per frame, scoring each
frame as it goes with the scorer of the cell's modality
(:class:`benchmark.modality.Modality`; the camera rule is seeds/004,
section VI-C, Table V).  A frame whose observation or truth is not of the
modality's types is a data error, so trackers can rely on them.  Timing
covers ``step`` only, so frames per second compare trackers rather than
image decoders, as in the thesis' Table 5.3 (seeds/000, section 5.2.5).

The generator of a cell is seeded from the seed and the CRC-32 of the
tracker's and the dataset's names, so that a seed replays a cell bit for bit
and different cells draw independent streams.

Nothing a cell does stops the others.  Whatever a tracker raises, whatever
invalid estimate it returns, and any error reading a frame, turns the cell
into a result with status ``"error"`` and a message
``"ExceptionType: message (frame k)"``; a cell that runs past its time limit
gets status ``"timeout"``.  Frames scored before the failure stay in the
result.  :func:`run_cells` runs cells inline or in a pebble process pool; in
the pool, a worker that hangs inside ``step`` is killed shortly after the
limit and only that cell is lost.
"""

from __future__ import annotations

import concurrent.futures
import dataclasses
import functools
import math
import os
import time
import traceback
import zlib
from collections.abc import Iterable, Iterator
from dataclasses import dataclass
from typing import Any, Literal

import numpy as np

from benchmark.modality import EstimateError, Modality
from benchmark.model import Sequence, SequenceInfo
from benchmark.registry import TrackerEntry
from benchmark.results import CellKey, CellResult, FrameScore, Status

InitMode = Literal["truth", "none"]
DEFAULT_TIMEOUT_S = 600.0
"""Time limit of one cell unless the caller sets another."""


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
    """

    tracker: TrackerEntry
    sequence: Sequence
    seed: int
    init: InitMode = "truth"
    modality: Modality = dataclasses.field(kw_only=True)

    def __post_init__(self) -> None:
        if self.init not in ("truth", "none"):
            raise ValueError(f"init must be 'truth' or 'none', not {self.init!r}")
        if self.modality.name != self.tracker.modality:
            raise ValueError(
                f"tracker {self.tracker.name!r} reads {self.tracker.modality} frames, not {self.modality.name} frames"
            )

    @functools.cached_property
    def info(self) -> SequenceInfo:
        """The sequence's description, read once and carried to worker processes."""
        return self.sequence.info

    @property
    def dataset(self) -> str:
        """The sequence's name in results."""
        return self.info.name

    @property
    def key(self) -> CellKey:
        """Identity of the computation: tracker cache key, dataset, seed, init."""
        return CellKey(self.tracker.cache_key, self.dataset, self.seed, self.init)

    def label(self) -> str:
        """Short human-readable name: ``tracker on dataset, seed s``."""
        return f"{self.tracker.name} on {self.dataset}, seed {self.seed}"


def cell_result(cell: Cell, status: Status, message: str = "", **fields: Any) -> CellResult:
    """A result carrying ``cell``'s identity; ``fields`` fill the rest (scores, elapsed_s, detail)."""
    try:
        dataset, modality = cell.info.name, cell.info.modality
    except Exception:
        dataset, modality = repr(cell.sequence), cell.modality.name
    values: dict[str, Any] = {"scores": (), "elapsed_s": 0.0, **fields}
    return CellResult(
        tracker=cell.tracker.name,
        tracker_version=cell.tracker.version,
        tracker_key=cell.tracker.cache_key,
        params=dataclasses.asdict(cell.tracker.params),
        dataset=dataset,
        modality=modality,
        seed=cell.seed,
        init=cell.init,
        status=status,
        message=message,
        error_columns=cell.modality.error_columns,
        **values,
    )


def cell_rng(seed: int, tracker_name: str, dataset_name: str) -> np.random.Generator:
    """The generator of a cell.

    Seeded with ``[seed, crc32(tracker_name), crc32(dataset_name)]``, so the
    same triple gives the same stream in any process and different cells
    get independent streams.
    """
    return np.random.default_rng([seed, zlib.crc32(tracker_name.encode()), zlib.crc32(dataset_name.encode())])


def _describe(exc: BaseException) -> str:
    """``ExceptionType: message`` on one line."""
    text = " ".join(str(exc).split())
    return f"{type(exc).__name__}: {text}" if text else type(exc).__name__


def run_cell(cell: Cell, timeout_s: float | None = None) -> CellResult:
    """Run one cell and score every frame; never raises for the cell's own faults.

    Parameters
    ----------
    cell : Cell
        Tracker, sequence, seed and initialisation mode.
    timeout_s : float, optional
        Time limit of the cell, checked between frames: once exceeded, the
        cell stops with status ``"timeout"`` and keeps the frames so far.
        A ``step`` that never returns cannot be stopped here; run such
        cells through :func:`run_cells` with a pool.

    Returns
    -------
    CellResult
        Status ``"ok"`` with all frames scored, or ``"error"`` /
        ``"timeout"`` with the frames scored before.

    References
    ----------
    seeds/004, section VI-C and Table V (per-frame outcome);
    seeds/000, section 5.2.5 (speed as time per frame).
    """
    started = time.perf_counter()
    deadline = math.inf if timeout_s is None else started + timeout_s
    scores: list[FrameScore] = []
    where = "before frame 0"
    status: Status = "ok"
    message = detail = ""
    try:
        info = cell.info
        modality = cell.modality
        scorer = modality.scorer
        tracker = cell.tracker.create()
        frames = iter(cell.sequence.frames())
        where = "reading frame 0"
        first = next(frames, None)
        if first is None:
            raise ValueError(f"sequence {info.name!r} has no frames")
        modality.check_frame(first, f"sequence {info.name!r}, frame {first.index}")
        where = "reset, frame 0"
        rng = cell_rng(cell.seed, cell.tracker.name, info.name)
        tracker.reset(info, rng, init=first.truth if cell.init == "truth" else None)
        frame = first
        while True:
            where = f"frame {frame.index}"
            tick = time.perf_counter()
            estimate = tracker.step(frame)
            step_s = time.perf_counter() - tick
            try:
                modality.check_estimate(estimate)
            except EstimateError as exc:
                raise EstimateError(f"tracker {cell.tracker.name!r} returned an invalid estimate: {exc}") from exc
            outcome, errors = scorer.score(estimate, frame.truth, info)
            scores.append(FrameScore(frame.index, outcome, dict(zip(scorer.error_columns, errors)), step_s))
            where = f"reading frame {frame.index + 1}"
            following = next(frames, None)
            if following is None:
                break
            modality.check_frame(following, f"sequence {info.name!r}, frame {following.index}")
            if time.perf_counter() > deadline:
                status = "timeout"
                message = f"exceeded the {timeout_s:g} s limit after {len(scores)} frames (frame {following.index})"
                break
            frame = following
    except Exception as exc:
        status = "error"
        message = f"{_describe(exc)} ({where})"
        detail = traceback.format_exc()
    return cell_result(
        cell, status, message, scores=tuple(scores), elapsed_s=time.perf_counter() - started, detail=detail
    )


def _grace_s(timeout_s: float) -> float:
    """Extra time a worker gets before it is killed, so ``run_cell`` can stop on its own first."""
    return max(1.0, 0.05 * timeout_s)


def _from_future(cell: Cell, future: concurrent.futures.Future, timeout_s: float | None) -> CellResult:
    try:
        return future.result()
    except TimeoutError:
        return cell_result(
            cell,
            "timeout",
            f"no result within the {timeout_s:g} s limit; the worker was stopped and the frames are lost",
            elapsed_s=float(timeout_s or 0.0),
        )
    except Exception as exc:
        return cell_result(
            cell, "error", f"{_describe(exc)} (worker process)", detail="".join(traceback.format_exception(exc))
        )


def run_cells(
    cells: Iterable[Cell], *, jobs: int | None = None, timeout_s: float | None = DEFAULT_TIMEOUT_S
) -> Iterator[CellResult]:
    """Run cells inline or in a process pool and yield each result as it finishes.

    Parameters
    ----------
    cells : iterable of Cell
        The cells to run.
    jobs : int, optional
        Worker processes; None uses every core (``os.cpu_count()``) and 0
        runs the cells one after another in this process.
    timeout_s : float, optional
        Time limit of each cell (None: no limit).  In the pool a worker
        still busy a grace period after the limit is killed and its cell
        becomes a ``"timeout"`` result without frames.

    Yields
    ------
    CellResult
        One per cell, in order of completion (input order when inline).

    Notes
    -----
    Closing the generator early stops the pool and its workers.
    """
    todo = list(cells)
    if jobs is None:
        jobs = os.cpu_count() or 1
    if jobs < 0:
        raise ValueError(f"jobs must be >= 0, not {jobs}")
    if jobs == 0:
        for cell in todo:
            yield run_cell(cell, timeout_s)
        return
    if not todo:
        return
    from pebble import ProcessPool

    hard_limit = None if timeout_s is None else timeout_s + _grace_s(timeout_s)
    pool = ProcessPool(max_workers=min(jobs, len(todo)))
    try:
        futures = {pool.schedule(run_cell, args=(cell, timeout_s), timeout=hard_limit): cell for cell in todo}
        for future in concurrent.futures.as_completed(futures):
            yield _from_future(futures[future], future, timeout_s)
    finally:
        pool.stop()
        pool.join()
