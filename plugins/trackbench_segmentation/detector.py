"""One frame of the method of Ortiz et al.: cells, segmentation, contours, lines, pairs, fusion.

The detection process of seeds/000, section 2.3 and Fig. 2.5, in order:

1. divide the image into a pyramid of cells (:func:`cell_pyramid`);
2. in each cell: segment by the grey level x gradient histogram
   (:mod:`trackbench_segmentation.histogram`), follow the segments'
   contours up from the bottom in the predicted direction and cut them into
   straight pieces (:mod:`trackbench_segmentation.contours`), fit segments,
   discard short ones, group co-linear ones in strips and keep the long ones
   that lie on an edge (:mod:`trackbench_segmentation.lines`), and pair
   nearly parallel lines (:mod:`trackbench_segmentation.pairing`);
3. fuse the best pairs of all cells and report the best pair.

:func:`detect_pairs` runs these steps in compiled passes over all cells at
once (:func:`trackbench_segmentation.passes.pyramid_lines`,
:func:`trackbench_segmentation.pairing.cells_pair_lines`,
:func:`trackbench_segmentation.pairing.fuse_pairs`); :func:`cell_lines` states
them one cell and one step at a time, and the passes give its lines and
pairs bit for bit.

While tracking, only the region of interest the Kalman filter predicts is
searched: its pixels alone are counted in the cells' histograms and give
contour pixels, chains follow the predicted orientation, and pairs are
judged against the predicted width.  Without a prediction the whole image is
searched, chains follow the vertical (the camera looks along the cable) and
any width in the plausible range is accepted.

The image is smoothed by a small Gaussian before everything else (not in
the thesis): grey-level cuts through pixel noise otherwise break the
contours into short pieces.  Without it the mean share of correct frames
over camera/S1..S7 and two clutter draws falls from 86.3 to 78.2 % (S4 95.3
to 76.2 %, S6 94.6 to 75.2 %; ``smoothing_sigma`` in
:class:`trackbench_segmentation.params.SegmentationParams`).

Three things make the search independent of the frame's contrast and size
(not in the thesis; the numbers are in :mod:`trackbench_segmentation.params`):
the smoothed grey levels are stretched between two quantiles of the frame
(:mod:`trackbench_segmentation.grey`); a long line must be steeper than a
multiple of the frame's median gradient (:func:`edge_gradient`); and the
lengths that describe the cable, its plausible widths and the region of
interest's margin, follow the frame width (:mod:`trackbench_segmentation.scaling`).
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np

from trackbench_segmentation.contours import follow_chains, label_changes, snap_to_edges, split_chains
from trackbench_segmentation.grey import normalised_grey
from trackbench_segmentation.histogram import frame_gradients, gradient_level, mountain_starts
from trackbench_segmentation.lines import Segments, group_collinear, select_long
from trackbench_segmentation.pairing import BorderPair, PairRules, border_pairs, cells_pair_lines, fuse_pairs, pair_lines
from trackbench_segmentation.params import SegmentationParams
from trackbench_segmentation.passes import CellTable, cell_table, pyramid_lines
from trackbench_segmentation.scaling import frame_params

Cell = tuple[slice, slice]
"""Rows and columns of one cell."""


@functools.lru_cache(maxsize=16)
def cell_pyramid(size: tuple[int, int], levels: int) -> tuple[Cell, ...]:
    """The cells of a pyramid over an image, coarsest first.

    Parameters
    ----------
    size : tuple of int
        Image ``(W, H)``.
    levels : int
        Level ``k`` (from 1) splits the image into ``2^(k-1) x 2^(k-1)``
        cells of nearly equal size.

    Returns
    -------
    tuple of (slice, slice)
        Row and column slices; level by level, each level row by row.

    References
    ----------
    seeds/000, section 2.3: "the division of the input image into a pyramid
    of cells (for instance, 2 x 2)".
    """
    width, height = size
    cells: list[Cell] = []
    for level in range(levels):
        parts = 2**level
        row_edges = np.linspace(0, height, parts + 1).round().astype(int)
        col_edges = np.linspace(0, width, parts + 1).round().astype(int)
        for r in range(parts):
            for c in range(parts):
                cells.append((slice(row_edges[r], row_edges[r + 1]), slice(col_edges[c], col_edges[c + 1])))
    return tuple(cells)


@functools.lru_cache(maxsize=16)
def pyramid_table(size: tuple[int, int], levels: int) -> CellTable:
    """The cells of :func:`cell_pyramid` as the compiled passes take them (:func:`trackbench_segmentation.passes.cell_table`)."""
    return cell_table(cell_pyramid(size, levels), 4 ** (levels - 1), size)


@dataclass(frozen=True, slots=True)
class Prediction:
    """What the tracking filter tells the detector about the next frame.

    Attributes
    ----------
    roi : numpy.ndarray
        Boolean ``(H, W)`` region of interest.
    alpha : float
        Predicted cable orientation, rad: the direction chains follow.
    width : float
        Predicted cable width, px: the expected width of a pair.
    """

    roi: np.ndarray
    alpha: float
    width: float


@functools.lru_cache(maxsize=32)
def pair_rules(params: SegmentationParams) -> PairRules:
    """The pairing limits of a parameter set."""
    return PairRules(
        max_skew=math.radians(params.max_skew_deg),
        min_width=params.min_width_px,
        max_width=params.max_width_px,
        min_overlap=params.min_overlap,
        width_tolerance=params.width_tolerance,
    )


def edge_gradient(modulus: np.ndarray, params: SegmentationParams) -> float:
    """The smallest mean gradient modulus of a long line on a frame, grey levels per px.

    ``min_gradient``, or ``min_gradient_ratio`` times the frame's gradient
    level (:func:`trackbench_segmentation.histogram.gradient_level`) when
    that is larger: a line must stand out of the frame's own ground and
    noise, whatever the contrast the normalisation stretched them to.

    References
    ----------
    seeds/000, section 2.3: long lines are filtered by "the average of the
    gradient modulus of the contour pixels", rejecting "lines that do not
    lie on or near an edge".
    """
    return level_gradient(gradient_level(modulus), params)


def level_gradient(level: float, params: SegmentationParams) -> float:
    """:func:`edge_gradient` of a frame whose gradient level is ``level``."""
    if params.min_gradient_ratio == 0:
        return params.min_gradient
    return max(params.min_gradient, params.min_gradient_ratio * level)


def cell_lines(
    grey: np.ndarray,
    modulus: np.ndarray,
    gradient_rows: np.ndarray,
    cell: Cell,
    params: SegmentationParams,
    prediction: Prediction | None,
    min_gradient: float,
) -> Segments:
    """The lines of the most likely border pairs of one cell: :func:`cell_long_lines`, paired.

    Parameters and result as :func:`cell_long_lines`, whose lines are
    paired (:func:`best_pair_lines`).  :func:`detect_pairs` finds the long
    lines of all cells at once (:func:`trackbench_segmentation.passes.pyramid_lines`).
    """
    height, width = grey.shape
    lines = cell_long_lines(grey, modulus, gradient_rows, cell, params, prediction, min_gradient)
    return best_pair_lines(lines, (width, height), params, prediction)


def best_pair_lines(lines: Segments, size: tuple[int, int], params: SegmentationParams,
                    prediction: Prediction | None) -> Segments:
    """The lines that take part in a cell's ``pairs_per_cell`` best pairs (seeds/000, section 2.3)."""
    expected = None if prediction is None else prediction.width
    pairs = border_pairs(lines, size, pair_rules(params), expected)[: params.pairs_per_cell]
    return pair_lines(lines, pairs)


def cell_long_lines(
    grey: np.ndarray,
    modulus: np.ndarray,
    gradient_rows: np.ndarray,
    cell: Cell,
    params: SegmentationParams,
    prediction: Prediction | None,
    min_gradient: float,
) -> Segments:
    """The long lines of one cell, the candidates of its border pairs.

    Parameters
    ----------
    grey : numpy.ndarray
        The smoothed ``uint8`` image, ``(H, W)``.
    modulus : numpy.ndarray
        Its gradient modulus (:func:`trackbench_segmentation.histogram.gradient_modulus`).
    gradient_rows : numpy.ndarray
        The modulus' rows of the joint histogram
        (:func:`trackbench_segmentation.histogram.gradient_bins`).
    cell : (slice, slice)
        The cell's rows and columns.
    params : SegmentationParams
        The tracker's parameters.
    prediction : Prediction, optional
        The filter's prediction while tracking.
    min_gradient : float
        Smallest mean gradient modulus of a long line (:func:`edge_gradient`).

    Returns
    -------
    Segments
        The cell's long lines (:func:`trackbench_segmentation.lines.select_long`),
        most pixels first, in image coordinates.

    References
    ----------
    seeds/000, section 2.3 and Fig. 2.5.
    """
    p = params
    rows, cols = cell
    height, width = grey.shape
    cell_modulus = modulus[rows, cols]
    cell_grey = grey[rows, cols]
    # One mask serves the histogram and the contours: every pixel, or the region of interest's.
    if prediction is None:
        mask = np.ones(cell_grey.shape, np.bool_)
    else:
        mask = np.ascontiguousarray(prediction.roi[rows, cols], dtype=np.bool_)
    levels = mountain_starts(
        cell_grey,
        cell_modulus,
        gradient_rows[rows, cols],
        smooth_share=p.smooth_share,
        bin_width=p.gradient_bin,
        n_bins=p.gradient_bins,
        sigma=p.projection_sigma,
        valley_ratio=p.valley_ratio,
        mask=mask,
    )
    if levels is None:
        return Segments.empty()
    contours = label_changes(cell_grey, levels, mask)
    alpha = 0.0 if prediction is None else prediction.alpha
    chain_rows, chain_cols, starts = follow_chains(
        contours, alpha, reach=p.reach_px, max_gap=p.max_gap_rows, min_rows=p.min_segment_rows
    )
    pieces = split_chains(chain_rows, chain_cols, starts, p.split_px)
    offset = (rows.start or 0, cols.start or 0)
    columns = snap_to_edges(chain_rows, chain_cols, cell_modulus, p.snap_px)
    segments = Segments.from_pieces(chain_rows, columns, pieces, cell_modulus, offset)
    segments = segments.longer_than(p.min_segment_rows)
    grouped = group_collinear(segments, p.strip_px, math.radians(p.group_angle_deg))
    cell_height = (rows.stop if rows.stop is not None else height) - offset[0]
    return select_long(
        grouped,
        min_rows=p.long_share * cell_height,
        min_gradient=min_gradient,
        max_rms=p.max_rms_px,
        max_count=p.max_lines,
    )


def detect(image: np.ndarray, params: SegmentationParams, prediction: Prediction | None = None) -> BorderPair | None:
    """The best pair of cable borders in one grey image: the first of :func:`detect_pairs`, or None."""
    pairs = detect_pairs(image, params, prediction)
    return pairs[0] if pairs else None


def detect_pairs(image: np.ndarray, params: SegmentationParams, prediction: Prediction | None = None) -> list[BorderPair]:
    """The plausible pairs of cable borders in one grey image, best first.

    Parameters
    ----------
    image : numpy.ndarray
        ``uint8`` grey image of shape ``(H, W)``.
    params : SegmentationParams
        The tracker's parameters.
    prediction : Prediction, optional
        The tracking filter's prediction; None searches the whole image.

    Returns
    -------
    list of BorderPair
        The pairs after the fusion of all cells' pairs, highest score
        first; empty when no plausible pair is found.

    References
    ----------
    seeds/000, section 2.3 and Fig. 2.5.
    """
    height, width = image.shape
    p = frame_params(params, (width, height))
    grey = normalised_grey(image, p.smoothing_sigma, p.grey_quantiles)
    modulus, gradient_rows, level = frame_gradients(grey, p.gradient_bin, p.gradient_bins)
    min_gradient = level_gradient(level, p)
    table = pyramid_table((width, height), p.pyramid_levels)
    mask, alpha = (None, 0.0) if prediction is None else (prediction.roi, prediction.alpha)
    long_lines, offsets = pyramid_lines(grey, modulus, gradient_rows, table, p, mask, alpha, min_gradient)
    expected = None if prediction is None else prediction.width
    found = cells_pair_lines(long_lines, offsets, (width, height), pair_rules(p), expected, p.pairs_per_cell)
    return fuse_pairs(
        found,
        (width, height),
        pair_rules(p),
        strip_px=p.strip_px,
        max_angle=math.radians(p.group_angle_deg),
        min_rows=p.long_share * height,
        min_gradient=min_gradient,
        max_rms=p.max_rms_px,
        max_lines=p.max_lines,
        expected_width=None if prediction is None else prediction.width,
    )


def compile_kernels() -> None:
    """Compile (or load from numba's cache) the compiled passes of :func:`detect_pairs` now, on a tiny image.

    Searched whole and in a region of interest, with and without a power of
    two for the gradient bins, so that every pass a frame may take is ready.
    """
    image = np.zeros((24, 32), np.uint8)
    image[:, 12:18] = 200
    mask = np.zeros(image.shape, np.bool_)
    mask[:, 4:28] = True
    for params in (SegmentationParams(), SegmentationParams(gradient_bin=1.5)):
        for prediction in (None, Prediction(mask, 0.0, 6.0)):
            detect_pairs(image, params, prediction)
