"""Recording a cell for its replay: the runner's play, frame by frame, with what the page shows kept.

:func:`record_cell` plays one :class:`~benchmark.runner.Cell` with
:func:`benchmark.runner.run_cell` itself, stopped after the range's last
frame, and watches it through the runner's
:class:`~benchmark.runner.StepObserver`.  Frames before the range asked
for are stepped and not kept, so a range replays what the runner saw.
After each kept step (outside the timing) the observer takes the step's
score and CPU time, the tracker's belief, if it exposes one through the
protocols of :mod:`benchmark.testing.beliefs`, and the frame's picture and
overlays from the modality's view (:mod:`benchmark.replay.views`).  Taking
them only reads the tracker: it draws nothing from the tracker's
generator, so the estimates are the runner's, bit for bit.

A particle belief is cut to at most :data:`MAX_PARTICLES` particles by a
deterministic systematic subsample (:func:`systematic_subsample`), the
particles the thesis's GUI would show as the longest lines (seeds/000,
section 4.7, Figs. 4.11 and 4.14).
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from benchmark.errors import TrackbenchError
from benchmark.model import Frame
from benchmark.replay.views import Mark, Picture, ReplayView, view_of
from benchmark.results import FrameScore
from benchmark.runner import Cell, run_cell
from benchmark.testing.beliefs import GaussianBelief, ParticleBelief
from benchmark.tracker import Searches

MAX_PARTICLES = 200
"""Most particles a recorded frame keeps of a particle belief."""


class FrameRangeError(TrackbenchError, ValueError):
    """A frame range that selects no frame of the sequence."""


@dataclass(frozen=True)
class FrameRange:
    """Frames ``first`` to ``stop - 1`` of a sequence; ``stop`` None runs to its end.

    Attributes
    ----------
    first : int
        The first frame kept, ``>= 0``.
    stop : int or None
        One past the last frame kept, ``> first``; None: the sequence's end.
    """

    first: int = 0
    stop: int | None = None

    def __post_init__(self) -> None:
        if self.first < 0 or (self.stop is not None and self.stop <= self.first):
            raise FrameRangeError(f"frame range {self}: needs 0 <= A < B")

    @classmethod
    def parse(cls, text: str) -> FrameRange:
        """``"A:B"``, ``"A:"`` or ``":B"`` as a range.

        Raises
        ------
        FrameRangeError
            For anything else, or ``A >= B``.
        """
        first, colon, stop = text.partition(":")
        try:
            if not colon:
                raise ValueError("no colon")
            return cls(int(first) if first.strip() else 0, int(stop) if stop.strip() else None)
        except ValueError as exc:
            raise FrameRangeError(f"frame range {text!r} is not A:B with integers 0 <= A < B ({exc})") from exc

    def __str__(self) -> str:
        return f"{self.first}:{'' if self.stop is None else self.stop}"


@dataclass(frozen=True)
class Belief:
    """A tracker's belief after a step, as the page draws it.

    Attributes
    ----------
    kind : {"particles", "gaussian"}
        Which protocol the tracker exposed.
    particles, weights : numpy.ndarray or None
        The (subsampled) particle set, ``(n, D)`` and ``(n,)`` summing to one.
    mean, variance : numpy.ndarray or None
        The Gaussian's mean and the diagonal of its covariance, ``(D,)``.
    covariance : numpy.ndarray or None
        The Gaussian's covariance, ``(D, D)``, of which a view draws the
        block of the dimensions its picture shows as an ellipse.
    """

    kind: str
    particles: np.ndarray | None = None
    weights: np.ndarray | None = None
    mean: np.ndarray | None = None
    variance: np.ndarray | None = None
    covariance: np.ndarray | None = None


@dataclass(frozen=True)
class FrameRecord:
    """One kept frame of a recording.

    Attributes
    ----------
    index : int
        The frame's index.
    outcome : str
        ``correct``, ``false``, ``missed`` or ``unscored``.
    errors : dict
        The scorer's error columns.
    step_s : float
        CPU time of the tracker's ``step``, s.
    truth, estimate : tuple of float or None
        The states, in the view's dimensions.
    truth_marks, estimate_marks : list of Mark
        Their overlays on the picture.
    belief : Belief or None
        The tracker's belief after the step, where it exposes one.
    picture : Picture
        The frame as a JPEG.
    estimate_value : object
        The estimate the tracker returned, as it returned it.
    region : object
        The part of the frame the tracker searched, where it says
        (:class:`~benchmark.tracker.Searches`); None: all of it, or unknown.
    loop : dict
        On a closed-loop sequence, the vehicle at this frame by frame-table
        column (``loop_offset_m``, ..., :class:`benchmark.results.LoopValues`);
        empty on every other.
    """

    index: int
    outcome: str
    errors: dict[str, float]
    step_s: float
    truth: tuple[float, ...] | None
    estimate: tuple[float, ...] | None
    truth_marks: list[Mark]
    estimate_marks: list[Mark]
    belief: Belief | None
    picture: Picture
    estimate_value: Any = field(repr=False, compare=False, default=None)
    region: Any = field(repr=False, compare=False, default=None)
    loop: dict[str, float] = field(default_factory=dict)


@dataclass
class Recording:
    """A cell's frames as recorded for its replay.

    Attributes
    ----------
    tracker, dataset, modality : str
        What ran on what.
    seed : int
        The cell's seed.
    dimensions : tuple of str
        Names of the state's components: the view's, and the further columns a tracker's belief names
        (``belief_dimensions``, e.g. velocities).
    frames : list of FrameRecord
        The kept frames, in order.
    ended : str
        Empty when the sequence (or range) was played to its end; else why it stopped.
    step_s, capture_s : float
        Summed CPU time of the tracker's steps over the kept frames, and the
        time taken to capture beliefs and pictures, s.
    """

    tracker: str
    dataset: str
    modality: str
    seed: int
    dimensions: tuple[str, ...]
    frames: list[FrameRecord] = field(default_factory=list)
    ended: str = ""
    step_s: float = 0.0
    capture_s: float = 0.0


def systematic_subsample(
    particles: np.ndarray, weights: np.ndarray, limit: int = MAX_PARTICLES
) -> tuple[np.ndarray, np.ndarray]:
    """At most ``limit`` particles of a weighted set, chosen deterministically, with their weights renormalised.

    The ``limit`` points ``(k + 1/2) / limit`` are laid on the cumulative
    weights, as systematic resampling lays its comb, but without a random
    offset; each particle one of them falls on is kept once, with its own
    weight.  Every particle of weight ``1 / limit`` or more (of the sum) is
    kept, and no generator is touched.  A set without positive finite weights keeps evenly spaced
    particles with equal weights.

    Parameters
    ----------
    particles : numpy.ndarray
        States, ``(N, D)``.
    weights : numpy.ndarray
        Weights, ``(N,)``.
    limit : int
        Most particles kept, ``>= 1``.

    Returns
    -------
    particles, weights : numpy.ndarray
        ``(n, D)`` and ``(n,)`` with ``n <= min(N, limit)``, the weights summing to one.

    References
    ----------
    seeds/000, eqs. (3.8)-(3.9), Figs. 3.6-3.7 (the walk up the cumulative weights);
    :func:`benchmark.filters.resampling.systematic_resample` draws the comb's offset, this one fixes it at 1/2.
    """
    states = np.asarray(particles, dtype=float)
    w = np.asarray(weights, dtype=float)
    if states.ndim != 2 or w.shape != (states.shape[0],) or states.shape[0] == 0:
        raise ValueError(f"particles {states.shape} and weights {w.shape} are not a weighted set (N, D), (N,)")
    n = states.shape[0]
    usable = np.where(np.isfinite(w) & (w > 0), w, 0.0)
    total = float(usable.sum())
    if not (math.isfinite(total) and total > 0):
        chosen = np.unique(np.linspace(0, n - 1, min(n, limit)).round().astype(int))
        return states[chosen].copy(), np.full(chosen.size, 1.0 / chosen.size)
    if n <= limit:
        chosen = np.arange(n)
    else:
        cumulative = np.cumsum(usable) / total
        comb = (np.arange(limit) + 0.5) / limit
        chosen = np.unique(np.minimum(np.searchsorted(cumulative, comb, side="right"), n - 1))
    kept = usable[chosen]
    return states[chosen].copy(), kept / kept.sum()


def belief_of(tracker: Any, limit: int = MAX_PARTICLES) -> Belief | None:
    """The belief ``tracker`` exposes now (:class:`ParticleBelief`, :class:`GaussianBelief`), or None.

    Reads only: the tracker's state and generator stay as they are.
    """
    if isinstance(tracker, ParticleBelief):
        particles, weights = tracker.particles, tracker.weights
        if particles is None or weights is None:
            return None
        kept, kept_weights = systematic_subsample(np.asarray(particles), np.asarray(weights), limit)
        return Belief("particles", particles=kept, weights=kept_weights)
    if isinstance(tracker, GaussianBelief):
        mean, covariance = tracker.mean, tracker.covariance
        if mean is None or covariance is None:
            return None
        matrix = np.array(covariance, dtype=float)
        return Belief("gaussian", mean=np.array(mean, dtype=float), variance=np.diag(matrix).copy(), covariance=matrix)
    return None


def record_cell(
    cell: Cell,
    frames: FrameRange = FrameRange(),
    report: Callable[[int, int], None] | None = None,
    view: ReplayView | None = None,
) -> Recording:
    """Play ``cell`` with the runner and record the frames of ``frames``.

    Parameters
    ----------
    cell : Cell
        Tracker, sequence, seed and initialisation.
    frames : FrameRange
        The frames kept; the frames before are stepped, not kept.
    report : callable, optional
        ``report(done, total)`` after each frame stepped.
    view : ReplayView, optional
        The view of the frames; by default the cell's modality's.

    Returns
    -------
    Recording
        The kept frames; a tracker that raises, or returns what is not an
        estimate, ends the recording there, with the runner's message in ``ended``.

    Raises
    ------
    FrameRangeError
        When the sequence has no frame in the range.
    NoViewError
        For a modality the replay cannot show yet.
    """
    view = view or view_of(cell.modality.name)
    info = cell.sequence.info
    if frames.first >= info.n_frames:
        raise FrameRangeError(f"frame range {frames}: {info.name} has {info.n_frames} frames")
    stop = info.n_frames if frames.stop is None else min(frames.stop, info.n_frames)
    recording = Recording(cell.tracker.name, cell.dataset, cell.modality.name, cell.seed, tuple(view.dimensions))
    recorder = _Recorder(cell, view, frames.first, stop, recording, report)
    result = run_cell(cell, observer=recorder, until=stop)
    if result.status != "ok":
        recording.ended = result.message
    return recording


@dataclass
class _Recorder:
    """The runner's observer that keeps what the page shows of the frames from ``first`` on."""

    cell: Cell
    view: ReplayView
    first: int
    stop: int
    recording: Recording
    report: Callable[[int, int], None] | None

    def __call__(self, tracker: Any, frame: Frame, estimate: Any, score: FrameScore) -> None:
        if frame.index == 0:  # the tracker names its belief's columns once, for the whole recording
            names = tuple(getattr(tracker, "belief_dimensions", ()))
            if len(names) > len(self.view.dimensions) and names[: len(self.view.dimensions)] == self.view.dimensions:
                self.recording.dimensions = names
        if frame.index >= self.first:
            tick = time.perf_counter()
            self.recording.frames.append(self._kept(tracker, frame, estimate, score))
            self.recording.capture_s += time.perf_counter() - tick
            self.recording.step_s += score.step_s
        if self.report is not None:
            self.report(frame.index + 1, self.stop)

    def _kept(self, tracker: Any, frame: Frame, estimate: Any, score: FrameScore) -> FrameRecord:
        view = self.view
        picture = view.picture(frame)
        return FrameRecord(
            index=int(frame.index),
            outcome="unscored" if score.outcome is None else str(score.outcome),
            errors={name: float(error) for name, error in score.errors.items()},
            step_s=score.step_s,
            truth=view.state(frame.truth),
            estimate=view.state(estimate),
            truth_marks=view.overlay(frame.truth, frame, picture),
            estimate_marks=view.overlay(estimate, frame, picture),
            belief=belief_of(tracker),
            picture=picture,
            estimate_value=estimate,
            region=tracker.search_region if isinstance(tracker, Searches) else None,
            loop={} if score.loop is None else score.loop.columns(),
        )
