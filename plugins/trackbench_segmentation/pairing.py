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
from dataclasses import dataclass

import numpy as np

from benchmark.modalities.camera.geometry import ImageSize, Line, cable_from_borders
from benchmark.modalities.camera.model import CableState
from trackbench_segmentation.lines import Segments, group_collinear, pixel_line, select_long


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

