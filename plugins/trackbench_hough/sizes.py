"""Sizes in pixels for one frame: the parameters' sizes, stated for one frame size, scaled to the frame.

The thesis states its sizes for the 320 x 240 frames of its sequences
(seeds/000, Table 5.2: cable widths of 5 to 100 px); the Hough papers it
reviews (section 2.1) work on frames of that order too.  A frame of another
size shows the same scene with more or fewer pixels, so every size that
measures the scene scales with the frame's short side,
``scale = min(W, H) / reference_side_px``:

* the plausible cable widths, the tracking window's distance range and the
  distance below which two lines are one edge;
* the accumulator's distance step, and with it, inversely, its angle step:
  a line across the frame whose angle is off by one angle step moves by
  about one distance step at its ends at every frame size, so a border
  gathers its votes in as few cells at 640 x 480 as at 320 x 240;
* the vote thresholds, fractions of the short side already.

The LoG's ``sigma`` is not scaled: the zero crossings of a rounded cable's
shading lie inside its silhouette by a distance that grows with ``sigma``,
and the detection rule judges that distance in pixels, whatever the frame
size (:mod:`trackbench_hough.params` gives the numbers).  Angles other than
the accumulator's step are the scene's and stay as they are.

With ``reference_side_px = None`` every size is taken as it is, in pixels
of any frame (``hough-paper``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from benchmark.modalities.camera.geometry import ImageSize
from trackbench_hough.params import HoughParams


@dataclass(frozen=True, slots=True)
class FrameSizes:
    """The Hough baseline's sizes for one frame size.

    Attributes
    ----------
    size : ImageSize
        ``(W, H)`` of the frame, px.
    scale : float
        Short side of the frame over ``reference_side_px`` (1 without a reference).
    rho_step : float
        Accumulator distance step, px.
    theta_step : float
        Accumulator angle step, rad.
    min_votes : int
        Votes every line needs: the partner threshold.
    anchor_votes : float
        Votes the stronger line of a pair needs.
    min_width, max_width : float
        Plausible cable widths, px.
    window_rho : float
        Half-width in distance of the tracking window, px.
    duplicate_rho : float
        Distance below which two lines are one edge, px.
    """

    size: ImageSize
    scale: float
    rho_step: float
    theta_step: float
    min_votes: int
    anchor_votes: float
    min_width: float
    max_width: float
    window_rho: float
    duplicate_rho: float

    @classmethod
    def for_frame(cls, params: HoughParams, size: ImageSize) -> FrameSizes:
        """The sizes of ``params`` scaled to a frame of ``size = (W, H)`` px.

        References
        ----------
        seeds/000, Table 5.2 (widths for its 320 x 240 frames) and section 2.1.
        """
        short = min(size)
        scale = 1.0 if params.reference_side_px is None else short / params.reference_side_px
        return cls(
            size=size,
            scale=scale,
            rho_step=params.rho_step_px * scale,
            theta_step=math.radians(params.theta_step_deg) / scale,
            min_votes=max(1, math.ceil(params.partner_fraction * short)),
            anchor_votes=params.vote_fraction * short,
            min_width=params.min_width_px * scale,
            max_width=params.max_width_px * scale,
            window_rho=params.window_rho_px * scale,
            duplicate_rho=params.duplicate_rho_px * scale,
        )
