"""The Hough baseline tracker of seeds/000, section 2.1.

Matsumoto and Ito and Balasuriya et al. find the cable as the most
particular pair of straight edges in the image.  Each frame goes through

1. a Laplacian of Gaussian and a threshold on the strength of its zero
   crossings, giving a binary edge image (:mod:`trackbench_hough.edges`,
   :mod:`trackbench_hough.thresholds`);
2. the Hough transform for lines and non-maximum suppression of its
   near-duplicate maxima (:mod:`trackbench_hough.lines`);
3. the choice of the pair of lines most likely to be the cable borders:
   nearly parallel or slightly converging towards the top, of plausible
   width, with the most votes (:mod:`trackbench_hough.pairing`).

Sizes in pixels are stated for one frame size and scaled to each frame
(:mod:`trackbench_hough.sizes`); the parameters and the measurements behind
their defaults are in :mod:`trackbench_hough.params`.

Once a pair is found the Hough parameter space is limited to a window
around it, as Balasuriya et al. do (:mod:`trackbench_hough.window`); after
``max_misses`` frames in a row without a pair it is widened to the whole
space again.  The thesis names the weakness this brings: in an ambiguous
scene the wrong alternative may be tracked, and the window then keeps the
right one out.

Ground truth: the tracker never reads a frame's truth.  When the run
initialises from truth (``init`` in :meth:`HoughTracker.reset`) and
``use_init`` is set, the first frame is searched in the window around the
initial state instead of the whole space; otherwise ``init`` is ignored.
The tracker is deterministic and does not use the random generator.
"""

from __future__ import annotations

import math

import numpy as np

from benchmark.errors import DataError
from benchmark.modalities.camera.geometry import ImageSize, Line, cable_borders
from benchmark.modalities.camera.model import CableState, CameraFrame, CameraTruth
from benchmark.model import SequenceInfo
from benchmark.tracker import Tracker
from trackbench_hough.edges import compile_kernels, log_response, zero_crossings, zero_crossings_in
from trackbench_hough.lines import accumulator_maxima, distinct_line_rows
from trackbench_hough.lines import compile_kernels as compile_line_kernels
from trackbench_hough.pairing import best_pair
from trackbench_hough.params import HoughParams
from trackbench_hough.sizes import FrameSizes
from trackbench_hough.thresholds import EDGE_THRESHOLDS
from trackbench_hough.window import SearchWindow


class HoughTracker(Tracker[CameraTruth, CableState]):
    """LoG edges, Hough lines and border-pair grouping with a tracking window.

    References
    ----------
    seeds/000, section 2.1 (Matsumoto and Ito; Balasuriya et al.);
    seeds/004, section IV (straight-line grouping).
    """

    name = "hough"
    version = "2.0"
    modality = "camera"
    deterministic = True
    Params = HoughParams

    def __init__(self, params: HoughParams | None = None) -> None:
        super().__init__(params)
        self._window: SearchWindow | None = None
        self._searched: SearchWindow | None = None
        self._init_borders: tuple[Line, Line] | None = None
        self._sizes: FrameSizes | None = None
        self._misses = 0

    def reset(self, info: SequenceInfo, rng: np.random.Generator, init: CameraTruth | None = None) -> None:
        """Forget the previous sequence; optionally start tracking from ``init``.

        Parameters
        ----------
        info : SequenceInfo
            Its frame size, when known, scales the first window; otherwise
            the first frame's size does.
        rng : numpy.random.Generator
            Not used: the tracker is deterministic.
        init : CameraTruth, optional
            The first frame's truth; with ``use_init`` the borders of its
            cable, when known, centre the first search window.
        """
        compile_kernels()
        compile_line_kernels()
        self._window = None
        self._searched = None
        self._misses = 0
        self._init_borders = None
        if self.params.use_init and init is not None and init.cable.is_known:
            self._init_borders = cable_borders(init.cable)
            if info.frame_size is not None:
                self._start_window(self._sizes_for(info.frame_size))

    @property
    def search_region(self) -> tuple[Line, ...] | None:
        """The lines bounding the window the latest step searched (:class:`~benchmark.tracker.Searches`); None: all of it."""
        return None if self._searched is None else self._searched.bounds()

    def _sizes_for(self, size: ImageSize) -> FrameSizes:
        if self._sizes is None or self._sizes.size != size:
            self._sizes = FrameSizes.for_frame(self.params, size)
        return self._sizes

    def _start_window(self, sizes: FrameSizes) -> None:
        """Open the window around the initial borders, once the frame size is known."""
        if self._init_borders is not None:
            self._window = SearchWindow.around_borders(
                self._init_borders, sizes.window_rho, math.radians(self.params.window_theta_deg)
            )
            self._init_borders = None

    def edge_image(self, image: np.ndarray) -> np.ndarray:
        """The binary edge image the next :meth:`step` votes from, for a grey ``uint8`` image of shape ``(H, W)``.

        The LoG and the threshold are the whole frame's; while tracking, the
        zero crossings are found only where a pixel can vote for a line the
        window admits (:meth:`trackbench_hough.window.SearchWindow.voting_strips`),
        which changes no admitted line.

        References
        ----------
        seeds/000, section 2.1 (LoG zero crossings, thresholded; the limited search space).
        """
        p = self.params
        height, width = image.shape
        sizes = self._sizes_for((width, height))
        self._start_window(sizes)
        response = log_response(image, p.log_sigma)
        min_step = EDGE_THRESHOLDS[p.edge_rule](response, p.log_sigma, p)
        if self._window is None:
            return zero_crossings(response, p.log_sigma, min_step)
        strips = self._window.voting_strips(sizes.size, sizes.rho_step, sizes.theta_step)
        return zero_crossings_in(response, p.log_sigma, min_step, strips)

    def step(self, frame: CameraFrame) -> CableState | None:
        """Detect the cable borders in one frame.

        Parameters
        ----------
        frame : CameraFrame
            Its observation is a grey ``uint8`` image of shape ``(H, W)``.

        Returns
        -------
        CableState or None
            The state of the chosen border pair
            (:func:`benchmark.modalities.camera.geometry.cable_from_borders`); None when no
            plausible pair exists.

        Raises
        ------
        DataError
            If the observation is not a 2-D grey image.
        """
        image = np.asarray(frame.observation)
        if image.ndim != 2 or image.size == 0:
            raise DataError(
                f"hough: frame {frame.index}: expected a grey image of shape (H, W), got shape {image.shape}"
            )
        p = self.params
        height, width = image.shape
        sizes = self._sizes_for((width, height))
        edges = self.edge_image(image)
        window = self._searched = self._window
        raw = accumulator_maxima(
            edges,
            sizes.rho_step,
            sizes.theta_step,
            sizes.min_votes,
            window.theta_intervals() if window is not None else None,
        )
        lines = distinct_line_rows(
            raw,
            sizes.size,
            sizes.duplicate_rho,
            math.radians(p.duplicate_theta_deg),
            p.max_lines,
            *((window.borders, window.r_half, window.phi_half) if window is not None else ()),
        )
        pair = best_pair(
            lines,
            sizes.size,
            window,
            p.closeness_weight,
            max_skew=math.radians(p.max_skew_deg),
            max_divergence=math.radians(p.max_divergence_deg),
            min_width=sizes.min_width,
            max_width=sizes.max_width,
            anchor_votes=sizes.anchor_votes,
        )
        if pair is None:
            self._misses += 1
            if self._misses >= p.max_misses:
                self._window = None
            return None
        self._misses = 0
        self._window = SearchWindow.around(pair.first, pair.second, sizes.window_rho, math.radians(p.window_theta_deg))
        return pair.state
