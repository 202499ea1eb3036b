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

Its score (:func:`choose_pair`; :func:`best_pair` does both steps on line rows) is the sum of the two lines' votes; while
tracking, only pairs inside the search window count and the score shrinks
with the distance from the previous pair.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from benchmark.lazy import lazy_module
from benchmark.modalities.camera.geometry import ImageSize, Line
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


def _line_rows(lines: Sequence[HoughLine]) -> np.ndarray:
    """The rows ``(rho, theta, votes, r, phi)`` of the compiled loops (:mod:`trackbench_hough.line_loops`)."""
    return np.array([(line.rho, line.theta, line.votes, line.r, line.phi) for line in lines], np.float64).reshape(-1, 5)


def _window_rows(window: SearchWindow | None) -> tuple[np.ndarray, float, float]:
    """The window's border rows ``(r, phi)`` and half-widths for :func:`trackbench_hough.line_loops.best_pair`."""
    if window is None:
        return np.zeros((0, 2)), math.inf, math.inf
    return np.array(window.borders, np.float64), float(window.r_half), float(window.phi_half)


def _compatible_rows(
    rows: np.ndarray,
    size: ImageSize,
    max_skew: float,
    max_divergence: float,
    min_width: float,
    max_width: float,
    anchor_votes: float,
) -> tuple[np.ndarray, np.ndarray]:
    """:func:`trackbench_hough.line_loops.border_pairs` of line rows: the pairs' indices and states."""
    return line_loops.border_pairs(
        rows,
        (size[0] - 1) / 2.0,
        (size[1] - 1) / 2.0,
        float(anchor_votes),
        2.0 * max(max_skew, max_divergence),
        float(max_skew),
        float(max_divergence),
        float(min_width),
        float(max_width),
    )


def _border_pair(first: HoughLine, second: HoughLine, state: list[float], size: ImageSize) -> BorderPair:
    return BorderPair(first, second, (first.line(size), second.line(size)), CableState(*state), first.votes + second.votes)


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

    One compiled loop (:func:`trackbench_hough.line_loops.border_pairs`)
    tests the pairs, with the steps of
    :func:`benchmark.modalities.camera.geometry.cable_from_borders` and
    CPython's ``hypot``, so the same states to the last bit.

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
    pairs, states = _compatible_rows(
        _line_rows(lines), size, max_skew, max_divergence, min_width, max_width, anchor_votes
    )
    return [
        _border_pair(lines[i], lines[j], state, size) for (i, j), state in zip(pairs.tolist(), states.tolist())
    ]


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
    rows = _line_rows([line for pair in pairs for line in (pair.first, pair.second)])
    indices = np.arange(2 * len(pairs), dtype=np.int64).reshape(-1, 2)
    best = line_loops.best_pair(rows, indices, *_window_rows(window), float(closeness_weight))
    return None if best < 0 else pairs[best]


def best_pair(
    rows: np.ndarray,
    size: ImageSize,
    window: SearchWindow | None,
    closeness_weight: float,
    *,
    max_skew: float,
    max_divergence: float,
    min_width: float,
    max_width: float,
    anchor_votes: float = 0.0,
) -> BorderPair | None:
    """``choose_pair(compatible_pairs(lines, ...), window, closeness_weight)`` of line rows, making only the chosen pair.

    Parameters
    ----------
    rows : numpy.ndarray
        ``(rho, theta, votes, r, phi)`` rows of the candidate lines
        (:func:`trackbench_hough.lines.distinct_line_rows`).
    size, window, closeness_weight, max_skew, max_divergence, min_width, max_width, anchor_votes
        As :func:`compatible_pairs` and :func:`choose_pair`.

    Returns
    -------
    BorderPair or None
        The pair :func:`choose_pair` chooses among :func:`compatible_pairs`.

    References
    ----------
    seeds/004, section IV.
    """
    pairs, states = _compatible_rows(rows, size, max_skew, max_divergence, min_width, max_width, anchor_votes)
    best = line_loops.best_pair(rows, pairs, *_window_rows(window), float(closeness_weight))
    if best < 0:
        return None
    i, j = pairs[best].tolist()
    return _border_pair(HoughLine(*rows[i].tolist()), HoughLine(*rows[j].tolist()), states[best].tolist(), size)
