"""Timing a subject against its bounds: the same frames, alternating rounds, thread CPU time.

For each subject (a tracker, or a core component) the frames of its
dataset are read once into memory (rendered into the frame cache if they
are not there yet).  Every workload, the subject's and each bound's, then
plays them once untimed (numba compiles, caches fill), and the timed rounds
follow: in each, the subject and then each bound in turn is reset with the
same generator (seeded as a run's cell of seed 0 is,
:func:`benchmark.runner.cell_rng`) and stepped over every frame, each step
timed by the CPU time of this thread (:func:`time.thread_time`), which is
the workload's own work because the native libraries run one thread here
(:func:`benchmark.workers.limit_native_threads`).  A round's figure is the
mean per frame; a row shows the medians over rounds and the median of the
per-round ratios ours / bound, with their quartiles as spread: taken side by
side, the ratios cancel what the machine's other load does to both.
"""

from __future__ import annotations

import math
import statistics
import time
import zlib
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from itertools import islice
from typing import Any

import numpy as np

from benchmark.model import Frame, SequenceInfo
from benchmark.speed.bounds import BoundContext, BoundUnavailable, SpeedBound, Workload, WorkloadFactory

Report = Callable[[int, int], None]
"""Progress callback ``report(done, total)``, in workload passes."""


@dataclass(frozen=True)
class Subject:
    """A subject ready to time: its frames in memory, its context and its bounds.

    Attributes
    ----------
    name : str
        The tracker's or component's name.
    dataset : str
        The sequence the frames come from.
    frames : tuple of Frame
        The frames every workload steps over, in order.
    init : object or None
        The first frame's truth, handed to every ``reset``.
    context : BoundContext
        What the factories get.
    ours : callable
        ``ours(context) -> Workload``.
    bounds : tuple of SpeedBound
        The rows of this subject.
    seed_material : int
        Mixed into the generator of every round, as a cell's dataset is.
    """

    name: str
    dataset: str
    frames: tuple[Frame, ...]
    init: Any
    context: BoundContext
    ours: WorkloadFactory
    bounds: tuple[SpeedBound, ...]
    seed_material: int = 0

    @property
    def info(self) -> SequenceInfo:
        return self.context.info


@dataclass(frozen=True)
class Row:
    """One line of the table: a subject against one bound, over ``rounds`` rounds of ``frames`` frames.

    Times are thread CPU seconds a frame, medians over the rounds; the
    ratio is the median of the per-round ratios ours / bound, between its
    quartiles ``ratio_low`` and ``ratio_high``.  ``met`` is None when the
    row has no goal or could not be measured (``note`` says why).
    """

    subject: str
    bound: str
    dataset: str
    frames: int
    rounds: int
    ours_s: float
    bound_s: float
    ratio: float
    ratio_low: float
    ratio_high: float
    goal: str
    met: bool | None
    note: str = ""

    @property
    def ours_fps(self) -> float:
        return 1.0 / self.ours_s if self.ours_s > 0 else math.inf


def read_frames(frames: Any, count: int) -> tuple[Frame, ...]:
    """The first ``count`` frames of an iterable of frames, held in memory."""
    return tuple(islice(frames, count))


def round_generator(seed: int, subject: str, seed_material: int) -> np.random.Generator:
    """The generator every workload of ``subject`` gets in every round: the same stream each time."""
    return np.random.default_rng([seed, zlib.crc32(subject.encode()), seed_material])


def play(workload: Workload, subject: Subject, seed: int = 0) -> float:
    """Reset ``workload`` with the round's generator and step it over the subject's frames.

    Returns
    -------
    float
        Thread CPU seconds a frame, the mean over the frames (the reset is not timed).
    """
    workload.reset(subject.info, round_generator(seed, subject.name, subject.seed_material), subject.init)
    spent = 0.0
    for frame in subject.frames:
        tick = time.thread_time()
        workload.step(frame)
        spent += time.thread_time() - tick
    return spent / max(len(subject.frames), 1)


def quartiles(values: Sequence[float]) -> tuple[float, float, float]:
    """Lower quartile, median and upper quartile of ``values`` (all the one value for fewer than two)."""
    if len(values) < 2:
        value = values[0] if values else math.nan
        return value, value, value
    low, middle, high = statistics.quantiles(values, n=4, method="inclusive")
    return low, middle, high


def time_subject(subject: Subject, rounds: int, report: Report | None = None) -> list[Row]:
    """Time ``subject`` against each of its bounds in ``rounds`` alternating rounds; one :class:`Row` per bound.

    A bound whose factory raises :class:`BoundUnavailable` is left out of
    the rounds, and its row says why.
    """
    ours = subject.ours(subject.context)
    workloads: list[tuple[SpeedBound, Workload | None, str]] = []
    for bound in subject.bounds:
        try:
            workloads.append((bound, bound.make_bound(subject.context), ""))
        except BoundUnavailable as exc:
            workloads.append((bound, None, str(exc)))
    playing = [ours, *(workload for _, workload, _ in workloads if workload is not None)]
    total = len(playing) * (rounds + 1)
    done = 0
    times: list[list[float]] = [[] for _ in playing]
    for round_index in range(rounds + 1):  # round 0 warms up and is not counted
        for index, workload in enumerate(playing):
            seconds = play(workload, subject)
            if round_index > 0:
                times[index].append(seconds)
            done += 1
            if report is not None:
                report(done, total)
    ours_times = times[0]
    ours_s = statistics.median(ours_times) if ours_times else math.nan
    rows = []
    timed = iter(times[1:])
    for bound, workload, note in workloads:
        bound_times = next(timed) if workload is not None else []
        ratios = [a / b for a, b in zip(ours_times, bound_times) if b > 0]
        low, ratio, high = quartiles(ratios)
        bound_s = statistics.median(bound_times) if bound_times else math.nan
        goal = bound.goal
        met = None
        if goal is not None and not math.isnan(ours_s) and (ratios or not goal.uses_ratio):
            met = goal.met(ratio, ours_s)
        rows.append(
            Row(
                subject.name,
                bound.bound,
                subject.dataset,
                len(subject.frames),
                rounds,
                ours_s,
                bound_s,
                ratio,
                low,
                high,
                str(goal) if goal is not None else "",
                met,
                note,
            )
        )
    return rows
