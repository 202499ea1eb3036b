"""Pairs of nearly parallel lines as cable borders, and the fusion of the cells' best pairs.

"The expected width of the cable is afterwards used to find (nearly)
parallel line pairs that are likely to be the cable borders regarding their
degree of parallelism and their length.  The most likely line pairs of each
cell of the image are fused re-executing the line segment grouping,
filtering and selection as previously described.  The output of the system
contains the pair of lines which has the highest score after the fusion"
(seeds/000, section 2.3, Fig. 2.5).  The readings made here:

* two long lines may be a pair when the skew ``beta`` of the cable state
  they define (half the angle between them, conventions.md section 1) is
  at most ``max_skew``, its width ``w`` lies in ``[min_width, max_width]``,
  and they face each other over at least ``min_overlap`` of the shorter
  one's rows (two borders of one cable are seen over the same rows);
* the expected width is the tracking filter's predicted width; a pair's
  width may differ from it by at most ``width_tolerance`` times it.  Without
  a prediction (the first frame, or after a loss) only the range applies;
* the score is the length, the number of contour pixels of both lines,
  times the parallelism ``1 - |beta| / max_skew``, times the width's
  agreement ``1 - |w - w_expected| / (width_tolerance w_expected)`` when a
  width is expected (:func:`border_pairs`);
* the "most likely pairs" of a cell are its ``pairs_per_cell`` best, and
  fusing re-runs :func:`trackbench_segmentation.lines.group_collinear`,
  :func:`trackbench_segmentation.lines.select_long` and :func:`border_pairs`
  on the lines of all cells' pairs together (:func:`fuse`).
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numba
import numpy as np

from benchmark.modalities.camera.geometry import ImageSize, Line, cable_from_borders
from benchmark.modalities.camera.geometry_kernels import cable_of_borders, python_hypot
from benchmark.modalities.camera.model import CableState
from trackbench_segmentation.lines import Segments, group_collinear, pixel_line, select_long
from trackbench_segmentation.lines import _NAMES as _FIELDS
from trackbench_segmentation.passes import group_and_select, take_segments


@dataclass(frozen=True, slots=True)
class PairRules:
    """What makes two lines a plausible pair of cable borders.

    Attributes
    ----------
    max_skew : float
        Largest ``|beta|``, rad.
    min_width, max_width : float
        Range of plausible widths, px.
    min_overlap : float
        Smallest share of the shorter line's rows the other line also covers.
    width_tolerance : float
        Largest relative difference from an expected width.
    """

    max_skew: float
    min_width: float
    max_width: float
    min_overlap: float
    width_tolerance: float


@dataclass(frozen=True, slots=True)
class BorderPair:
    """Two lines taken as the cable borders.

    Attributes
    ----------
    first, second : int
        Indices of the two lines in the :class:`Segments` they were paired from.
    borders : tuple of Line
        The two lines in model coordinates.
    state : CableState
        The cable state they define (:func:`benchmark.modalities.camera.geometry.cable_from_borders`).
    score : float
        Length x parallelism x width agreement.
    """

    first: int
    second: int
    borders: tuple[Line, Line]
    state: CableState
    score: float


def border_pairs(
    lines: Segments, size: ImageSize, rules: PairRules, expected_width: float | None = None
) -> list[BorderPair]:
    """All plausible border pairs among long lines, best first.

    Parameters
    ----------
    lines : Segments
        Long lines (:func:`trackbench_segmentation.lines.select_long`).
    size : tuple of int
        Image ``(W, H)``.
    rules : PairRules
        Parallelism, width and overlap limits.
    expected_width : float, optional
        The predicted cable width, px.

    Returns
    -------
    list of BorderPair
        Sorted by decreasing score; ties keep the order of the lines.

    References
    ----------
    seeds/000, section 2.3: pairs by expected width, parallelism and length.
    """
    count = len(lines)
    if count < 2:
        return []
    a, b = lines.fit()
    angle, v_low, v_high, span = np.arctan(b), lines.v_low, lines.v_high, lines.span
    first, second = _pairs_of(count)
    overlap = np.minimum(v_high[first], v_high[second]) - np.maximum(v_low[first], v_low[second]) + 1.0
    candidates = (np.abs(angle[first] - angle[second]) <= 2.0 * rules.max_skew + 1e-9) & (
        overlap >= rules.min_overlap * np.minimum(span[first], span[second])
    )
    candidates[candidates] = may_pass(a, b, v_low, v_high, first[candidates], second[candidates], size, rules,
                                      expected_width)
    found: list[BorderPair] = []
    made: dict[int, Line] = {}

    def line(k: int) -> Line:
        # A line takes part in many candidate pairs; it is made once.
        if k not in made:
            made[k] = pixel_line(a[k], b[k], v_low[k], v_high[k], size)
        return made[k]

    for i, j in zip(first[candidates].tolist(), second[candidates].tolist()):
        borders = (line(i), line(j))
        state = cable_from_borders(*borders)
        if abs(state.beta) > rules.max_skew or not rules.min_width <= state.w <= rules.max_width:
            continue
        score = float(lines.n[i] + lines.n[j]) * (1.0 - abs(state.beta) / rules.max_skew if rules.max_skew > 0 else 1.0)
        if expected_width is not None:
            agreement = 1.0 - abs(state.w - expected_width) / (rules.width_tolerance * expected_width)
            if agreement <= 0:
                continue
            score *= agreement
        found.append(BorderPair(i, j, borders, state, score))
    found.sort(key=lambda pair: -pair.score)
    return found


ROUNDING_PX = 1e-6
"""Room left for rounding by :func:`may_pass`, px (and rad for the skew): far more than the last bits it may differ in."""


def may_pass(
    a: np.ndarray,
    b: np.ndarray,
    v_low: np.ndarray,
    v_high: np.ndarray,
    first: np.ndarray,
    second: np.ndarray,
    size: ImageSize,
    rules: PairRules,
    expected_width: float | None,
) -> np.ndarray:
    """Whether each pair of lines ``u = a + b v`` may pass :func:`border_pairs`' tests of skew, width and agreement.

    The cable state of every pair at once, by the steps of
    :func:`benchmark.modalities.camera.geometry.cable_from_borders` on arrays;
    its width and skew may differ from the one-pair computation in their
    last bits (``numpy.hypot`` is not Python's), so a pair is passed over
    only when it fails a test by more than :data:`ROUNDING_PX`.  The pairs
    kept are then judged one by one exactly as before: the found pairs are
    the same, only the pairs that cannot be found are not built.

    Returns
    -------
    numpy.ndarray
        Boolean, one per pair ``(first[k], second[k])``.
    """
    width, height = size
    narrow = v_high - v_low < 1.0
    top = np.where(narrow, v_low - 0.5, v_low)
    bottom = np.where(narrow, v_low + 0.5, v_high)
    x_centre, y_centre = (width - 1) / 2.0, (height - 1) / 2.0
    x0, y0 = (a + b * top) - x_centre, y_centre - top
    dx, dy = ((a + b * bottom) - x_centre) - x0, (y_centre - bottom) - y0
    norm = np.hypot(dx, dy)
    dx, dy = dx / norm, dy / norm
    ux, uy, vx, vy = dx[first], dy[first], dx[second], dy[second]
    flip = ux * vx + uy * vy < 0
    vx, vy = np.where(flip, -vx, vx), np.where(flip, -vy, vy)
    tx, ty = ux + vx, uy + vy
    t_norm = np.hypot(tx, ty)
    tx, ty = tx / t_norm, ty / t_norm
    nx, ny = ty, -tx
    half_angle = 0.5 * np.arctan2(np.abs(ux * vy - uy * vx), ux * vx + uy * vy)
    crossings = []
    normals = []
    for k in (first, second):
        mx, my = dy[k], -dx[k]
        turn = mx * nx + my * ny < 0
        mx, my = np.where(turn, -mx, mx), np.where(turn, -my, my)
        normals.append((mx, my, mx * x0[k] + my * y0[k]))
    (m1x, m1y, c1), (m2x, m2y, c2) = normals
    d = (c1 + c2) / np.hypot(m1x + m2x, m1y + m2y)
    c0x, c0y = d * nx, d * ny
    with np.errstate(divide="ignore", invalid="ignore"):
        crossings = [(c - (mx * c0x + my * c0y)) / (mx * nx + my * ny) for mx, my, c in normals]
    pair_width = np.abs(crossings[1] - crossings[0])
    passes = (half_angle <= rules.max_skew + ROUNDING_PX) & (pair_width >= rules.min_width - ROUNDING_PX) & (
        pair_width <= rules.max_width + ROUNDING_PX
    )
    if expected_width is not None and expected_width > 0:
        passes &= np.abs(pair_width - expected_width) < rules.width_tolerance * expected_width + ROUNDING_PX
    # A pair whose numbers are not finite is left to the exact test.
    return passes | ~np.isfinite(pair_width) | ~np.isfinite(half_angle)


@functools.lru_cache(maxsize=64)
def _pairs_of(count: int) -> tuple[np.ndarray, np.ndarray]:
    """Indices ``(i, j)``, ``i < j``, of every pair of ``count`` lines, in row-major order (read-only)."""
    first, second = np.triu_indices(count, 1)
    first.flags.writeable = second.flags.writeable = False
    return first, second


def pair_lines(lines: Segments, pairs: list[BorderPair]) -> Segments:
    """The lines that take part in ``pairs``, each once."""
    used = sorted({index for pair in pairs for index in (pair.first, pair.second)})
    return lines.take(np.asarray(used, dtype=np.int64))


def fuse(
    cell_lines: list[Segments],
    size: ImageSize,
    rules: PairRules,
    *,
    strip_px: float,
    max_angle: float,
    min_rows: float,
    min_gradient: float,
    max_rms: float,
    max_lines: int,
    expected_width: float | None = None,
) -> list[BorderPair]:
    """Fuse the lines of the cells' best pairs and rank the final pairs.

    Parameters
    ----------
    cell_lines : list of Segments
        For each cell, the lines of its most likely pairs (:func:`pair_lines`).
    size : tuple of int
        Image ``(W, H)``.
    rules : PairRules
        Pairing limits.
    strip_px, max_angle : float
        Grouping strip (:func:`trackbench_segmentation.lines.group_collinear`).
    min_rows, min_gradient, max_rms, max_lines : float, float, float, int
        Filtering (:func:`trackbench_segmentation.lines.select_long`).
    expected_width : float, optional
        The predicted cable width, px.

    Returns
    -------
    list of BorderPair
        The plausible pairs after the fusion, best first, their indices
        into the fused lines; empty when no pair survives.  The first is
        the system's output; the tracker may pass over pairs its filter
        cannot have produced (:mod:`trackbench_segmentation.tracking`).

    References
    ----------
    seeds/000, section 2.3: "the most likely line pairs of each cell of the
    image are fused re-executing the line segment grouping, filtering and
    selection".
    """
    merged = group_collinear(Segments.concatenate(cell_lines), strip_px, max_angle)
    lines = select_long(merged, min_rows=min_rows, min_gradient=min_gradient, max_rms=max_rms, max_count=max_lines)
    return border_pairs(lines, size, rules, expected_width)



@numba.njit(cache=True, nogil=True)
def _pixel_line(a: float, b: float, top: float, bottom: float, width: int, height: int) -> tuple[float, float, float, float]:
    """:func:`trackbench_segmentation.lines.pixel_line` as ``(x0, y0, dx, dy)``; ``dx = dy = nan`` when it is not a line."""
    if bottom - top < 1.0:
        top, bottom = top - 0.5, top + 0.5
    x_centre, y_centre = (width - 1) / 2.0, (height - 1) / 2.0
    x0, y0 = (a + b * top) - x_centre, y_centre - top
    dx, dy = ((a + b * bottom) - x_centre) - x0, (y_centre - bottom) - y0
    norm = python_hypot(dx, dy)
    if not (math.isfinite(norm) and norm > 0 and math.isfinite(x0) and math.isfinite(y0)):
        return x0, y0, math.nan, math.nan
    return x0, y0, dx / norm, dy / norm


@numba.njit(cache=True, nogil=True)
def _line_table(a: np.ndarray, b: np.ndarray, fields: np.ndarray, width: int, height: int) -> np.ndarray:
    """Every segment's :func:`_pixel_line`, ``(n, 4)``."""
    lines = np.empty((a.shape[0], 4))
    for k in range(a.shape[0]):
        lines[k, 0], lines[k, 1], lines[k, 2], lines[k, 3] = _pixel_line(a[k], b[k], fields[7, k], fields[8, k], width, height)
    return lines


@numba.njit(cache=True, nogil=True)
def _ranked_pairs(
    fields: np.ndarray,
    start: int,
    stop: int,
    lines: np.ndarray,
    angle: np.ndarray,
    max_skew: float,
    min_width: float,
    max_width: float,
    min_overlap: float,
    width_tolerance: float,
    expected_width: float,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, bool]:
    """:func:`border_pairs` of the segments ``start:stop``: their indices and scores, best first.

    ``expected_width`` nan: none.  The flag is False when a line of a
    candidate pair is not one (:class:`benchmark.modalities.camera.geometry.Line`
    would refuse it): the pairs are then to be found the slow way.
    """
    count = stop - start
    capacity = max(count * (count - 1) // 2, 0)
    scores = np.empty(capacity)
    firsts = np.empty(capacity, dtype=np.int64)
    seconds = np.empty(capacity, dtype=np.int64)
    found = 0
    for i in range(start, stop):
        for j in range(i + 1, stop):
            if not abs(angle[i] - angle[j]) <= 2.0 * max_skew + 1e-9:
                continue
            span_i = fields[8, i] - fields[7, i] + 1.0
            span_j = fields[8, j] - fields[7, j] + 1.0
            overlap = min(fields[8, i], fields[8, j]) - max(fields[7, i], fields[7, j]) + 1.0
            if not overlap >= min_overlap * min(span_i, span_j):
                continue
            if math.isnan(lines[i, 2]) or math.isnan(lines[j, 2]):
                return firsts[:0], seconds[:0], scores[:0], False
            _, _, w, beta = cable_of_borders(
                lines[i, 0], lines[i, 1], lines[i, 2], lines[i, 3], lines[j, 0], lines[j, 1], lines[j, 2], lines[j, 3]
            )
            if abs(beta) > max_skew or not min_width <= w <= max_width:
                continue
            score = (fields[0, i] + fields[0, j]) * (1.0 - abs(beta) / max_skew if max_skew > 0 else 1.0)
            if not math.isnan(expected_width):
                agreement = 1.0 - abs(w - expected_width) / (width_tolerance * expected_width)
                if agreement <= 0:
                    continue
                score *= agreement
            scores[found] = score
            firsts[found] = i
            seconds[found] = j
            found += 1
    ranked = np.argsort(-scores[:found], kind="mergesort")
    return firsts[ranked], seconds[ranked], scores[ranked], True


@numba.njit(cache=True, nogil=True)
def _best_pair_lines(
    fields: np.ndarray,
    offsets: np.ndarray,
    a: np.ndarray,
    b: np.ndarray,
    angle: np.ndarray,
    width: int,
    height: int,
    max_skew: float,
    min_width: float,
    max_width: float,
    min_overlap: float,
    width_tolerance: float,
    expected_width: float,
    pairs_per_cell: int,
) -> tuple[np.ndarray, bool]:
    """Each cell's :func:`border_pairs` and :func:`pair_lines`, the lines of its best pairs side by side (flag: see
    :func:`_ranked_pairs`)."""
    lines = _line_table(a, b, fields, width, height)
    chosen = np.zeros(a.shape[0], dtype=np.bool_)
    for cell in range(offsets.shape[0] - 1):
        firsts, seconds, _, ok = _ranked_pairs(
            fields, offsets[cell], offsets[cell + 1], lines, angle, max_skew, min_width, max_width, min_overlap,
            width_tolerance, expected_width,
        )
        if not ok:
            return np.empty((9, 0)), False
        for k in range(min(pairs_per_cell, firsts.shape[0])):
            chosen[firsts[k]] = True
            chosen[seconds[k]] = True
    return take_segments(fields, np.flatnonzero(chosen)), True


@numba.njit(cache=True, nogil=True)
def _fused_pairs(
    fields: np.ndarray,
    a: np.ndarray,
    b: np.ndarray,
    angle: np.ndarray,
    width: int,
    height: int,
    max_skew: float,
    min_width: float,
    max_width: float,
    min_overlap: float,
    width_tolerance: float,
    expected_width: float,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, bool]:
    """:func:`_ranked_pairs` of all the segments."""
    lines = _line_table(a, b, fields, width, height)
    # A typed zero: a literal would compile a second form of the ranking.
    return _ranked_pairs(
        fields, np.int64(0), a.shape[0], lines, angle, max_skew, min_width, max_width, min_overlap, width_tolerance,
        expected_width,
    )


def fuse_pairs(
    cell_lines: Segments,
    size: ImageSize,
    rules: PairRules,
    *,
    strip_px: float,
    max_angle: float,
    min_rows: float,
    min_gradient: float,
    max_rms: float,
    max_lines: int,
    expected_width: float | None = None,
) -> list[BorderPair]:
    """:func:`fuse` of the cells' pair lines, side by side in one :class:`Segments`, in compiled passes, bit for bit.

    The grouping and filtering of :func:`fuse` by
    :func:`trackbench_segmentation.passes.group_and_select`, the pairs'
    tests, scores and ranking by :func:`_ranked_pairs`; only the pairs found
    are built as :class:`BorderPair`, with the lines and states of
    :func:`border_pairs`.  An expected width of 0 or a degenerate line is
    left to :func:`fuse`.

    References
    ----------
    seeds/000, section 2.3: the fusion of the cells' most likely pairs.
    """
    if _divides_by_zero(rules, expected_width):
        return fuse([cell_lines], size, rules, strip_px=strip_px, max_angle=max_angle, min_rows=min_rows,
                    min_gradient=min_gradient, max_rms=max_rms, max_lines=max_lines, expected_width=expected_width)
    fields = group_and_select(_fields(cell_lines), -math.inf, float(strip_px), float(max_angle), float(min_rows),
                              float(min_gradient), float(max_rms), int(max_lines))
    lines = Segments(*fields)
    a, b = lines.fit()
    firsts, seconds, scores, ok = _fused_pairs(
        fields, a, b, np.arctan(b), int(size[0]), int(size[1]), *_rule_values(rules, expected_width)
    )
    if not ok:
        return border_pairs(lines, size, rules, expected_width)
    made: dict[int, Line] = {}

    def line(k: int) -> Line:
        if k not in made:
            made[k] = pixel_line(a[k], b[k], lines.v_low[k], lines.v_high[k], size)
        return made[k]

    # border_pairs' score is a numpy float once the width's agreement, from the state's numpy width, multiplies it.
    as_score = float if expected_width is None else np.float64
    found = []
    for i, j, score in zip(firsts.tolist(), seconds.tolist(), scores.tolist()):
        borders = (line(i), line(j))
        found.append(BorderPair(i, j, borders, cable_from_borders(*borders), as_score(score)))
    return found


def _divides_by_zero(rules: PairRules, expected_width: float | None) -> bool:
    """Whether the widths' agreement divides by zero (an expected width of 0): left to :func:`border_pairs`."""
    return expected_width is not None and rules.width_tolerance * expected_width == 0


def _fields(segments: Segments) -> np.ndarray:
    """The segments as a ``(9, n)`` array, their fields in order."""
    return np.stack([getattr(segments, name) for name in _FIELDS]) if len(segments) else np.empty((9, 0))


def _rule_values(rules: PairRules, expected_width: float | None) -> tuple[float, ...]:
    """The pairing limits and the expected width (nan: none) as the compiled passes take them."""
    return (
        float(rules.max_skew), float(rules.min_width), float(rules.max_width), float(rules.min_overlap),
        float(rules.width_tolerance), math.nan if expected_width is None else float(expected_width),
    )


def cells_pair_lines(
    lines: np.ndarray,
    offsets: np.ndarray,
    size: ImageSize,
    rules: PairRules,
    expected_width: float | None,
    pairs_per_cell: int,
) -> Segments:
    """The lines of each cell's ``pairs_per_cell`` best pairs, all cells' side by side, in one compiled pass.

    Parameters
    ----------
    lines, offsets : numpy.ndarray
        The cells' long lines side by side, ``(9, n)`` in the order of the
        fields of :class:`~trackbench_segmentation.lines.Segments`, cell ``k``'s
        at ``offsets[k] : offsets[k + 1]``
        (:func:`trackbench_segmentation.passes.pyramid_lines`).
    size, rules, expected_width
        As :func:`border_pairs`.
    pairs_per_cell : int
        The best pairs of each cell whose lines are kept.

    Returns
    -------
    Segments
        ``Segments.concatenate([pair_lines(cell, border_pairs(cell, size, rules,
        expected_width)[:pairs_per_cell]) for cell in cells])``, bit for bit:
        the pairs' states by :func:`cable_of_borders`, the same tests, the
        same stable ranking.  An expected width of 0 (whose agreement divides
        by zero) or a degenerate line is left to that one-cell form.

    References
    ----------
    seeds/000, section 2.3: "the most likely line pairs of each cell".
    """
    joined = Segments(*lines)
    if not _divides_by_zero(rules, expected_width):
        a, b = joined.fit()
        taken, ok = _best_pair_lines(
            lines, offsets, a, b, np.arctan(b), int(size[0]), int(size[1]), *_rule_values(rules, expected_width),
            int(pairs_per_cell),
        )
        if ok:
            return Segments(*taken)
    cells = [joined.take(np.arange(offsets[k], offsets[k + 1])) for k in range(len(offsets) - 1)]
    return _slow_pair_lines(cells, size, rules, expected_width, pairs_per_cell)


def _slow_pair_lines(
    cell_lines: list[Segments], size: ImageSize, rules: PairRules, expected_width: float | None, pairs_per_cell: int
) -> Segments:
    """:func:`cells_pair_lines` one cell at a time, in Python."""
    return Segments.concatenate(
        [pair_lines(lines, border_pairs(lines, size, rules, expected_width)[:pairs_per_cell]) for lines in cell_lines]
    )
