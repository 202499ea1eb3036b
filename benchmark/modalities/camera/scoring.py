"""Scoring camera frames: the line-pair rule of Foresti's Table V and the cable-state errors.

A frame is correct when, for each ground-truth border of the cable, the
matched reported line has its mid-point within 5 px and its orientation
within 3 degrees (seeds/004, section VI-C, Table V; ``conventions.md``
section 3); the errors are those of ``(d, alpha, w, beta)``, angles in
degrees (seeds/000, section 5.2.3).  A finite but absurd estimate is false
(:meth:`CameraScorer.score`).  An estimate that reports the camera pose
(:class:`~benchmark.modalities.camera.model.PosedCableState`) is also
scored on it against a truth that knows the pose: the errors of ``C_x``,
``C_y`` (m), pan ``theta`` and tilt ``phi`` (deg), the quantities of
seeds/004, Tables III-IV; other estimates leave those errors empty.
"""

from __future__ import annotations

import math
import sys
from dataclasses import dataclass

import numpy as np

from benchmark.modalities.camera.geometry import DetectionRule, cable_borders, score_line_pair, state_errors
from benchmark.modalities.camera.model import CableState, CameraTruth, PosedCableState
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
    error_columns: tuple[str, ...] = (
        "err_d_px",
        "err_alpha_deg",
        "err_w_px",
        "err_beta_deg",
        "err_cx_m",
        "err_cy_m",
        "err_theta_deg",
        "err_phi_deg",
    )

    def check(self, estimate: CableState) -> None:
        """Raise EstimateError for non-finite values, of the cable or of a reported pose."""
        if not estimate.is_known:
            raise EstimateError(f"estimate has non-finite values: {estimate}")
        pose = estimate.pose if isinstance(estimate, PosedCableState) else None
        if pose is not None and not all(math.isfinite(v) for v in (pose.cx, pose.cy, pose.theta, pose.phi)):
            raise EstimateError(f"estimate reports a pose with non-finite values: {pose}")

    def score(
        self, estimate: CableState | None, truth: CameraTruth | None, info: SequenceInfo
    ) -> tuple[Outcome | None, tuple[float, ...]]:
        """Outcome, ``(d, alpha, w, beta)`` errors (px, deg, px, deg) and pose errors (m, m, deg, deg) of one frame.

        A finite but absurd estimate is false whatever its line pair looks
        like, and its errors stay finite so that the store keeps them and the
        RMSEs show it:

        * an error too large for a float (``degrees(beta)`` beyond about
          ``3e306`` rad) is reported as ``+-sys.float_info.max``;
        * an angle so large that neighbouring floats are farther apart than
          the rule's orientation tolerance names no direction: the float
          ``2 pi`` wrapping of ``alpha`` and the exact reduction inside
          ``cos`` and ``sin`` then disagree, and either may match the truth
          by chance.  An ``alpha`` like that is charged 90 deg, the largest
          error an orientation modulo 180 deg has; ``beta`` keeps its
          (huge) difference;
        * a border whose points overflow (``|d| + |w|/2`` beyond the float
          range) is nowhere near the image.

        Otherwise the line-pair rule decides (seeds/004, section VI-C,
        Table V); its mid-point distances may overflow to ``inf``, which it
        reads as far.
        """
        nan = (math.nan,) * len(self.error_columns)
        if truth is None or not truth.cable.is_known:
            return None, nan
        if estimate is None:
            return Outcome.MISSED, nan
        outcome, errors = self._score_lines(estimate, truth, info)
        return outcome, errors + pose_errors(estimate, truth)

    def _score_lines(
        self, estimate: CableState, truth: CameraTruth, info: SequenceInfo
    ) -> tuple[Outcome, tuple[float, float, float, float]]:
        """The outcome by the line-pair rule and the cable-state errors."""
        if info.frame_size is None:
            raise ValueError(f"sequence {info.name!r} has no frame size; cannot score line pairs")
        max_angle = math.radians(self.rule.max_angle_deg)
        alpha_names_a_direction = math.ulp(estimate.alpha) <= max_angle
        d, alpha, w, beta = state_errors(estimate, truth.cable)
        errors = (d, math.degrees(alpha) if alpha_names_a_direction else 90.0, w, math.degrees(beta))
        if not all(math.isfinite(e) for e in errors):
            largest = sys.float_info.max
            return Outcome.FALSE, tuple(e if math.isfinite(e) else math.copysign(largest, e) for e in errors)
        if not (alpha_names_a_direction and math.ulp(estimate.beta) <= max_angle):
            return Outcome.FALSE, errors
        try:
            reported = cable_borders(estimate)
        except ValueError:
            return Outcome.FALSE, errors
        with np.errstate(over="ignore", invalid="ignore"):
            outcome = score_line_pair(reported, cable_borders(truth.cable), info.frame_size, self.rule)
        return outcome, errors


def pose_errors(estimate: CableState, truth: CameraTruth) -> tuple[float, float, float, float]:
    """Errors of ``C_x``, ``C_y`` (m), ``theta`` and ``phi`` (deg), estimate minus truth.

    All nan unless the estimate reports a finite pose and the truth knows it.

    References
    ----------
    seeds/004, section VI-A, Tables III-IV (the columns ``X*(k) - x(k)``, with the sign reversed).
    """
    pose = estimate.pose if isinstance(estimate, PosedCableState) else None
    if pose is None or truth.pose is None:
        return (math.nan,) * 4
    errors = (
        pose.cx - truth.pose.cx,
        pose.cy - truth.pose.cy,
        math.degrees(pose.theta - truth.pose.theta),
        math.degrees(pose.phi - truth.pose.phi),
    )
    return tuple(e if math.isfinite(e) else math.nan for e in errors)  # type: ignore[return-value]
