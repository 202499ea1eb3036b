"""Grouping Hough lines into the pair most likely to be the cable borders.

The Hough papers reviewed in seeds/000, section 2.1 assume that the cable
borders are the most particular straight edges of the scene.  Seeds/004,
section IV spells out the grouping step such a detector needs: "only pairs
of lines which are compatible with the geometrical characteristic of the
scene and the perspective laws are considered ... it is not possible that
two candidate lines representing the pipeline borders intersect or
diverge", and "the prediction of the position of the searched lines ... is
also used to choose the best pair".

Here a pair is compatible (:func:`compatible_pairs`) when

* the borders are nearly parallel: the skew ``beta`` of the cable state they
  define (half the angle between them) is at most ``max_skew``, and they
  diverge towards the top by at most ``max_divergence`` (Hough angle
  quantisation can tilt two parallel lines apart by one step);
* they do not cross inside the image;
* the width ``w`` lies in ``[min_width, max_width]`` (seeds/000, Table 5.2:
  5 to 100 px);
* the stronger of the two lines has at least ``anchor_votes`` votes.  The
  weaker one needs only the votes every line of the transform has: the
  two borders of a cable are seldom equally clear (one lies in the lamp's
  shadow, or along a bright sunlit band), and a weaker line is believable
  as a border once a strong one beside it vouches for the pair.  A single
  vote threshold for both (``anchor_votes`` no higher than the transform's
  own) is the paper's detector.

Its score (:func:`choose_pair`) is the sum of the two lines' votes; while
tracking, only pairs inside the search window count and the score shrinks
with the distance from the previous pair.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from benchmark.lazy import lazy_module
from benchmark.modalities.camera.geometry import ImageSize, Line, cable_from_borders
from benchmark.modalities.camera.model import CableState
from trackbench_hough.lines import HoughLine
from trackbench_hough.window import SearchWindow

# The compiled loops load on the first frame, so that listing the trackers does not import numba.
line_loops = lazy_module("trackbench_hough.line_loops")


@dataclass(frozen=True, slots=True)
class BorderPair:
    """Two Hough lines taken as the cable borders.

    Attributes
    ----------
    first, second : HoughLine
        The two lines, in no particular order.
    borders : tuple of Line
        The same lines in model coordinates.
    state : CableState
        The cable state they define (:func:`benchmark.modalities.camera.geometry.cable_from_borders`).
    votes : float
        Sum of the two lines' votes.
    """

    first: HoughLine
    second: HoughLine
    borders: tuple[Line, Line]
    state: CableState
    votes: float


def _crossing_inside(a: Line, b: Line, size: ImageSize) -> bool:
    det = a.dx * b.dy - a.dy * b.dx
    if abs(det) < 1e-12:
        return False
    s = ((b.x0 - a.x0) * b.dy - (b.y0 - a.y0) * b.dx) / det
    x, y = a.x0 + s * a.dx, a.y0 + s * a.dy
    return abs(x) <= (size[0] - 1) / 2.0 and abs(y) <= (size[1] - 1) / 2.0


def compatible_pairs(
    lines: list[HoughLine],
    size: ImageSize,
    *,
    max_skew: float,
    max_divergence: float,
    min_width: float,
    max_width: float,
    anchor_votes: float = 0.0,
) -> list[BorderPair]:
    """All pairs of lines that could be the two borders of one cable.

    Parameters
    ----------
    lines : list of HoughLine
        Candidate lines (after duplicate suppression).
    size : tuple of int
        Image ``(W, H)`` in px.
    max_skew : float
        Largest skew ``beta`` (rad) of a converging pair.
    max_divergence : float
        Largest skew (rad) of a pair that diverges towards the top.
    min_width, max_width : float
        Plausible cable widths in px.
    anchor_votes : float
        Votes the stronger line of a pair needs.

    Returns
    -------
    list of BorderPair
        In the order of the input lines.

    References
    ----------
    seeds/004, section IV (grouping: no crossing, no divergence);
    seeds/000, section 2.1 and Table 5.2 (width and skew ranges).
    """
    rows = np.array([(line.rho, line.theta, line.votes, line.r, line.phi) for line in lines], np.float64)
    candidates = line_loops.near_parallel_pairs(
        rows.reshape(-1, 5), float(anchor_votes), 2.0 * max(max_skew, max_divergence)
    )
    models: dict[int, Line] = {}
    pairs: list[BorderPair] = []
    for i, j in candidates.tolist():
        first, second = lines[i], lines[j]
        a = models[i] if i in models else models.setdefault(i, first.line(size))
        b = models[j] if j in models else models.setdefault(j, second.line(size))
        if _crossing_inside(a, b, size):
            continue
        state = cable_from_borders(a, b)
        if not (-max_divergence <= state.beta <= max_skew and min_width <= state.w <= max_width):
            continue
        pairs.append(BorderPair(first, second, (a, b), state, first.votes + second.votes))
    return pairs


def choose_pair(
    pairs: list[BorderPair], window: SearchWindow | None = None, closeness_weight: float = 0.5
) -> BorderPair | None:
    """The pair most likely to be the cable borders.

    Parameters
    ----------
    pairs : list of BorderPair
        Compatible pairs (:func:`compatible_pairs`).
    window : SearchWindow, optional
        While tracking: the window around the previous pair.  Pairs outside
        it are ignored, and a pair's votes are scaled by
        ``1 - closeness_weight * deviation`` (:meth:`SearchWindow.deviation`).
    closeness_weight : float
        How much a pair at the window's edge loses against one that repeats
        the previous result, in ``[0, 1]``.

    Returns
    -------
    BorderPair or None
        The best pair; None when no pair qualifies.  Ties go to the pair
        listed first (the stronger lines).

    References
    ----------
    seeds/004, section IV: the prediction chooses among compatible pairs;
    without one, the most reliable compatible pair is selected.
    """
    best: BorderPair | None = None
    best_score = -math.inf
    fits: dict[int, tuple[tuple[float, float] | None, tuple[float, float] | None]] = {}
    for pair in pairs:
        score = pair.votes
        if window is not None:
            # A line is in many pairs: its fits to the window are computed once.
            first = fits.get(id(pair.first)) or fits.setdefault(id(pair.first), window.fits(pair.first))
            second = fits.get(id(pair.second)) or fits.setdefault(id(pair.second), window.fits(pair.second))
            deviation = window.deviation_of_fits(first, second)
            if deviation is None:
                continue
            score *= 1.0 - closeness_weight * deviation
        if score > best_score:
            best, best_score = pair, score
    return best
