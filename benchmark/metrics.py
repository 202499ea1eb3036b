"""Per-frame scores and per-cell summaries.

Every frame a tracker processes gets a :class:`FrameScore`: its detection
outcome (seeds/004, section VI-C, Table V), the estimate's errors and the
time the tracker's ``step`` took.  A modality's :class:`Scorer` knows what an
estimate and a truth look like; :func:`summarise` turns a cell's frame
scores into the rates, RMSEs and speed of a leaderboard row.

Column names carry their units (``conventions.md`` section 4): angles are
reported in degrees, distances in px (camera) or m (sonar, stereo).
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from typing import Any, Protocol

import numpy as np
import pandas as pd

from benchmark.geometry import DetectionRule, cable_borders, score_line_pair, state_errors
from benchmark.model import (
    CableState,
    CameraTruth,
    Outcome,
    PipeEstimate,
    SequenceInfo,
    SonarTruth,
    StereoTruth,
    TargetEstimate,
)


class EstimateError(TypeError):
    """A tracker returned something that is not an estimate of its modality."""


@dataclass(frozen=True)
class FrameScore:
    """The score of one frame.

    Attributes
    ----------
    index : int
        Frame index in its sequence.
    outcome : Outcome or None
        None when the frame has no ground truth and is not scored.
    errors : Mapping[str, float]
        Estimate minus truth, one entry per error column of the modality;
        ``nan`` where there is no estimate or no truth.
    step_s : float
        Wall time of the tracker's ``step`` for this frame.
    """

    index: int
    outcome: Outcome | None
    errors: Mapping[str, float] = field(default_factory=dict)
    step_s: float = 0.0


class Scorer(Protocol):
    """What scoring needs to know about a modality."""

    error_columns: tuple[str, ...]
    """Names of the per-frame error columns, with units, e.g. ``err_d_px``."""

    def check(self, estimate: Any) -> None:
        """Raise :class:`EstimateError` unless ``estimate`` is None or valid."""

    def score(self, estimate: Any, truth: Any, info: SequenceInfo) -> tuple[Outcome | None, tuple[float, ...]]:
        """Outcome and errors (in ``error_columns`` order) of one frame."""


@dataclass(frozen=True)
class CameraScorer:
    """Scores camera frames by the line-pair rule and the cable-state errors.

    Parameters
    ----------
    rule : DetectionRule
        Thresholds of the line-pair rule (5 px, 3 deg by default).

    References
    ----------
    seeds/004, section VI-C and Table V; conventions.md section 3.
    """

    rule: DetectionRule = DetectionRule()
    error_columns: tuple[str, ...] = ("err_d_px", "err_alpha_deg", "err_w_px", "err_beta_deg")

    def check(self, estimate: Any) -> None:
        if estimate is None:
            return
        if not isinstance(estimate, CableState):
            raise EstimateError(f"expected a CableState or None, got {type(estimate).__name__}: {estimate!r}")
        if not estimate.is_known:
            raise EstimateError(f"estimate has non-finite values: {estimate}")

    def score(
        self, estimate: CableState | None, truth: CameraTruth | None, info: SequenceInfo
    ) -> tuple[Outcome | None, tuple[float, ...]]:
        nan = (math.nan,) * len(self.error_columns)
        if truth is None or not truth.cable.is_known:
            return None, nan
        if estimate is None:
            return Outcome.MISSED, nan
        if info.frame_size is None:
            raise ValueError(f"sequence {info.name!r} has no frame size; cannot score line pairs")
        outcome = score_line_pair(cable_borders(estimate), cable_borders(truth.cable), info.frame_size, self.rule)
        d, alpha, w, beta = state_errors(estimate, truth.cable)
        return outcome, (d, math.degrees(alpha), w, math.degrees(beta))


@dataclass(frozen=True)
class StereoScorer:
    """Scores target estimates by their position, speed and heading errors.

    A frame is correct when the estimated position is within
    ``tolerance_m`` of the true one, false when it is farther, missed when
    the tracker reported nothing.  The paper scores by RMSE only (seeds/002,
    Tables 6-8); the default tolerance of 1 m is about one and a half times
    the EKF's position RMSE there, so a tracker of that quality is correct
    in most frames.

    Parameters
    ----------
    tolerance_m : float
        Largest position error of a correct frame.

    References
    ----------
    seeds/002, section 3.5 and Tables 6-8.
    """

    tolerance_m: float = 1.0
    error_columns: tuple[str, ...] = ("err_position_m", "err_speed_mps", "err_heading_deg")

    def check(self, estimate: Any) -> None:
        if estimate is None:
            return
        if not isinstance(estimate, TargetEstimate):
            raise EstimateError(f"expected a TargetEstimate or None, got {type(estimate).__name__}: {estimate!r}")
        if not all(math.isfinite(v) for v in (*estimate.position_m, *estimate.velocity_mps)):
            raise EstimateError(f"estimate has non-finite values: {estimate}")

    def score(
        self, estimate: TargetEstimate | None, truth: StereoTruth | None, info: SequenceInfo
    ) -> tuple[Outcome | None, tuple[float, ...]]:
        nan = (math.nan,) * len(self.error_columns)
        if truth is None:
            return None, nan
        if estimate is None:
            return Outcome.MISSED, nan
        true = truth.target
        position = math.dist(estimate.position_m, true.position_m)
        heading = math.remainder(estimate.heading - true.heading, 2.0 * math.pi)
        outcome = Outcome.CORRECT if position <= self.tolerance_m else Outcome.FALSE
        return outcome, (position, estimate.speed_mps - true.speed_mps, math.degrees(heading))


@dataclass(frozen=True)
class SonarScorer:
    """Scores across-track pipe positions against the sonar's resolution.

    A ping is correct when the estimate is within ``tolerance_beams`` times
    the truth's ``resolution_m`` (the across-track distance between
    neighbouring beams at the pipe) of the pipe's axis, false when it is
    farther, missed when the tracker reported nothing.  The paper counts a
    detection as a match "with the accuracy set by the sensor's
    resolution" (seeds/003, section 4.1); one beam spacing is that reading.

    Parameters
    ----------
    tolerance_beams : float
        Largest error of a correct ping, in beam spacings at the pipe.

    References
    ----------
    seeds/003, sections 4.1-4.2.
    """

    tolerance_beams: float = 1.0
    error_columns: tuple[str, ...] = ("err_across_m",)

    def check(self, estimate: Any) -> None:
        if estimate is None:
            return
        if not isinstance(estimate, PipeEstimate):
            raise EstimateError(f"expected a PipeEstimate or None, got {type(estimate).__name__}: {estimate!r}")
        if not math.isfinite(estimate.across_m):
            raise EstimateError(f"estimate has a non-finite position: {estimate}")

    def score(
        self, estimate: PipeEstimate | None, truth: SonarTruth | None, info: SequenceInfo
    ) -> tuple[Outcome | None, tuple[float, ...]]:
        if truth is None or not math.isfinite(truth.across_m):
            return None, (math.nan,)
        if estimate is None:
            return Outcome.MISSED, (math.nan,)
        error = estimate.across_m - truth.across_m
        correct = abs(error) <= self.tolerance_beams * truth.resolution_m
        return (Outcome.CORRECT if correct else Outcome.FALSE), (error,)


SCORERS: dict[str, Scorer] = {"camera": CameraScorer(), "sonar": SonarScorer(), "stereo": StereoScorer()}
"""The scorer of each modality."""


def scorer_for(modality: str) -> Scorer:
    """The :class:`Scorer` of a modality."""
    try:
        return SCORERS[modality]
    except KeyError:
        raise KeyError(f"no scorer for modality {modality!r} (known: {', '.join(SCORERS)})") from None


def frame_table(scores: Iterable[FrameScore]) -> pd.DataFrame:
    """Frame scores as a table: ``frame``, ``outcome``, error columns, ``step_ms``."""
    rows = [
        {
            "frame": s.index,
            "outcome": None if s.outcome is None else str(s.outcome),
            **s.errors,
            "step_ms": 1000.0 * s.step_s,
        }
        for s in scores
    ]
    return pd.DataFrame(rows)


def summarise(frames: pd.DataFrame, error_columns: Iterable[str]) -> dict[str, float]:
    """Rates, RMSEs and speed of one cell (or of several pooled cells).

    Parameters
    ----------
    frames : pandas.DataFrame
        Frame scores as made by :func:`frame_table`.
    error_columns : iterable of str
        The modality's error columns; ``err_X`` becomes ``rmse_X``.

    Returns
    -------
    dict
        ``frames`` (scored frames), ``correct_pct``, ``false_pct``,
        ``missed_pct`` (percentages of scored frames, summing to 100),
        ``rmse_*`` over frames with both an estimate and a truth, and ``fps``
        (frames processed per second of ``step`` time).
    """
    columns = list(error_columns)
    outcomes = frames["outcome"].dropna() if "outcome" in frames else pd.Series(dtype=object)
    scored = len(outcomes)
    summary: dict[str, float] = {"frames": float(scored)}
    for outcome in Outcome:
        count = int((outcomes == str(outcome)).sum())
        summary[f"{outcome}_pct"] = 100.0 * count / scored if scored else math.nan
    for column in columns:
        values = frames[column].to_numpy(dtype=float) if column in frames else np.array([])
        values = values[np.isfinite(values)]
        name = "rmse_" + column.removeprefix("err_")
        summary[name] = float(np.sqrt(np.mean(values**2))) if values.size else math.nan
    step_s = frames["step_ms"].sum() / 1000.0 if "step_ms" in frames else 0.0
    summary["fps"] = len(frames) / step_s if step_s > 0 else math.nan
    return summary
