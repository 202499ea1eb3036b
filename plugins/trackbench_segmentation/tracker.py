"""The segmentation tracker of Ortiz et al. (seeds/000, section 2.3).

Each frame is searched by the detection process of Fig. 2.5
(:mod:`trackbench_segmentation.detector`): a pyramid of cells, each
segmented by its grey level x gradient histogram (Panda and Rosenfeld),
contour chains followed up from the bottom of the image in the predicted
direction, straight segments grouped and filtered, nearly parallel pairs
chosen by expected width, parallelism and length, and the cells' best pairs
fused into one.  The pair with the highest score after the fusion is the
frame's estimate, reported as the cable state its two lines define.

Between frames a Kalman filter on the cable's position, orientation and
width (:mod:`trackbench_segmentation.tracking`) predicts a region of
interest, the orientation the chains follow and the expected width.  On a
frame without a pair the filter only predicts, so its covariance, and with
it the region of interest, grows; after ``max_misses`` such frames in a row
the cable is lost, the filter forgets it and the next frame is searched
whole again.

The filter's variances and the region of interest's margin are stated for
a 320 px wide frame and follow the frame width
(:func:`trackbench_segmentation.scaling.frame_params`): on a 640 x 480
frame the cable moves twice as many pixels between frames.

The thesis reports 89.8 % of 1367 real 320 x 240 images detected at 24 ms a
frame on an 800 MHz Pentium III ([AO03], seeds/000, section 2.3).  Ours on
the rendered camera suite and clutter family are in :mod:`trackbench_segmentation`.

Ground truth: the tracker never reads a frame's truth.  When the run
initialises from truth (``init`` in :meth:`SegmentationTracker.reset`) and
``use_init`` is set, the filter starts from the initial cable, so the first
frame is already searched in its region of interest.  The tracker is
deterministic and does not use the random generator.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from benchmark.filters.kalman import Gaussian, GaussianBeliefView
from benchmark.filters.kalman import compile_kernels as compile_filter_kernels
from benchmark.lazy import lazy_module
from benchmark.modalities.camera.geometry import Line
from benchmark.modalities.camera.io.video import grey_frame
from benchmark.modalities.camera.model import CableState, CameraFrame, CameraTruth
from benchmark.model import SequenceInfo
from benchmark.tracker import Tracker
from trackbench_segmentation.params import SegmentationParams
from trackbench_segmentation.scaling import frame_params
from trackbench_segmentation.tracking import CableKalman, region_of_interest

if TYPE_CHECKING:
    from trackbench_segmentation.detector import Prediction
    from trackbench_segmentation.pairing import BorderPair

# The detector and its numba kernels load on the first frame, so that listing the trackers does not import numba.
band = lazy_module("trackbench_segmentation.band")
detector = lazy_module("trackbench_segmentation.detector")
lines = lazy_module("trackbench_segmentation.lines")


class SegmentationTracker(GaussianBeliefView, Tracker[CameraTruth, CableState]):
    """Histogram segmentation, contour lines and border pairs with a Kalman-predicted region of interest.

    Attributes
    ----------
    filter : CableKalman
        The Kalman filter on ``(d, alpha, w)``; its ``belief`` is None while
        the cable is lost.
    prediction : Prediction or None
        What the last frame was searched with; None for the whole image.

    The filter's belief is exposed as a :class:`~benchmark.testing.beliefs.GaussianBelief`
    (:attr:`mean`, :attr:`covariance`), and the prediction a frame's pair
    corrected as a :class:`~benchmark.testing.beliefs.GaussianUpdate`
    (:attr:`prior_covariance`).

    References
    ----------
    seeds/000, section 2.3 (Ortiz et al. [AO03, OSO02]; Panda and Rosenfeld [PR78]) and Fig. 2.4-2.5.
    """

    name = "segmentation"
    version = "2.0"
    modality = "camera"
    deterministic = True
    Params = SegmentationParams

    def __init__(self, params: SegmentationParams | None = None) -> None:
        super().__init__(params)
        p = self.params
        self.filter = CableKalman(p.process_var, p.measurement_var)
        self.prediction: Prediction | None = None
        self.search_region: tuple[Line, ...] | None = None
        """The two lines bounding the region of interest the latest step searched (:class:`~benchmark.tracker.Searches`)."""
        self._misses = 0
        self._started = False
        self._pending: CableState | None = None

    @property
    def belief(self) -> Gaussian | None:
        """The filter's Gaussian belief over ``(d, alpha, w)``, or None while the cable is lost."""
        return self.filter.belief

    @property
    def prior(self) -> Gaussian | None:
        """The prediction this frame's pair corrected (seeds/002, Table 2, line 3); None when no pair did."""
        return self.filter.prior

    def reset(self, info: SequenceInfo, rng: np.random.Generator, init: CameraTruth | None = None) -> None:
        """Forget the previous sequence; optionally start tracking from ``init``.

        Parameters
        ----------
        info : SequenceInfo
            Its frame size, when known, states the filter's variances in
            pixels of that size at once; otherwise the start waits for the
            first frame.
        rng : numpy.random.Generator
            Not used: the tracker is deterministic.
        init : CameraTruth, optional
            The first frame's truth; with ``use_init`` its cable, when known,
            starts the filter.
        """
        # What frames run: the filter, the region of interest, the detector's passes (with the histogram kernels a
        # cell may need), and the grouping of the pairs' slow form; the contours' one-cell forms are not run.
        compile_filter_kernels()
        band.compile_kernels()
        detector.compile_kernels()
        lines.compile_kernels()
        self.filter.forget()
        self.prediction = None
        self.search_region = None
        self._misses = 0
        self._started = False
        self._pending = init.cable if self.params.use_init and init is not None and init.cable.is_known else None
        if info.frame_size is not None:
            self._take_frame_size(info.frame_size)

    def _take_frame_size(self, size: tuple[int, int]) -> SegmentationParams:
        """The parameters in pixels of frames of ``size``; the filter takes their variances and a waiting start."""
        p = frame_params(self.params, size)
        self.filter.use_noise(p.process_var, p.measurement_var)
        if self._pending is not None:
            self.filter.start(self._pending)
            self._pending = None
        return p

    def step(self, frame: CameraFrame) -> CableState | None:
        """Predict, search the region of interest, correct the filter and report the best pair.

        Parameters
        ----------
        frame : CameraFrame
            Its observation is a grey ``uint8`` image of shape ``(H, W)``.

        Returns
        -------
        CableState or None
            The state of the best border pair
            (:func:`benchmark.modalities.camera.geometry.cable_from_borders`); None when
            no plausible pair is found.

        Raises
        ------
        DataError
            If the observation is not a grey image, naming the frame.

        References
        ----------
        seeds/000, section 2.3.
        """
        image = grey_frame(frame.observation, f"segmentation: frame {frame.index}", min_size_px=3)
        height, width = image.shape
        p = self._take_frame_size((width, height))
        if self._started:
            self.filter.predict()
        self._started = True
        belief = self.filter.belief
        self.search_region = None
        if belief is None:
            self.prediction = None
        else:
            roi, half_width = region_of_interest(belief, (width, height), p.roi_margin_px, p.roi_sigmas)
            alpha = float(np.clip(belief.mean[1], -1.4, 1.4))
            self.prediction = detector.Prediction(roi, alpha, float(belief.mean[2]))
            d, roi_alpha = float(belief.mean[0]), float(belief.mean[1])
            self.search_region = tuple(Line.from_normal(d + side * half_width, roi_alpha) for side in (-1, 1))
        pair = self._first_in_gate(detector.detect_pairs(image, p, self.prediction), p.gate_sigmas)
        if pair is None:
            self._misses += 1
            if self._misses >= p.max_misses:
                self.filter.forget()
            return None
        self._misses = 0
        self.filter.update(pair.state)
        return pair.state

    def _first_in_gate(self, pairs: list[BorderPair], gate_sigmas: float) -> BorderPair | None:
        """The best pair whose state lies within ``gate_sigmas`` (Mahalanobis) of the prediction; 0: the best pair."""
        if gate_sigmas == 0:
            return pairs[0] if pairs else None
        limit = gate_sigmas**2
        return next((pair for pair in pairs if self.filter.distance(pair.state) <= limit), None)
