"""One frame's cells in two compiled passes: the lines of :func:`~trackbench_segmentation.detector.cell_long_lines`, bit for bit.

:func:`trackbench_segmentation.detector.cell_long_lines` states the method
of Ortiz et al. (seeds/000, section 2.3, Fig. 2.4-2.5) one cell and one step
at a time; run so, a frame spends most of its time between the steps, in
Python.  :func:`pyramid_lines` does the same arithmetic on all the cells of
a frame in two compiled passes:

1. :func:`_projections` counts the joint histograms of the finest cells only
   (a coarser cell is the union of finer ones, so its histogram is their
   sum; :func:`cell_table`), and only within each row's extent of the
   region of interest (:func:`row_extents`), finds each cell's contour cut
   from its rows' totals and projects the smooth rows on the grey axis,
   each projection padded for the smoothing;
2. the projections are smoothed by one ``numpy.convolve`` over all of them
   side by side: each smoothed value is the same dot product of the same
   numbers as a cell's own ``numpy.convolve`` takes
   (:func:`trackbench_segmentation.histogram.mountains`);
3. :func:`_cell_lines` finds, cell after cell, the valleys, the label
   changes and the chains with the kernels of
   :mod:`trackbench_segmentation.histogram` and
   :mod:`trackbench_segmentation.contours`, cuts the chains into straight
   pieces, drops the short pieces before their points are snapped
   (:func:`trackbench_segmentation.contours.snap_to_edges`) and summed (:func:`piece_sums`), and groups
   (:func:`trackbench_segmentation.lines.group_collinear`'s kernel) and filters the segments
   (:func:`group_and_select`).

Every number is computed with the same operations in the same order as the
one-cell form, so the lines are the same to the last bit: the segments'
sums (``numpy.add.reduceat``) by numpy's pairwise summation
(:func:`_pairwise_sum`), stable sorts where numpy sorts stably.  A cell whose
cut the rows' totals do not settle (:func:`trackbench_segmentation.histogram.counted_cut`
needs the moduli themselves) has its mountains found by
:func:`trackbench_segmentation.histogram.mountain_starts`, and the second
pass takes them as they are.  Each compiled step has a property test of
equality with its first form (tests/plugins/segmentation/test_segmentation_passes.py).
"""

from __future__ import annotations

import functools
import math

import numba
import numpy as np

from trackbench_segmentation.contours import _follow, _snap, _split, label_changes
from trackbench_segmentation.histogram import GREY_LEVELS, _is_power_of_two, _smoothing_kernel, _valleys, mountain_starts
from trackbench_segmentation.lines import Segments, _fit, _group, _is_long, _join
from trackbench_segmentation.params import SegmentationParams

EMPTY, READY, GIVEN = 0, 1, 2
"""A cell's state after the first pass: no pixel counted, its projection ready, its mountains found outside."""


CellTable = tuple[np.ndarray, np.ndarray]
"""A pyramid's cells as :func:`cell_table` gives them."""


def cell_table(cells: tuple[tuple[slice, slice], ...], finest: int, size: tuple[int, int]) -> CellTable:
    """The cells as ``(top, bottom, left, right)`` rows, and for each the finest cells it is the union of.

    Parameters
    ----------
    cells : tuple of (slice, slice)
        A pyramid of cells (:func:`trackbench_segmentation.detector.cell_pyramid`).
    finest : int
        How many of the last cells make the finest level.
    size : tuple of int
        Image ``(W, H)``.

    Returns
    -------
    bounds : numpy.ndarray
        ``int64`` array of shape ``(n, 4)``.
    parts : numpy.ndarray
        ``int64`` array of shape ``(n, m)``: ``parts[k, j]`` is 1 when the
        ``j``-th of the ``m`` cells of the finest level lies in cell ``k``.
        When the finest cells do not tile every cell exactly, every cell is
        its own only part (and counted on its own).
    """
    width, height = size
    bounds = np.array(
        [[r.start or 0, height if r.stop is None else r.stop, c.start or 0, width if c.stop is None else c.stop]
         for r, c in cells],
        dtype=np.int64,
    ).reshape(-1, 4)
    first_fine = len(cells) - finest
    fine = bounds[first_fine:]
    inside = (
        (fine[None, :, 0] >= bounds[:, None, 0])
        & (fine[None, :, 1] <= bounds[:, None, 1])
        & (fine[None, :, 2] >= bounds[:, None, 2])
        & (fine[None, :, 3] <= bounds[:, None, 3])
    )
    areas = (bounds[:, 1] - bounds[:, 0]) * (bounds[:, 3] - bounds[:, 2])
    fine_areas = areas[first_fine:]
    tiled = np.array_equal(inside @ fine_areas, areas) and np.all(inside.sum(axis=0)[None, :] >= 1)
    parts = inside.astype(np.int64) if tiled else np.eye(len(cells), dtype=np.int64)
    bounds.flags.writeable = parts.flags.writeable = False
    return bounds, parts


@numba.njit(cache=True, nogil=True)
def row_extents(mask: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """For each row of a boolean ``mask``, the columns ``[first, stop)`` from its first to its last True (``0, 0``: none)."""
    height, width = mask.shape
    first = np.zeros(height, dtype=np.int64)
    stop = np.zeros(height, dtype=np.int64)
    for r in range(height):
        lo = 0
        while lo < width and not mask[r, lo]:
            lo += 1
        if lo == width:
            continue
        hi = width
        while not mask[r, hi - 1]:
            hi -= 1
        first[r] = lo
        stop[r] = hi
    return first, stop


@numba.njit(cache=True, nogil=True)
def _projections(
    grey: np.ndarray,
    rows: np.ndarray,
    mask: np.ndarray,
    first: np.ndarray,
    stop: np.ndarray,
    bounds: np.ndarray,
    parts: np.ndarray,
    n_bins: int,
    smooth_share: float,
    exact_rows: bool,
    radius: int,
) -> tuple[np.ndarray, np.ndarray]:
    """Each cell's state (:data:`EMPTY`, :data:`READY`, :data:`GIVEN`) and padded projection.

    The projection of cell ``k`` is ``padded[k*(256 + 2 radius) : (k+1)*(256 + 2 radius)]``: its first and last
    value repeated ``radius`` times on either side, as :func:`trackbench_segmentation.histogram.mountains` pads.
    """
    n_cells = bounds.shape[0]
    n_parts = parts.shape[1]
    first_part = n_cells - n_parts
    histograms = np.zeros((n_parts, n_bins, GREY_LEVELS), dtype=np.int64)
    part_totals = np.zeros((n_parts, n_bins), dtype=np.int64)
    for j in range(n_parts):
        top, bottom, left, right = bounds[first_part + j]
        for r in range(top, bottom):
            for c in range(max(left, first[r]), min(right, stop[r])):
                if mask[r, c]:
                    histograms[j, rows[r, c], grey[r, c]] += 1
                    part_totals[j, rows[r, c]] += 1
    state = np.zeros(n_cells, dtype=np.int64)
    totals = np.zeros((n_cells, n_bins), dtype=np.int64)
    stride = GREY_LEVELS + 2 * radius
    padded = np.zeros(n_cells * stride)
    for k in range(n_cells):
        last = -1
        for b in range(n_bins):
            for j in range(n_parts):
                if parts[k, j]:
                    totals[k, b] += part_totals[j, b]
            last += totals[k, b]
        if last < 0:
            continue
        # histogram.counted_cut: the rows of two order statistics about the quantile, from the rows' totals.
        middle = int(smooth_share * last)
        low_rank, high_rank = max(middle - 1, 0), min(middle + 2, last)
        low_row = _row_of_rank(totals[k], low_rank)
        high_row = _row_of_rank(totals[k], high_rank)
        if low_row != high_row or not exact_rows:
            state[k] = GIVEN
            continue
        state[k] = READY
        cut = low_row + 1
        projection = np.zeros(GREY_LEVELS, dtype=np.int64)
        for j in range(n_parts):
            if parts[k, j]:
                for b in range(min(cut, n_bins)):
                    for i in range(GREY_LEVELS):
                        projection[i] += histograms[j, b, i]
        start = k * stride
        for i in range(radius):
            padded[start + i] = projection[0]
            padded[start + radius + GREY_LEVELS + i] = projection[GREY_LEVELS - 1]
        for i in range(GREY_LEVELS):
            padded[start + radius + i] = projection[i]
    return state, padded


@numba.njit(cache=True, nogil=True)
def _row_of_rank(totals: np.ndarray, rank: int) -> int:
    """``numpy.searchsorted(numpy.cumsum(totals), rank, side="right")``: the row holding the ``rank``-th smallest."""
    row = 0
    below = 0
    while row < totals.shape[0] and below + totals[row] <= rank:
        below += totals[row]
        row += 1
    return row


@numba.njit(cache=True, nogil=True)
def _pairwise_sum(values: np.ndarray, first: int, count: int) -> float:
    """numpy's pairwise sum of ``values[first : first + count]`` (the inner loop of ``numpy.add.reduce``)."""
    if count < 8:
        total = -0.0
        for i in range(count):
            total += values[first + i]
        return total
    if count <= 128:
        r0, r1, r2, r3 = values[first], values[first + 1], values[first + 2], values[first + 3]
        r4, r5, r6, r7 = values[first + 4], values[first + 5], values[first + 6], values[first + 7]
        i = 8
        while i < count - count % 8:
            at = first + i
            r0 += values[at]
            r1 += values[at + 1]
            r2 += values[at + 2]
            r3 += values[at + 3]
            r4 += values[at + 4]
            r5 += values[at + 5]
            r6 += values[at + 6]
            r7 += values[at + 7]
            i += 8
        total = ((r0 + r1) + (r2 + r3)) + ((r4 + r5) + (r6 + r7))
        while i < count:
            total += values[first + i]
            i += 1
        return total
    half = count // 2
    half -= half % 8
    return _pairwise_sum(values, first, half) + _pairwise_sum(values, first + half, count - half)


@numba.njit(cache=True, nogil=True)
def piece_sums(values: np.ndarray, pieces: np.ndarray) -> np.ndarray:
    """``numpy.add.reduceat(values, pieces[:, 0])`` for contiguous ordered ``[first, stop)`` pieces covering ``values``."""
    sums = np.empty(pieces.shape[0])
    for k in range(pieces.shape[0]):
        first, stop = pieces[k, 0], pieces[k, 1]
        sums[k] = values[first] + _pairwise_sum(values, first + 1, stop - first - 1) if stop - first > 1 else values[first]
    return sums


@numba.njit(cache=True, nogil=True)
def _segments_of(
    rows: np.ndarray, columns: np.ndarray, pieces: np.ndarray, gradient: np.ndarray, top: int, left: int
) -> np.ndarray:
    """:meth:`trackbench_segmentation.lines.Segments.from_pieces` as a ``(9, n)`` array, the fields in order."""
    n_pieces = pieces.shape[0]
    fields = np.empty((9, n_pieces))
    if n_pieces == 0:
        return fields
    width = gradient.shape[1]
    count = rows.shape[0]
    v = np.empty(count)
    u = np.empty(count)
    g = np.empty(count)
    for i in range(count):
        nearest = min(max(np.int64(np.rint(columns[i])), 0), width - 1)
        g[i] = np.float64(gradient[rows[i], nearest])
        v[i] = np.float64(rows[i]) + top
        u[i] = columns[i] + np.float64(left)
    # Row by row, element by element: an array assigned to a row would compile numpy's shape checks.
    sums = (piece_sums(v, pieces), piece_sums(u, pieces), piece_sums(v * v, pieces), piece_sums(u * v, pieces),
            piece_sums(u * u, pieces), piece_sums(g, pieces))
    for k in range(n_pieces):
        fields[0, k] = np.float64(pieces[k, 1] - pieces[k, 0])
        for f in range(6):
            fields[f + 1, k] = sums[f][k]
        fields[7, k] = v[pieces[k, 1] - 1]
        fields[8, k] = v[pieces[k, 0]]
    return fields


@numba.njit(cache=True, nogil=True)
def take_segments(fields: np.ndarray, index: np.ndarray) -> np.ndarray:
    """The segments at ``index`` of a ``(9, n)`` array of segments."""
    taken = np.empty((9, index.shape[0]))
    for k in range(index.shape[0]):
        for f in range(9):
            taken[f, k] = fields[f, index[k]]
    return taken


@numba.njit(cache=True, nogil=True)
def group_and_select(
    s: np.ndarray,
    min_segment_rows: float,
    strip: float,
    max_angle: float,
    min_rows: float,
    min_gradient: float,
    max_rms: float,
    max_count: int,
) -> np.ndarray:
    """``select_long(group_collinear(segments.longer_than(min_segment_rows)))`` on a ``(9, n)`` array of segments.

    The steps of :func:`trackbench_segmentation.lines.group_collinear` and
    :func:`trackbench_segmentation.lines.select_long`, with the same kernels
    and the same stable sorts.
    """
    s = take_segments(s, np.flatnonzero(s[8] - s[7] + 1.0 >= min_segment_rows))
    if s.shape[1] == 0:
        return s
    order = np.argsort(-s[0], kind="mergesort")
    labels = _group(s[0], s[1], s[2], s[3], s[4], s[5], s[7], s[8], order, strip, max_angle)
    n_groups = np.int64(0)
    for label in labels:
        n_groups = max(n_groups, label + 1)
    joined = _join(labels, n_groups, s[0], s[1], s[2], s[3], s[4], s[5], s[6], s[7], s[8])
    grouped = np.empty((9, joined[0].shape[0]))
    for f in range(9):
        for k in range(grouped.shape[1]):
            grouped[f, k] = joined[f][k]
    grouped = take_segments(grouped, np.argsort(-grouped[0], kind="mergesort"))
    g = grouped
    keep = np.flatnonzero(_is_long(g[0], g[1], g[2], g[3], g[4], g[5], g[6], g[7], g[8], min_rows, min_gradient, max_rms))
    ranked = keep[np.argsort(-g[0][keep], kind="mergesort")[:max_count]]
    return take_segments(g, ranked)


@numba.njit(cache=True, nogil=True)
def _long_pieces(
    rows: np.ndarray, cols: np.ndarray, pieces: np.ndarray, min_rows: int
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The points of the pieces spanning at least ``min_rows`` rows, side by side, and those pieces' ranges into them.

    A piece climbs one row at a time from its first point, so its span is the
    rows between its first and last point; the pieces keep their order.
    """
    keep = np.empty(pieces.shape[0], dtype=np.bool_)
    total = 0
    for k in range(pieces.shape[0]):
        keep[k] = rows[pieces[k, 0]] - rows[pieces[k, 1] - 1] + 1 >= min_rows
        if keep[k]:
            total += pieces[k, 1] - pieces[k, 0]
    kept_rows = np.empty(total, dtype=np.int64)
    kept_cols = np.empty(total, dtype=np.int64)
    n_long = 0
    for k in range(pieces.shape[0]):
        n_long += keep[k]
    kept = np.empty((n_long, 2), dtype=np.int64)
    count = 0
    n_kept = 0
    for k in range(pieces.shape[0]):
        if keep[k]:
            kept[n_kept, 0] = count
            for i in range(pieces[k, 0], pieces[k, 1]):
                kept_rows[count] = rows[i]
                kept_cols[count] = cols[i]
                count += 1
            kept[n_kept, 1] = count
            n_kept += 1
    return kept_rows, kept_cols, kept


@numba.njit(cache=True, nogil=True)
def _cell_lines(
    grey: np.ndarray,
    modulus: np.ndarray,
    mask: np.ndarray,
    bounds: np.ndarray,
    state: np.ndarray,
    smoothed: np.ndarray,
    stride: int,
    given: np.ndarray,
    given_starts: np.ndarray,
    valley_ratio: float,
    slope: float,
    reach: int,
    max_gap: int,
    min_segment_rows: int,
    split_px: float,
    snap_px: int,
    strip: float,
    max_angle: float,
    min_rows: np.ndarray,
    min_gradient: float,
    max_rms: float,
    max_count: int,
) -> tuple[np.ndarray, np.ndarray]:
    """The second pass: each cell's long lines (:func:`trackbench_segmentation.detector.cell_lines` before pairing).

    Returns the lines of all cells side by side as a ``(9, n)`` array, the fields of
    :class:`~trackbench_segmentation.lines.Segments` in order, and the offsets
    of each cell's lines into it, the total appended.
    """
    n_cells = bounds.shape[0]
    found = []
    offsets = np.zeros(n_cells + 1, dtype=np.int64)
    for k in range(n_cells):
        top, bottom, left, right = bounds[k]
        lines = np.empty((9, 0))
        if state[k] != EMPTY:
            if state[k] == READY:
                levels = _valleys(smoothed[k * stride : k * stride + GREY_LEVELS].copy(), valley_ratio)
            else:
                levels = given[given_starts[k] : given_starts[k + 1]].copy()
            cell_grey = grey[top:bottom, left:right]
            cell_modulus = modulus[top:bottom, left:right]
            contours = label_changes(cell_grey, levels, mask[top:bottom, left:right])
            chain_rows, chain_cols, starts = _follow(contours, slope, reach, max_gap, min_segment_rows)
            # Short pieces are discarded before the grouping: their points are neither snapped nor summed.
            point_rows, point_cols, pieces = _long_pieces(
                chain_rows, chain_cols, _split(chain_rows, chain_cols, starts, split_px), min_segment_rows
            )
            if snap_px <= 0 or point_cols.shape[0] == 0:
                columns = point_cols.astype(np.float64) + 0.5
            else:
                columns = _snap(point_rows, point_cols, cell_modulus, snap_px)
            segments = _segments_of(point_rows, columns, pieces, cell_modulus, top, left)
            lines = group_and_select(
                segments, np.float64(min_segment_rows), strip, max_angle, min_rows[k], min_gradient, max_rms, max_count
            )
        found.append(lines)
        offsets[k + 1] = offsets[k] + lines.shape[1]
    joined = np.empty((9, offsets[n_cells]))
    for k in range(n_cells):
        for f in range(9):
            for i in range(found[k].shape[1]):
                joined[f, offsets[k] + i] = found[k][f, i]
    return joined, offsets


@functools.lru_cache(maxsize=8)
def _everywhere(shape: tuple[int, int]) -> np.ndarray:
    """A read-only mask of every pixel."""
    mask = np.ones(shape, dtype=np.bool_)
    mask.flags.writeable = False
    return mask


def _read_only(array: np.ndarray) -> np.ndarray:
    """A read-only view of ``array``."""
    view = array.view()
    view.flags.writeable = False
    return view


@functools.lru_cache(maxsize=8)
def _full_rows(shape: tuple[int, int]) -> tuple[np.ndarray, np.ndarray]:
    """The :func:`row_extents` of a mask of every pixel (read-only)."""
    height, width = shape
    first, stop = np.zeros(height, dtype=np.int64), np.full(height, width, dtype=np.int64)
    first.flags.writeable = stop.flags.writeable = False
    return first, stop


def pyramid_lines(
    grey: np.ndarray,
    modulus: np.ndarray,
    gradient_rows: np.ndarray,
    table: CellTable,
    params: SegmentationParams,
    mask: np.ndarray | None,
    alpha: float,
    min_gradient: float,
) -> tuple[np.ndarray, np.ndarray]:
    """The long lines of every cell, before pairing: :func:`trackbench_segmentation.detector.cell_long_lines`', bit for bit.

    Parameters
    ----------
    grey, modulus, gradient_rows : numpy.ndarray
        The frame's normalised grey levels, gradient moduli and their
        gradient rows, ``(H, W)``.
    table : CellTable
        The pyramid's cells (:func:`cell_table`).
    params : SegmentationParams
        In pixels of the frame (:func:`trackbench_segmentation.scaling.frame_params`).
    mask : numpy.ndarray or None
        Boolean ``(H, W)`` region of interest; None: every pixel.
    alpha : float
        The orientation chains follow, rad, ``|alpha| < pi/2``.
    min_gradient : float
        Smallest mean gradient modulus of a long line.

    Returns
    -------
    lines : numpy.ndarray
        ``(9, n)``: the fields of :class:`~trackbench_segmentation.lines.Segments`
        in order, the long lines of each cell (``select_long``, most pixels
        first), cell after cell.
    offsets : numpy.ndarray
        Cell ``k``'s lines are ``lines[:, offsets[k] : offsets[k + 1]]``.

    References
    ----------
    seeds/000, section 2.3 and Fig. 2.4-2.5.
    """
    p = params
    if not -np.pi / 2 < alpha < np.pi / 2:
        raise ValueError(f"the walk climbs rows and needs |alpha| < 90 deg, got {np.degrees(alpha):.1f} deg")
    if p.split_px <= 0:
        raise ValueError(f"the split tolerance must be positive, got {p.split_px}")
    height, width = grey.shape
    bounds, parts = table
    # The mask and its rows' extents are read-only whether searched whole or not: one compiled form of each pass.
    counted = _everywhere((height, width)) if mask is None else _read_only(np.ascontiguousarray(mask, dtype=np.bool_))
    radius = len(_smoothing_kernel(p.projection_sigma)) // 2 if p.projection_sigma > 0 else 0
    first, stop = _full_rows((height, width)) if mask is None else map(_read_only, row_extents(counted))
    state, padded = _projections(
        grey, gradient_rows, counted, first, stop, bounds, parts, p.gradient_bins, p.smooth_share,
        _is_power_of_two(p.gradient_bin), radius,
    )
    # One convolution over the cells' padded projections side by side: cell k's smoothed values start at k * stride.
    smoothed = np.convolve(padded, _smoothing_kernel(p.projection_sigma), mode="valid") if radius else padded
    given_starts = np.zeros(len(bounds) + 1, dtype=np.int64)
    given = [np.zeros(0, np.int64)] * len(bounds)
    for k in np.flatnonzero(state == GIVEN):
        top, bottom, left, right = bounds[k]
        cell = np.s_[top:bottom, left:right]
        given[k] = mountain_starts(
            grey[cell], modulus[cell], gradient_rows[cell], smooth_share=p.smooth_share, bin_width=p.gradient_bin,
            n_bins=p.gradient_bins, sigma=p.projection_sigma, valley_ratio=p.valley_ratio, mask=counted[cell],
        )
    np.cumsum([len(levels) for levels in given], out=given_starts[1:])
    lines, offsets = _cell_lines(
        grey, modulus, counted, bounds, state, smoothed, GREY_LEVELS + 2 * radius,
        np.concatenate(given).astype(np.int64), given_starts, float(p.valley_ratio),
        -float(np.tan(alpha)), p.reach_px, p.max_gap_rows, p.min_segment_rows, float(p.split_px), p.snap_px,
        float(p.strip_px), math.radians(p.group_angle_deg), _long_rows(p.long_share, bounds), float(min_gradient),
        float(p.max_rms_px), p.max_lines,
    )
    return lines, offsets


def _long_rows(long_share: float, bounds: np.ndarray) -> np.ndarray:
    """Per cell, the smallest row span of a long line: ``long_share`` of the cell's rows."""
    return long_share * (bounds[:, 1] - bounds[:, 0])
