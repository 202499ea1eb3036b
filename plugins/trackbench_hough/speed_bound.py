"""The speed bound of the hough tracker: OpenCV alone, as the tracker calls it, in the tracker's window.

Per frame the tracker's OpenCV work is the Laplacian of Gaussian
(``GaussianBlur`` and ``Laplacian``, :func:`trackbench_hough.edges.log_response`)
and the standard Hough transform (``HoughLinesWithAccumulator``) over the
angle intervals of its search window (seeds/000, section 2.1; Balasuriya's
limited parameter space).  The bound makes exactly those calls, with the
tracker's sigma, accumulator steps and vote threshold, on the tracker's own
edge image (:meth:`trackbench_hough.tracker.HoughTracker.edge_image`, which
while tracking holds zero crossings only near the window's borders) and
window of each frame; both are found once, untimed, by a shadow tracker
stepped over the same frames (:class:`benchmark.speed.bounds.PerFrame`).
OpenCV does not write to the edge image, so it is passed without a copy,
as the tracker passes it.
What it leaves out, the zero crossings, the window's admission, duplicate
suppression and pairing, is the tracker's own work.  Goal: issue 34's.

The LoG stays frame-wide in both: "the LoG filter still has to be applied
on the whole image" (seeds/000, section 2.1), and the tracker's threshold is
a statistic of the whole frame's zero crossings
(:mod:`trackbench_hough.thresholds`).
"""

from __future__ import annotations

import math
from typing import Any

import cv2
import numpy as np

from benchmark import hookimpl
from benchmark.model import Frame, SequenceInfo
from benchmark.speed.bounds import BoundContext, PerFrame, RatioAtMost, SpeedBound, SpeedBounds
from trackbench_hough.edges import log_response
from trackbench_hough.sizes import FrameSizes
from trackbench_hough.tracker import HoughTracker

DATASET = "camera/S1"
"""The sequence timed: the thesis' first test sequence (seeds/000, Fig. 5.2)."""

HoughInput = tuple[np.ndarray, list[tuple[float, float]], float, float, int]
"""A frame's edge image, the window's angle intervals, and the accumulator's steps and vote threshold."""


class OpenCVInWindow:
    """``GaussianBlur`` + ``Laplacian`` and ``HoughLinesWithAccumulator`` in the tracker's window, per frame."""

    def __init__(self, context: BoundContext) -> None:
        params = self.params = context.params
        self.shadow = HoughTracker(params)
        self.inputs: PerFrame[HoughInput] = PerFrame(self._shadow_step)

    def _shadow_step(self, frame: Frame) -> HoughInput:
        p = self.params
        image = np.asarray(frame.observation)
        height, width = image.shape
        sizes = FrameSizes.for_frame(p, (width, height))
        edges = self.shadow.edge_image(image)
        window = getattr(self.shadow, "_window", None)  # the window this frame is searched in; None: everywhere
        intervals = window.theta_intervals() if window is not None else [(0.0, math.pi)]
        self.shadow.step(frame)
        return edges, intervals, sizes.rho_step, sizes.theta_step, int(sizes.min_votes)

    def reset(self, info: SequenceInfo, rng: np.random.Generator, init: Any = None) -> None:
        if not self.inputs.values:
            self.shadow.reset(info, rng, init=init)

    def step(self, frame: Frame) -> int:
        edges, intervals, rho_step, theta_step, min_votes = self.inputs(frame)
        log_response(np.asarray(frame.observation), self.params.log_sigma)
        found = 0
        for low, high in intervals:
            if high - low < theta_step:
                low, high = max(0.0, 0.5 * (low + high) - theta_step), min(math.pi, 0.5 * (low + high) + theta_step)
            lines = cv2.HoughLinesWithAccumulator(
                edges, rho_step, theta_step, min_votes, min_theta=float(low), max_theta=float(high)
            )
            found += 0 if lines is None else len(lines)
        return found


@hookimpl
def trackbench_register_speed_bounds(registry: SpeedBounds) -> None:
    """hough against OpenCV's LoG and HoughLines in its window."""
    bound = "OpenCV alone: LoG + HoughLines in its window"
    registry.add_bound(SpeedBound("hough", bound, OpenCVInWindow, DATASET, RatioAtMost(1.2)))
