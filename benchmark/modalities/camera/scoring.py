"""Scoring camera frames: the line-pair rule of Foresti's Table V and the cable-state errors.

A frame is correct when, for each ground-truth border of the cable, the
matched reported line has its mid-point within 5 px and its orientation
within 3 degrees (seeds/004, section VI-C, Table V; ``conventions.md``
section 3); the errors are those of ``(d, alpha, w, beta)``, angles in
degrees (seeds/000, section 5.2.3).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from benchmark.modalities.camera.geometry import DetectionRule, cable_borders, score_line_pair, state_errors
from benchmark.modalities.camera.model import CableState, CameraTruth
from benchmark.modality import EstimateError
from benchmark.model import Outcome, SequenceInfo


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

    def check(self, estimate: CableState) -> None:
        """Raise EstimateError for non-finite values."""
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
