"""The likelihood ceiling: how often a tracker's own observation model prefers a correct state.

A tracker that weighs hypotheses with an observation model can be no better
than that model: on a frame where the best-scoring state near the true
cable is itself wrong, a search that finds the best state reports a wrong
cable.  :func:`likelihood_ceiling` scores, on every labelled frame, a grid of
states in a window around the true cable state
(:class:`CeilingWindow`) with the tracker's own model
(:class:`benchmark.tracker.ScoresStates`; for ``condensation`` the weight of
seeds/000, eq. 4.11) and asks whether the best of them passes the detection
rule of seeds/004, section VI-C (Table V; :class:`~benchmark.modalities.camera.scoring.CameraScorer`).
The share of frames where it does, ``ceiling_pct``, is the most a tracker
that reports that model's best state can reach; a ceiling below 100 % shows
frames lost to the model itself, a tracker below its ceiling loses frames
to its search.  It is not a strict bound for a filter: a motion prior and a
mean (MMSE) estimate can carry a tracker over a frame whose best-scoring
state is wrong, so a tracker may exceed it by a few frames.

:func:`ceiling_report` does this for a registered tracker over several
sequences and sets each ceiling beside the share of frames the tracker got
correct in its latest stored run (``trackbench diagnose``).
"""

from __future__ import annotations

import math
import time
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np
import pandas as pd

from benchmark.leaderboard import is_pooled, leaderboards
from benchmark.modalities.camera.geometry import DetectionRule
from benchmark.modalities.camera.model import CableState
from benchmark.modalities.camera.scoring import CameraScorer
from benchmark.modality import Modality
from benchmark.model import Outcome, Sequence
from benchmark.report.markdown import titled_table
from benchmark.selection import SelectionError
from benchmark.tracker import ScoresStates

if TYPE_CHECKING:
    from benchmark.progress import Report
    from benchmark.registry import TrackerEntry
    from benchmark.store import ResultStore

CAMERA = "camera"
"""The modality whose sequences and trackers the ceiling is defined for."""

FRAME_COLUMNS = (
    "frame",
    "best_d_px",
    "best_alpha_deg",
    "best_w_px",
    "best_beta_deg",
    "best_score",
    "truth_score",
    "ceiling_ok",
    "score_ms",
)
"""Columns of :attr:`CeilingResult.frames`; angles in degrees (``conventions.md`` section 4)."""

REPORT_COLUMNS = ("dataset", "frames", "ceiling_pct", "correct_pct")
"""Columns of the table :func:`ceiling_report` returns."""


def _symmetric_steps(half_width: float, step: float) -> np.ndarray:
    """``0, +-step, +-2 step, ...`` up to ``half_width``, ascending, with 0 in the middle."""
    count = math.floor(half_width / step + 1e-9)
    return np.arange(-count, count + 1) * step


@dataclass(frozen=True)
class CeilingWindow:
    """The grid of states searched around the true cable state of a frame.

    Every axis is symmetric about the truth and holds it, so the grid holds
    the true state itself (at :attr:`truth_index`).

    Parameters
    ----------
    d_px, d_step_px : float
        ``d`` from ``truth - d_px`` to ``truth + d_px`` in steps of ``d_step_px``.
    alpha_deg, alpha_step_deg : float
        ``alpha`` likewise, in degrees.
    w_fraction : float
        ``w`` from ``(1 - w_fraction)`` to ``(1 + w_fraction)`` times the true width ...
    w_steps : int
        ... in this many steps, an odd number so that the true width is one of them.
    beta_deg, beta_step_deg : float
        ``beta`` likewise, in degrees.

    Notes
    -----
    The defaults give ``31 x 13 x 9 x 7 = 25389`` states a frame, well past
    the rule's 5 px and 3 deg (seeds/004, section VI-C) in ``d`` and
    ``alpha``, and past the width and skew a border can be off by before it
    leaves a 5 px band.  ``condensation`` scores them in about 5 ms a frame
    (one core), so the defaults need no coarsening.

    Raises
    ------
    ValueError
        For a negative half-width, a step that is not positive, ``w_fraction``
        outside ``[0, 1)`` or an even or non-positive ``w_steps``, naming the field.
    """

    d_px: float = 15.0
    d_step_px: float = 1.0
    alpha_deg: float = 6.0
    alpha_step_deg: float = 1.0
    w_fraction: float = 0.4
    w_steps: int = 9
    beta_deg: float = 3.0
    beta_step_deg: float = 1.0
    _offsets: np.ndarray = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        for name in ("d_px", "alpha_deg", "beta_deg"):
            if not getattr(self, name) >= 0:
                raise ValueError(f"CeilingWindow.{name} must be >= 0, got {getattr(self, name)!r}")
        for name in ("d_step_px", "alpha_step_deg", "beta_step_deg"):
            if not getattr(self, name) > 0:
                raise ValueError(f"CeilingWindow.{name} must be > 0, got {getattr(self, name)!r}")
        if not 0 <= self.w_fraction < 1:
            raise ValueError(f"CeilingWindow.w_fraction must be in [0, 1), got {self.w_fraction!r}")
        if not (isinstance(self.w_steps, int) and self.w_steps > 0 and self.w_steps % 2 == 1):
            raise ValueError(f"CeilingWindow.w_steps must be a positive odd int, got {self.w_steps!r}")
        axes = (
            _symmetric_steps(self.d_px, self.d_step_px),
            np.radians(_symmetric_steps(self.alpha_deg, self.alpha_step_deg)),
            np.linspace(1.0 - self.w_fraction, 1.0 + self.w_fraction, self.w_steps),
            np.radians(_symmetric_steps(self.beta_deg, self.beta_step_deg)),
        )
        offsets = np.stack([grid.ravel() for grid in np.meshgrid(*axes, indexing="ij")], axis=1)
        offsets.flags.writeable = False
        object.__setattr__(self, "_offsets", offsets)

    @property
    def size(self) -> int:
        """Number of states in the grid."""
        return len(self._offsets)

    @property
    def truth_index(self) -> int:
        """Row of :meth:`states` that is the true state (the middle of the grid)."""
        return (self.size - 1) // 2

    def states(self, truth: CableState) -> np.ndarray:
        """The ``(size, 4)`` grid of states ``(d, alpha, w, beta)`` around ``truth``, in px, rad, px, rad."""
        offsets = self._offsets
        return np.column_stack(
            (
                truth.d + offsets[:, 0],
                truth.alpha + offsets[:, 1],
                truth.w * offsets[:, 2],
                truth.beta + offsets[:, 3],
            )
        )


@dataclass(frozen=True, eq=False)
class CeilingResult:
    """The likelihood ceiling of one tracker's observation model on one sequence.

    Attributes
    ----------
    tracker : str
        The tracker's name.
    sequence : str
        The sequence's name.
    window : CeilingWindow
        The grid searched around each true state.
    frames : pandas.DataFrame
        One row per labelled frame, columns :data:`FRAME_COLUMNS`: the
        frame's index, the best-scoring state of the grid (angles in
        degrees), its score and the true state's, whether the best state is
        correct by the detection rule, and the time of the frame's
        ``score_states`` call in ms.
    """

    tracker: str
    sequence: str
    window: CeilingWindow
    frames: pd.DataFrame

    @property
    def labelled(self) -> int:
        """Number of labelled frames, the frames the ceiling is a share of."""
        return len(self.frames)

    @property
    def ceiling_pct(self) -> float:
        """Per cent of labelled frames whose best-scoring state is correct; nan without labelled frames."""
        return 100.0 * float(self.frames["ceiling_ok"].mean()) if self.labelled else math.nan

    @property
    def failures(self) -> list[int]:
        """Indices of the frames whose best-scoring state is not correct."""
        return [int(index) for index in self.frames.loc[~self.frames["ceiling_ok"], "frame"]]


def _tracker_name(tracker: object) -> str:
    return str(getattr(tracker, "name", type(tracker).__name__))


def likelihood_ceiling(
    tracker: ScoresStates,
    sequence: Sequence,
    window: CeilingWindow = CeilingWindow(),
    rule: DetectionRule = DetectionRule(),
) -> CeilingResult:
    """Search a window around every labelled frame's true cable for the state the tracker scores best.

    The tracker is reset once, with ``np.random.default_rng(0)`` and the
    first frame's truth, then asked for the scores of every state of the
    window in one :meth:`~benchmark.tracker.ScoresStates.score_states` call
    a frame.  A frame is a ceiling failure when the best-scoring state is
    not correct by the line-pair rule of seeds/004, section VI-C: a search
    that finds the maximum of this model reports a wrong cable there.  For
    ``condensation`` the score is the weight of seeds/000, eq. (4.11).

    Parameters
    ----------
    tracker : ScoresStates
        A camera tracker that scores states with its observation model.
    sequence : Sequence
        A camera sequence; frames whose truth is None or unknown
        (:data:`~benchmark.modalities.camera.model.UNKNOWN_CABLE`) are skipped.
    window : CeilingWindow
        The grid searched around each true state.
    rule : DetectionRule
        Thresholds of the detection rule (5 px, 3 deg by default).

    Returns
    -------
    CeilingResult
        Per-frame rows and ``ceiling_pct``, the share of labelled frames
        whose best-scoring state is correct.

    Raises
    ------
    TypeError
        If ``tracker`` does not implement ``score_states``.
    ValueError
        If the sequence is not a camera sequence or has no frames, or if
        the tracker returns scores of the wrong shape or NaN, naming the
        tracker, the sequence and the frame.

    References
    ----------
    seeds/000, section 4.5, eq. (4.11) (the condensation tracker's weight);
    seeds/004, section VI-C and Table V (the detection rule); conventions.md
    section 3.
    """
    name = _tracker_name(tracker)
    if not isinstance(tracker, ScoresStates):
        raise TypeError(f"tracker {name!r} ({type(tracker).__qualname__}) does not implement score_states")
    info = sequence.info
    if info.modality != CAMERA:
        raise ValueError(f"sequence {info.name!r} is a {info.modality} sequence; the ceiling needs a camera sequence")
    frames = iter(sequence.frames())
    first = next(frames, None)
    if first is None:
        raise ValueError(f"sequence {info.name!r} has no frames")
    tracker.reset(info, np.random.default_rng(0), init=first.truth)  # type: ignore[attr-defined]
    scorer = CameraScorer(rule)
    rows: list[tuple[Any, ...]] = []
    for frame in (first, *frames):
        truth = frame.truth
        if truth is None or not truth.cable.is_known:
            continue
        where = f"tracker {name!r}, sequence {info.name!r}, frame {frame.index}"
        states = window.states(truth.cable)
        tick = time.perf_counter()
        scores = np.asarray(tracker.score_states(frame, states), dtype=float)
        score_ms = 1000.0 * (time.perf_counter() - tick)
        if scores.shape != (len(states),):
            raise ValueError(f"{where}: score_states returned shape {scores.shape} for {len(states)} states")
        if np.isnan(scores).any():
            raise ValueError(f"{where}: score_states returned NaN")
        best_index = int(np.argmax(scores))
        best = CableState.from_array(states[best_index])
        outcome, _ = scorer.score(best, truth, info)
        rows.append(
            (
                frame.index,
                best.d,
                math.degrees(best.alpha),
                best.w,
                math.degrees(best.beta),
                float(scores[best_index]),
                float(scores[window.truth_index]),
                outcome is Outcome.CORRECT,
                score_ms,
            )
        )
    table = pd.DataFrame.from_records(rows, columns=list(FRAME_COLUMNS)).astype({"frame": int, "ceiling_ok": bool})
    return CeilingResult(name, info.name, window, table)


def latest_correct_pct(
    store: ResultStore, tracker_key: str, dataset_key: str, modalities: Mapping[str, Modality]
) -> float:
    """The share of frames correct in the latest stored run of a tracker on a dataset, seeds pooled.

    Parameters
    ----------
    store : ResultStore
        The results database.
    tracker_key : str
        The tracker's cache key (name, version and parameters:
        :attr:`benchmark.registry.TrackerEntry.cache_key`), so that the
        result is that of the model the ceiling was computed for.
    dataset_key : str
        The dataset's identity key (:attr:`benchmark.identity.DatasetIdentity.key`).
    modalities : Mapping
        The registered modalities by name.

    Returns
    -------
    float
        ``correct_pct`` as the leaderboard pools it over the seeds of the
        latest run holding the pair, initialised from the truth (the
        default run); nan when no run holds it.
    """
    for run_id in reversed(store.runs()["id"].tolist()):
        cells = store.cells(int(run_id))
        mine = cells[
            (cells["tracker_key"] == tracker_key) & (cells["dataset_key"] == dataset_key) & (cells["init"] == "truth")
        ]
        if not mine.empty:
            boards = leaderboards(mine, store.frame_tables(mine["id"]), modalities)
            rows = pd.concat(boards.values())
            return float(rows.loc[~rows["dataset"].map(is_pooled), "correct_pct"].iloc[0])
    return math.nan


def ceiling_report(
    entry: TrackerEntry,
    sequences: Iterable[Sequence],
    modalities: Mapping[str, Modality],
    store: ResultStore | None = None,
    window: CeilingWindow = CeilingWindow(),
    report: Report | None = None,
) -> tuple[pd.DataFrame, list[str]]:
    """The likelihood ceiling of a registered tracker on every camera sequence, beside its stored result.

    Parameters
    ----------
    entry : TrackerEntry
        A camera tracker whose instances implement
        :class:`~benchmark.tracker.ScoresStates`.
    sequences : iterable of Sequence
        Sequences to diagnose; those of other modalities are skipped.
    modalities : Mapping
        The registered modalities by name.
    store : ResultStore, optional
        The results database whose latest run of the tracker on each
        sequence gives ``correct_pct`` (:func:`latest_correct_pct`); without
        it the column is empty.
    window : CeilingWindow
        The grid searched around each true state.
    report : callable, optional
        Told ``report(done, total)`` sequences as each is diagnosed
        (:class:`benchmark.progress.Meter`).

    Returns
    -------
    table : pandas.DataFrame
        Columns :data:`REPORT_COLUMNS`, one row per camera sequence:
        ``frames`` labelled frames, ``ceiling_pct`` (:func:`likelihood_ceiling`)
        and ``correct_pct`` (nan when not stored).
    skipped : list of str
        One line per sequence left out, naming it and why.

    Raises
    ------
    SelectionError
        If the tracker is not a camera tracker or does not implement
        ``score_states``, or no sequence is a camera sequence.

    References
    ----------
    seeds/000, section 4.5, eq. (4.11); seeds/004, section VI-C.
    """
    if entry.modality != CAMERA:
        raise SelectionError(f"tracker {entry.name!r} reads {entry.modality}; the ceiling is for camera trackers")
    if not issubclass(entry.tracker_class, ScoresStates):
        raise SelectionError(
            f"tracker {entry.name!r} does not implement score_states (benchmark.tracker.ScoresStates): "
            "it exposes no observation model to search"
        )
    rows: list[dict[str, Any]] = []
    skipped: list[str] = []
    sequences = list(sequences)
    for done, sequence in enumerate(sequences):
        if report is not None:
            report(done, len(sequences))
        identity = sequence.identity
        if identity.modality != CAMERA:
            skipped.append(f"skipped {identity.name}: a {identity.modality} sequence, not a camera sequence")
            continue
        result = likelihood_ceiling(entry.create(), sequence, window)  # type: ignore[arg-type]
        stored = math.nan if store is None else latest_correct_pct(store, entry.cache_key, identity.key, modalities)
        rows.append(dict(zip(REPORT_COLUMNS, (identity.name, result.labelled, result.ceiling_pct, stored))))
    if not rows:
        raise SelectionError(f"nothing to diagnose: no camera sequence selected ({'; '.join(skipped) or 'none'})")
    if report is not None:
        report(len(sequences), len(sequences))
    return pd.DataFrame(rows, columns=list(REPORT_COLUMNS)), skipped


def ceiling_markdown(table: pd.DataFrame, tracker: str) -> str:
    """A :func:`ceiling_report` table as Markdown under a heading naming the tracker, percentages to 0.1."""
    return titled_table(table, f"Likelihood ceiling of {tracker}")


__all__ = [
    "CeilingResult",
    "CeilingWindow",
    "ceiling_markdown",
    "ceiling_report",
    "latest_correct_pct",
    "likelihood_ceiling",
]
