"""The speed bounds of the Foresti trackers: OpenCV's edge and line detection at their thresholds.

The feature extractor of seeds/004, section IV, finds Canny edges of the
smoothed image and votes their lines into a Hough accumulator.  The bound
is what OpenCV does of that in one call each, with the tracker's own
values: ``GaussianBlur`` at ``blur_sigma_px``, ``Canny`` (L2 gradient) at
the frame's hysteresis thresholds as the tracker's ``canny_rule`` sets them,
and ``HoughLines`` at its accumulator steps with its vote threshold scaled to
the frame (:meth:`~trackbench_foresti.params.FeatureParams.scaled_count`).
The thresholds of each frame are worked out once, untimed
(:class:`benchmark.speed.bounds.PerFrame`).  Goals: issue 34's.
"""

from __future__ import annotations

import math
from typing import Any

import cv2
import numpy as np

from benchmark import hookimpl
from benchmark.model import Frame, SequenceInfo
from benchmark.speed.bounds import BoundContext, PerFrame, RatioAtMost, SpeedBound, SpeedBounds
from trackbench_foresti.edges import as_grey, smoothed_gradient
from trackbench_foresti.thresholds import THRESHOLD_RULES

DATASET = "camera/S1"
"""The sequence timed: the thesis' first test sequence (seeds/000, Fig. 5.2)."""
GOALS = {"foresti_lines": RatioAtMost(1.2), "foresti_ekf": RatioAtMost(1.4)}
"""Issue 34's goal of each tracker timed."""


class OpenCVLines:
    """``GaussianBlur`` + ``Canny`` + ``HoughLines`` at the tracker's thresholds, per frame."""

    def __init__(self, context: BoundContext) -> None:
        self.params = context.params
        self.thresholds: PerFrame[tuple[float, float]] = PerFrame(self._thresholds)

    def _thresholds(self, frame: Frame) -> tuple[float, float]:
        p = self.params
        gu, gv = smoothed_gradient(as_grey(np.asarray(frame.observation)), p.blur_sigma_px)
        low, high = THRESHOLD_RULES[p.canny_rule](gu, gv, p.canny_low, p.canny_high, p.canny_percentile)
        return float(low), float(high)

    def reset(self, info: SequenceInfo, rng: np.random.Generator, init: Any = None) -> None:
        """Nothing to reset: each frame stands alone."""

    def step(self, frame: Frame) -> Any:
        p = self.params
        low, high = self.thresholds(frame)
        image = as_grey(np.asarray(frame.observation))
        smooth = cv2.GaussianBlur(image, (0, 0), sigmaX=p.blur_sigma_px, borderType=cv2.BORDER_REPLICATE)
        edges = cv2.Canny(smooth, low, high, L2gradient=True)
        votes = p.scaled_count(p.min_votes, image.shape[0])
        return cv2.HoughLines(edges, p.rho_step_px, math.radians(p.alpha_step_deg), int(votes))


@hookimpl
def trackbench_register_speed_bounds(registry: SpeedBounds) -> None:
    """Both Foresti trackers against OpenCV's GaussianBlur, Canny and HoughLines at their thresholds."""
    for name, goal in GOALS.items():
        bound = "OpenCV GaussianBlur + Canny + HoughLines, its thresholds"
        registry.add_bound(SpeedBound(name, bound, OpenCVLines, DATASET, goal))
