"""Scoring stereo frames: the target's position, speed and heading errors (seeds/002, Tables 6-8)."""

from __future__ import annotations

import math
import sys
from dataclasses import dataclass

from benchmark.modalities.stereo.model import StereoTruth, TargetEstimate
from benchmark.modality import EstimateError
from benchmark.model import Outcome, SequenceInfo


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

    def check(self, estimate: TargetEstimate) -> None:
        """Raise EstimateError for non-finite values."""
        if not all(math.isfinite(v) for v in (*estimate.position_m, *estimate.velocity_mps)):
            raise EstimateError(f"estimate has non-finite values: {estimate}")

    def score(
        self, estimate: TargetEstimate | None, truth: StereoTruth | None, info: SequenceInfo
    ) -> tuple[Outcome | None, tuple[float, ...]]:
        """Outcome and position (m), speed (m/s) and heading (deg) errors of one frame.

        Only the position decides the outcome, so a correct position with an
        absurd but finite velocity stays correct and its speed error shows
        on the board.  An error too large for a float (a distance or a speed
        beyond the largest float, e.g. a velocity of ``(1.7e308, 1.7e308)``)
        makes the frame false and is reported as ``sys.float_info.max``, so
        that the store keeps it and the RMSE shows it.
        """
        nan = (math.nan,) * len(self.error_columns)
        if truth is None:
            return None, nan
        if estimate is None:
            return Outcome.MISSED, nan
        true = truth.target
        position = math.dist(estimate.position_m, true.position_m)
        heading = math.remainder(estimate.heading - true.heading, 2.0 * math.pi)
        errors = (position, estimate.speed_mps - true.speed_mps, math.degrees(heading))
        if not all(math.isfinite(e) for e in errors):
            largest = sys.float_info.max
            return Outcome.FALSE, tuple(e if math.isfinite(e) else math.copysign(largest, e) for e in errors)
        outcome = Outcome.CORRECT if position <= self.tolerance_m else Outcome.FALSE
        return outcome, errors
