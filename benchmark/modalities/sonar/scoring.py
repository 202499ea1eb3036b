"""Scoring sonar pings: the across-track position against the sonar's resolution at the pipe."""

from __future__ import annotations

import math
import sys
from dataclasses import dataclass

from benchmark.modalities.sonar.model import PipeEstimate, SonarTruth
from benchmark.modality import EstimateError
from benchmark.model import Outcome, SequenceInfo


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

    def check(self, estimate: PipeEstimate) -> None:
        """Raise EstimateError for non-finite values."""
        if not math.isfinite(estimate.across_m):
            raise EstimateError(f"estimate has a non-finite position: {estimate}")

    def score(
        self, estimate: PipeEstimate | None, truth: SonarTruth | None, info: SequenceInfo
    ) -> tuple[Outcome | None, tuple[float, ...]]:
        """Outcome and across-track error (m) of one ping.

        An error too large for a float (``1e308 - (-1e308)``) is false
        whatever the tolerance and is reported as ``+-sys.float_info.max``,
        so that the store keeps it and the RMSE shows it.
        """
        if truth is None or not math.isfinite(truth.across_m):
            return None, (math.nan,)
        if estimate is None:
            return Outcome.MISSED, (math.nan,)
        error = estimate.across_m - truth.across_m
        if not math.isfinite(error):
            return Outcome.FALSE, (math.copysign(sys.float_info.max, error),)
        correct = abs(error) <= self.tolerance_beams * truth.resolution_m
        return (Outcome.CORRECT if correct else Outcome.FALSE), (error,)
