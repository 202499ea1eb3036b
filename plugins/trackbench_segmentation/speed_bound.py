"""The speed bound of the segmentation tracker: OpenCV's histogram and lookup over the same pyramid cells.

Ortiz et al.'s detector (seeds/000, section 2.3, Fig. 2.4) smooths the
image, takes its Sobel gradient, counts every cell of the image pyramid in
a grey level x gradient histogram and maps each pixel's grey level back to
its region.  The bound makes the OpenCV calls of that and nothing else:
``GaussianBlur`` at the tracker's smoothing, the two ``Sobel`` derivatives
and their ``magnitude`` over the frame, then, a cell at a time over the cells of
:func:`trackbench_segmentation.detector.cell_pyramid` at the tracker's
levels, ``calcHist`` of the two channels at the tracker's bins and ``LUT``
of the cell's grey levels.  The histograms count the tracker's own
normalised grey image and gradient rows (worked out once a frame, untimed,
by :class:`benchmark.speed.bounds.PerFrame`); the lookup table stands for the
mountains of a cell, which the bound does not look for.  Goal: issue 34's.
"""

from __future__ import annotations

from typing import Any

import cv2
import numpy as np

from benchmark import hookimpl
from benchmark.model import Frame, SequenceInfo
from benchmark.speed.bounds import BoundContext, PerFrame, RatioAtMost, SpeedBound, SpeedBounds
from trackbench_segmentation.detector import cell_pyramid
from trackbench_segmentation.grey import normalised_grey
from trackbench_segmentation.histogram import gradient_bins, gradient_modulus
from trackbench_segmentation.scaling import frame_params

DATASET = "camera/S1"
"""The sequence timed: the thesis' first test sequence (seeds/000, Fig. 5.2)."""
GREY_LEVELS = 256
MOUNTAINS = (np.arange(GREY_LEVELS) // 32).astype(np.uint8)
"""A lookup table of eight grey intervals, standing for a cell's mountains."""

Planes = tuple[np.ndarray, np.ndarray, tuple[Any, ...], int, float]
"""A frame's normalised grey image, gradient rows (``uint8``), pyramid cells, gradient bins and smoothing."""


class HistogramAndLookup:
    """``GaussianBlur``, ``Sobel`` and ``magnitude`` over the frame; ``calcHist`` and ``LUT`` over each pyramid cell."""

    def __init__(self, context: BoundContext) -> None:
        self.params = context.params
        self.planes: PerFrame[Planes] = PerFrame(self._planes)

    def _planes(self, frame: Frame) -> Planes:
        image = np.asarray(frame.observation)
        height, width = image.shape
        p = frame_params(self.params, (width, height))
        grey = normalised_grey(image, p.smoothing_sigma, p.grey_quantiles)
        rows = gradient_bins(gradient_modulus(grey), p.gradient_bin, p.gradient_bins).astype(np.uint8)
        return grey, rows, cell_pyramid((width, height), p.pyramid_levels), int(p.gradient_bins), p.smoothing_sigma

    def reset(self, info: SequenceInfo, rng: np.random.Generator, init: Any = None) -> None:
        """Nothing to reset: each frame stands alone."""

    def step(self, frame: Frame) -> int:
        grey, rows, cells, bins, sigma = self.planes(frame)
        smooth = cv2.GaussianBlur(np.asarray(frame.observation), (0, 0), sigma) if sigma > 0 else grey
        gx = cv2.Sobel(smooth, cv2.CV_32F, 1, 0, ksize=3, borderType=cv2.BORDER_REPLICATE)
        gy = cv2.Sobel(smooth, cv2.CV_32F, 0, 1, ksize=3, borderType=cv2.BORDER_REPLICATE)
        cv2.magnitude(gx, gy)
        counted = 0
        for cell in cells:
            cell_grey, cell_rows = grey[cell], rows[cell]
            ranges = [0, GREY_LEVELS, 0, bins]
            histogram = cv2.calcHist([cell_grey, cell_rows], [0, 1], None, [GREY_LEVELS, bins], ranges)
            cv2.LUT(cell_grey, MOUNTAINS)
            counted += int(histogram.shape[0])
        return counted


@hookimpl
def trackbench_register_speed_bounds(registry: SpeedBounds) -> None:
    """segmentation against OpenCV's smoothing, gradient, calcHist and LUT over its pyramid cells."""
    bound = "OpenCV GaussianBlur + Sobel + calcHist + LUT over its pyramid cells"
    registry.add_bound(SpeedBound("segmentation", bound, HistogramAndLookup, DATASET, RatioAtMost(1.5)))
