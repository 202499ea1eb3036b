"""The Hough baseline tracker of seeds/000, section 2.1.

Matsumoto and Ito and Balasuriya et al. find the cable as the most
particular pair of straight edges in the image.  Each frame goes through

1. a Laplacian of Gaussian and a threshold on the strength of its zero
   crossings, giving a binary edge image (:mod:`trackbench_hough.edges`);
2. the Hough transform for lines and non-maximum suppression of its
   near-duplicate maxima (:mod:`trackbench_hough.lines`);
3. the choice of the pair of lines most likely to be the cable borders:
   nearly parallel or slightly converging towards the top, of plausible
   width, with the most votes (:mod:`trackbench_hough.pairing`).

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
from typing import Annotated

import numpy as np
import pydantic
from annotated_types import Ge, Interval

from benchmark.errors import DataError
from benchmark.modalities.camera.geometry import cable_borders
from benchmark.modalities.camera.model import CableState, CameraFrame, CameraTruth
from benchmark.model import SequenceInfo
from benchmark.parameters import NonNegative, Positive, require_order
from benchmark.tracker import Tracker
from trackbench_hough.edges import edge_image
from trackbench_hough.lines import hough_lines, suppress_duplicates
from trackbench_hough.pairing import choose_pair, compatible_pairs
from trackbench_hough.window import SearchWindow


@pydantic.dataclasses.dataclass(frozen=True)
class HoughParams:
    """Parameters of the Hough baseline; defaults follow seeds/000 where it gives values.

    Each field's type declares its domain; the rule that is not a bound of
    one field is :meth:`__post_init__`.  A value outside them is a
    :class:`pydantic.ValidationError`.
    """

    log_sigma: Positive = 3.0
    """Standard deviation in px of the LoG's Gaussian (seeds/000, Fig. 2.2 shows 3 and 5)."""

    edge_step: NonNegative = 12.0
    """Edge threshold: smallest grey-level step a zero crossing must imply to survive."""

    rho_step_px: Positive = 1.0
    """Distance resolution of the Hough accumulator, px."""

    theta_step_deg: Annotated[float, Interval(gt=0, le=180)] = 1.0
    """Angle resolution of the Hough accumulator, degrees."""

    vote_fraction: Annotated[pydantic.FiniteFloat, Ge(0)] = 0.3
    """Vote threshold as a fraction of the shorter image side (a border spans the image)."""

    max_lines: Annotated[int, Ge(2)] = 12
    """Number of strongest lines, after duplicate suppression, that are paired."""

    duplicate_rho_px: NonNegative = 3.0
    """Lines closer than this in distance (and ``duplicate_theta_deg`` in angle) are one edge, px."""

    duplicate_theta_deg: NonNegative = 3.0
    """Lines closer than this in angle (and ``duplicate_rho_px`` in distance) are one edge, degrees."""

    max_skew_deg: Annotated[float, Interval(ge=0, lt=90)] = 10.0
    """Largest skew beta of a converging border pair, degrees (seeds/000, Table 5.2: 0 to 10)."""

    max_divergence_deg: Annotated[float, Interval(ge=0, lt=90)] = 1.0
    """Largest skew of a pair diverging towards the top, degrees (allows angle quantisation)."""

    min_width_px: NonNegative = 5.0
    """Smallest plausible cable width, px (seeds/000, Table 5.2)."""

    max_width_px: NonNegative = 100.0
    """Largest plausible cable width, px (seeds/000, Table 5.2)."""

    window_rho_px: Positive = 15.0
    """Half-width in distance of the tracking window around each previous border, px."""

    window_theta_deg: Positive = 5.0
    """Half-width in angle of the tracking window around each previous border, degrees."""

    closeness_weight: Annotated[float, Interval(ge=0, le=1)] = 0.5
    """While tracking, share of its votes a pair at the window's edge loses, in [0, 1]."""

    max_misses: Annotated[int, Ge(1)] = 3
    """Frames in a row without a pair after which the whole parameter space is searched again."""

    use_init: bool = True
    """Start in the window around ``init`` when the run initialises from truth."""

    def __post_init__(self) -> None:
        """The rule that is not a bound of one field: the plausible widths form a range.

        Raises
        ------
        ValueError
            Naming the parameters and their values.
        """
        require_order(self, ("min_width_px", "max_width_px"))


class HoughTracker(Tracker[CameraTruth, CableState]):
    """LoG edges, Hough lines and border-pair grouping with a tracking window.

    References
    ----------
    seeds/000, section 2.1 (Matsumoto and Ito; Balasuriya et al.);
    seeds/004, section IV (straight-line grouping).
    """

    name = "hough"
    version = "1.0"
    modality = "camera"
    deterministic = True
    Params = HoughParams

    def __init__(self, params: HoughParams | None = None) -> None:
        super().__init__(params)
        self._window: SearchWindow | None = None
        self._misses = 0

    def reset(self, info: SequenceInfo, rng: np.random.Generator, init: CameraTruth | None = None) -> None:
        """Forget the previous sequence; optionally start tracking from ``init``.

        Parameters
        ----------
        info : SequenceInfo
            Not used: the image size is read from each frame.
        rng : numpy.random.Generator
            Not used: the tracker is deterministic.
        init : CameraTruth, optional
            The first frame's truth; with ``use_init`` the borders of its
            cable, when known, centre the first search window.
        """
        self._window = None
        self._misses = 0
        if self.params.use_init and init is not None and init.cable.is_known:
            self._window = SearchWindow.around_borders(
                cable_borders(init.cable), self.params.window_rho_px, math.radians(self.params.window_theta_deg)
            )

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
        size = (width, height)
        edges = edge_image(image, p.log_sigma, p.edge_step)
        window = self._window
        lines = hough_lines(
            edges,
            p.rho_step_px,
            math.radians(p.theta_step_deg),
            max(1, math.ceil(p.vote_fraction * min(width, height))),
            window.theta_intervals() if window is not None else None,
        )
        if window is not None:
            lines = [line for line in lines if window.admits(line)]
        lines = suppress_duplicates(lines, p.duplicate_rho_px, math.radians(p.duplicate_theta_deg))[: p.max_lines]
        pairs = compatible_pairs(
            lines,
            size,
            max_skew=math.radians(p.max_skew_deg),
            max_divergence=math.radians(p.max_divergence_deg),
            min_width=p.min_width_px,
            max_width=p.max_width_px,
        )
        pair = choose_pair(pairs, window, p.closeness_weight)
        if pair is None:
            self._misses += 1
            if self._misses >= p.max_misses:
                self._window = None
            return None
        self._misses = 0
        self._window = SearchWindow.around(pair.first, pair.second, p.window_rho_px, math.radians(p.window_theta_deg))
        return pair.state
