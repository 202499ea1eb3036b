"""The parameters of the segmentation tracker and where their defaults come from.

The thesis' review (seeds/000, section 2.3) describes the method of Ortiz
et al. without a single number besides its results, so every default here is
a reading of the text or a measurement.  The first defaults were measured on
the thesis' camera suite: the share of frames scored correct on
camera/S1..S7 and on the first two draws of the clutter family
(camera-clutter/S1-d01, S1-d02), tracking from the first frame without
ground truth, every other parameter at its default.  "Mean" in a field's
docstring is the mean of those nine shares (86.3 % as then shipped).  Those
values, in raw grey levels and in pixels of a 320 x 240 frame, are the
variant ``segmentation-paper`` (:data:`PAPER`).

The camera world (camera-train, camera-dev) showed that they hold for the
suite's contrast and frame size only: ``segmentation-paper`` is 51.5 %
correct on the 24 world sequences of camera-train (w01-w24), 70.4 % on
camera-dev, 46.9 % on the twelve world sequences of train and dev with the
lowest cable contrast (5-49 grey levels), and 53.2 % on 640 x 480 frames.
Six departures, chosen on camera-train and confirmed on camera-dev (one run
each, truth initialisation; the tracker is deterministic), make the cuts
relative to each frame's own statistics and the lengths relative to the
frame size.  With all of them (the defaults): 78.0 % on w01-w24, 85.9 % on
camera-dev, 79.6 % on the twelve low-contrast sequences, 85.5 % on
640 x 480 frames; 89.5 % on the S1-S7 redraws of camera-train (86.9 % for
``segmentation-paper``).  Below, "train" is w01-w24, "dev" camera-dev and
"low" the twelve low-contrast sequences; the numbers set one departure back
with the others as shipped, the gate off.  A caution on reading them: a
sequence either holds the cable or loses it to clutter for good, so one
small change can move a sequence from 100 to 10 % and back; differences of
a few points between settings are within that spread.

``grey_quantiles`` (paper: none, raw grey levels).  The histogram's
projection is smoothed, its gradient axis binned and long lines filtered in
grey levels; set for the suite's contrast, a murky frame's cable (cable
contrast 5-40 grey levels) has gradients below the cut and hills merged by
the smoothing.  The smoothed frame is stretched between its 5 and 95 %
quantiles (:mod:`trackbench_segmentation.grey`).  Raw grey levels instead:
train 75.2, dev 82.3, low 76.1 % (normalised: 79.2 / 84.4 / 79.9); the 1
and 99 % quantiles: 79.3 / 83.4 / 81.1 %.  On the sequence w10 (contrast
17, noise 6 grey levels) the paper's values are 4.2 % correct, normalised
ones 100 %.

``projection_sigma`` (paper: 3 grey levels).  In normalised levels the
paper's 3 smooths away the valleys between the cable's hill and the
ground's: 3 / 2 / 1 gave train 74.2 / 78.6 / 79.2, dev 78.7 / 81.4 /
84.4 %.  Finer cuts mean more contours to follow: about two thirds of the
paper variant's frame rate.

``reference_width_px`` and ``max_width_px`` (paper: none, 100 px).  Pipes
in the camera world are up to 0.29 of the frame width on camera-train and
0.44 on camera-dev (279 px at 640 x 480); the world's altitudes and pipe
diameters allow up to about 0.6.  Widths, the region of interest's margin
and the filter's variances are stated for 320 px and follow the frame width
(:mod:`trackbench_segmentation.scaling`), and the largest plausible width is
half the frame, 160 px at 320.  With a largest width of 100 px: dev 82.2 %
(d06, a pipe of 91-131 px at 320 x 240: 29.2 against 70.8 %); without the
scaling: dev 84.1 % (d04, 200-279 px at 640 x 480: 0 against 11.7 %); train
unchanged (no pipe there is wider than 160 px).  Scaling the variances as
well makes no measurable difference (train 78.8, dev 85.4 % without); it is
kept because the cable moves twice as many pixels in a frame twice as wide.
What does not scale: the smoothing, the edge snap and the segment lengths
describe pixel noise and optical blur, which the renderer draws per pixel
whatever the frame size; scaling them too gave train 71.7, dev 76.3 % and
69.8 % on 640 x 480 frames (84.8 % unscaled).

``min_gradient_ratio`` (paper: none).  Stretching a frame of bare sand to
the full range makes its texture as steep as a cable's borders: on drawn
sand (4 textures and noise levels, 12 seeds each) the tracker reported a
pair on 48 of 48 frames.  A long line must be 3 times steeper than the
frame's median gradient (:func:`trackbench_segmentation.detector.edge_gradient`):
0 of 48.  The true borders on camera-train are 4.5 to 90 times the median
(the median over a sequence's frames of the border's mean gradient,
normalised as above), except three concrete pipes whose shading softens
their edges (w01, w04, w11: 2.3-3.1); the sand's long lines 1.4 to 2.4.
Without it: train 80.8, dev 85.0, low 80.1 % (w01 33.3 against 5.0 %, w11
10.8 against 0 %).

``gate_sigmas`` (paper: none, the best pair wherever it lies).  With the
cuts above the detector finds more pairs, and in clutter the best-scored one
is sometimes a pair of rock edges inside the region of interest; the filter
follows it and its width drifts with the clutter, and the cable is never
sought again (camera/S1: 13.7 % correct, clutter draws S1-d03 and S1-d08: 5.2
and 10.9 %).  The standard validation gate of a Kalman tracker: the best
pair within 4 standard deviations of the prediction (squared Mahalanobis
distance 16: about one true measurement in a thousand is passed over if the
filter's model holds).  On camera and camera-clutter (19 sequences) no gate
/ 3 / 4 / 5 gave 78.2 / 84.3 / 92.0 / 86.5 % correct (S1 13.7 / 92.7 / 88.7
/ 87.9 %); on train 79.2 / 79.4 / 78.0 / 79.7, on dev 84.4 / 86.1 / 85.9 /
85.0 %.  Over the whole splits (all 31 sequences of camera-train, all 48 of
camera-dev, one run each side by side): no gate / 3 / 4 / 5 gave train
83.4 / 81.5 / 82.4 / 82.5 and dev 86.9 / 88.0 / 87.8 / 87.3 %, S1-S7's
redraws in camera-train 85.2 / 82.9 / 84.5 / 81.1 %.  Train and dev cannot
tell the gates apart; 4 standard deviations is the textbook gate, not a
tuned one, and the thesis suite and the clutter family, which the board
publishes, show what it is for but did not choose its value.
"""

from __future__ import annotations

from typing import Annotated

import pydantic
from annotated_types import Ge, Interval

from benchmark.parameters import NonNegative, Positive, Share, require_order


@pydantic.dataclasses.dataclass(frozen=True)
class SegmentationParams:
    """Parameters of the segmentation tracker (seeds/000, section 2.3).

    Each field's type declares its domain; rules tying fields together are in
    :meth:`__post_init__`.  A value outside them is a
    :class:`pydantic.ValidationError`.
    """

    reference_width_px: Positive | None = 320.0
    """Width of the frame, px, for which the lengths of :data:`SCALED_LENGTHS` and the variances of
    :data:`SCALED_VARIANCES` are stated; on a frame ``W`` px wide they are multiplied by ``W / reference_width_px``
    (its square for variances, :func:`trackbench_segmentation.scaling.frame_params`).  320: the frames of Ortiz et
    al. (seeds/000, section 2.3).  None: they are pixels of any frame (the paper variant)."""

    grey_quantiles: tuple[Share, Share] | None = (0.05, 0.95)
    """Quantiles of the smoothed frame's grey levels that are stretched to 0 and 255 before the histograms
    (:func:`trackbench_segmentation.grey.normalised_grey`), so that ``projection_sigma``, ``gradient_bin`` and
    ``min_gradient`` are shares of the frame's own range; bright marine snow and lamp hot spots lie beyond the
    upper one.  None: raw grey levels (the paper variant)."""

    smoothing_sigma: NonNegative = 1.0
    """Gaussian smoothing of the image before the histogram, px; 0: none (not in the thesis).  With ``smooth_share``
    0.7: 1.5 px gave a mean of 79.1 %, 1.0 px 81.6 % (clutter draws 73.0 / 70.6 against 85.5 / 82.3 %); with the
    shipped defaults, 0 gives 78.2 % against 86.3 %."""

    pyramid_levels: Annotated[int, Interval(ge=1, le=4)] = 2
    """Levels of the pyramid of cells: level ``k`` splits the image into ``2^(k-1) x 2^(k-1)`` cells, so the default
    is the whole image and its 2 x 2 quarters (seeds/000, section 2.3: "for instance, 2 x 2").  A third level (4 x 4)
    gave a mean of 81.4 against 79.1 % (smoothing 1.5 px, share 0.7) at half the frame rate (about 120 against
    230 frames/s)."""

    gradient_bin: Positive = 1.0
    """Width of a gradient bin of the joint histogram, grey levels per px (normalised with ``grey_quantiles``)."""

    gradient_bins: Annotated[int, Ge(2)] = 64
    """Number of gradient bins of the joint histogram; larger moduli count in the last."""

    smooth_share: Annotated[pydantic.FiniteFloat, Interval(gt=0, le=1)] = 0.5
    """Share of a cell's pixels below the cut between smooth and contour pixels of its histogram.  With smoothing
    1.5 px: 0.5 / 0.7 / 0.9 gave means of 82.4 / 79.1 / 76.6 %; with 1.0 px, 0.5 gives 86.3 % against 81.6 % for
    0.7 (S1 69.0 against 54.4 %, S5 90.6 against 74.9 %)."""

    projection_sigma: NonNegative = 1.0
    """Gaussian smoothing of the grey-level projection before its valleys are sought, grey levels (normalised
    ones with ``grey_quantiles``; the module's notes give the measurements of 1).  In raw grey levels on the thesis
    suite: 2 / 3 / 5 gave means of 81.1 / 79.1 / 61.1 % (smoothing 1.5 px, share 0.7); 2 with the then shipped
    defaults 86.4 %, no better than 3 but with S7 falling from 59.3 to 42.7 % correct (50.0 % false)."""

    valley_ratio: Share = 1.0
    """A valley splits two mountains while its height is at most this share of the lower neighbouring peak; 1: every
    local minimum of the smoothed projection is a valley.  The cable covers a few per cent of a cell, and its hill
    is a shoulder of the sand's rather than a hill of its own, so only over-segmentation separates it: with 0.7 /
    0.9 / 1.0 (and ``snap_px`` 0), S4 was 0.6 / 36.0 (0.95) / 64.5 % correct and S2 47.9 / 92.6 (0.95) / 88.8 %."""

    reach_px: Annotated[int, Interval(ge=0, le=5)] = 1
    """Columns either side of the predicted position searched for the next contour pixel of a chain."""

    max_gap_rows: Annotated[int, Ge(0)] = 2
    """Rows without a contour pixel a chain may bridge along the predicted direction."""

    snap_px: Annotated[int, Interval(ge=0, le=32)] = 3
    """Contour points move to the strongest gradient within this many columns; 0: they stay (not in the thesis).
    Without it the grey-level cut lies inside soft edges, the width comes out 6-12 px narrow on S5 and S5 is
    41.5 % correct (45.0 % false); 2 / 3 / 4 px gave means of 71.5 / 79.1 / 80.2 % (smoothing 1.5 px, share 0.7),
    and 4 with the shipped defaults 79.1 % against 86.3 %."""

    split_px: Positive = 1.5
    """A chain is cut where a pixel lies farther than this from its piece's chord, px."""

    min_segment_rows: Annotated[int, Ge(2)] = 10
    """Straight segments spanning fewer rows are short and discarded."""

    strip_px: Positive = 2.0
    """Half-width of the strip co-linear segments must fall into to be grouped, px."""

    group_angle_deg: Annotated[float, Interval(ge=0, le=45)] = 3.0
    """Largest angle between two segments of one group, degrees."""

    long_share: Share = 0.4
    """A long segment spans at least this share of its cell's rows (of the image's rows when fusing)."""

    min_gradient: NonNegative = 4.0
    """Smallest mean gradient modulus of a long segment's contour pixels, grey levels per px (normalised with
    ``grey_quantiles``); see also ``min_gradient_ratio``.  With normalised levels 2 and 4 gave the same 78.1 % on
    camera-train, 8 gave 76.7 % (quantiles 0.01 and 0.99, projection smoothing 3, no ``min_gradient_ratio``)."""

    min_gradient_ratio: NonNegative = 3.0
    """Smallest mean gradient modulus of a long segment's contour pixels as a multiple of the frame's gradient level,
    the median modulus (:func:`trackbench_segmentation.detector.edge_gradient`); the larger of this and
    ``min_gradient`` holds.  0: ``min_gradient`` alone (the paper variant)."""

    max_rms_px: Positive = 1.5
    """Largest root mean square distance of a long segment's pixels from its line, px."""

    max_lines: Annotated[int, Ge(2)] = 12
    """Long segments kept per cell (and after fusion), those with the most pixels."""

    max_skew_deg: Annotated[float, Interval(gt=0, lt=45)] = 10.0
    """Largest skew ``|beta|`` of a border pair, degrees (seeds/000, Table 5.2: 0 to 10)."""

    min_width_px: NonNegative = 5.0
    """Smallest plausible cable width, px at ``reference_width_px`` (seeds/000, Table 5.2)."""

    max_width_px: Positive = 160.0
    """Largest plausible cable width, px at ``reference_width_px`` (seeds/000, Table 5.2: 100 px at 320 x 240; half
    the frame width here, see the module's notes)."""

    min_overlap: Share = 0.5
    """Share of the shorter border's rows the other border of a pair must also cover."""

    width_tolerance: Annotated[pydantic.FiniteFloat, Interval(gt=0, le=1)] = 0.3
    """Largest relative difference of a pair's width from the predicted width while tracking."""

    pairs_per_cell: Annotated[int, Ge(1)] = 3
    """Best pairs of each cell whose lines go into the fusion."""

    process_var: tuple[Positive, Positive, Positive] = (25.0, 0.003, 4.0)
    """Variances of the frame-to-frame change of ``(d, alpha, w)``: px^2 at ``reference_width_px``, rad^2, px^2."""

    measurement_var: tuple[Positive, Positive, Positive] = (4.0, 0.0003, 4.0)
    """Variances of a measured ``(d, alpha, w)``: px^2 at ``reference_width_px``, rad^2, px^2."""

    roi_margin_px: NonNegative = 10.0
    """Fixed margin of the region of interest beyond each predicted border, px at ``reference_width_px``."""

    roi_sigmas: NonNegative = 2.0
    """Further margin of the region of interest in standard deviations of a border's predicted position."""

    gate_sigmas: NonNegative = 4.0
    """A pair is taken only when its ``(d, alpha, w)`` lies within this many standard deviations (Mahalanobis
    distance under the predicted covariance plus the measurement noise) of the prediction; the best such pair is
    reported, and a frame without one counts as a miss.  0: the best pair, wherever it lies (the paper)."""

    max_misses: Annotated[int, Ge(1)] = 5
    """Frames in a row without a pair after which the cable is lost and the whole image is searched again."""

    use_init: bool = True
    """Start tracking from ``init`` when the run initialises from truth."""

    def __post_init__(self) -> None:
        """The rule that is not a bound of one field: the plausible widths form a range.

        Raises
        ------
        ValueError
            Naming the parameters and their values.
        """
        require_order(self, ("min_width_px", "max_width_px"))
        if self.grey_quantiles is not None:
            low, high = self.grey_quantiles
            if not low < high:
                raise ValueError(f"grey_quantiles must be (low, high) with low < high, got {self.grey_quantiles}")


SCALED_LENGTHS: tuple[str, ...] = ("min_width_px", "max_width_px", "roi_margin_px")
"""The lengths in px that scale with the frame width: sizes of the cable and of its moves in the image."""

SCALED_VARIANCES: tuple[str, ...] = ("process_var", "measurement_var")
"""The ``(d, alpha, w)`` variances whose ``d`` and ``w`` parts, in px^2, scale with the square of the frame width."""


PAPER: dict[str, object] = {
    "reference_width_px": None,
    "grey_quantiles": None,
    "projection_sigma": 3.0,
    "max_width_px": 100.0,
    "min_gradient_ratio": 0.0,
    "gate_sigmas": 0.0,
}
"""The values chosen for the thesis' 320 x 240 suite, in raw grey levels and fixed pixels: ``segmentation-paper``."""
