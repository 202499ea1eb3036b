"""Straight lines by the Hough transform, with their modulus and domain (seeds/004, section IV).

The "improvement of the Hough transform" of seeds/004 [19] returns, for
each line, "1) the alpha and rho parameters, which locate it (normal
parametrization) [Fig. 7(a)]; 2) the average amplitude (module) M of the
edges that vote for it; 3) a monodimensional array, called domain
(dom[i])", which marks where along the line its voters lie.  The paper does
not describe the improvement itself; what follows is our reading.

Parametrisation
---------------
Lines are ``x cos(alpha) + y sin(alpha) = rho`` in the model coordinates of
conventions.md section 1 (origin at the image centre, ``x`` right, ``y``
up), with ``alpha`` in ``[-pi/2, pi/2)`` and ``rho`` signed, in px.  A
vertical line has ``alpha = 0`` and ``rho`` its offset right of the centre;
the accumulator's wrap-around lies at horizontal lines, far from the
pipeline borders.  seeds/004's Tables I-II use pixel coordinates from the
top-left corner with ``alpha`` in ``[0, 180)`` deg; a line ``(a, r)`` there
is ``(-a, r - cu cos a - cv sin a)`` here, folded into ``[-pi/2, pi/2)``,
with ``(cu, cv) = ((W-1)/2, (H-1)/2)``.  (Every ``alpha`` in the tables is
a multiple of 0.7 deg, about 180/256, and every ``rho`` is ``6 k + 3``: an
accumulator of 256 angle bins and 6 px distance bins.  We default to 1 deg
and 1 px, then refit each line to its edges.)

Voting
------
Every edge votes once per angle bin, but only for the bins within
``phase_tolerance`` of the bin of its own gradient direction ``F(k)``
(folded modulo ``pi``), because the normal of a straight edge is its
gradient.  This standard restriction of the transform (the gradient
direction of O'Gorman and Clowes) cuts the votes per edge from 180 to a
handful and removes most accidental alignments among the "many other
extracted edges" the paper worries about.

A line between two bins splits its votes among up to four of them, so
peaks are sought on the sums of 2 x 2 blocks of bins (:func:`pooled_votes`):
the local maxima with at least ``min_votes`` votes in a ``(2 n + 1) x
(2 n + 1)`` neighbourhood of blocks (the angle axis wraps, flipping
``rho``); equal votes on a plateau give one peak.

Refit, voters and domain
------------------------
A peak gives its line only to within half a bin: up to
``(half diagonal) sin(alpha_step / 2) + rho_step / 2`` px (2.2 px for
320 x 240 at 1 deg and 1 px) from its edges at the image border, which
would cut its domain short at a 1.5 px tolerance.  Each peak line is
therefore refitted by total least squares to the phase-compatible edges
within that stray plus the tolerance (:func:`refine_lines`), and refitted
lines that land within the suppression neighbourhood of a stronger one are
dropped.

The voters of a line are then the edges within ``tolerance`` px of it whose
phase lies within ``phase_tolerance`` of its normal.  Its modulus ``M`` is
their mean modulus, and its polarity the way most of their phases point
along the normal (+1 with it, -1 against it): whether the grey level rises
or falls across the line, which grouping needs to tell a band from two
edges that step the same way.  Its domain is a boolean array over the image rows
(``dom[i]`` for row ``v = i``, ``i`` in ``[0, H)``) for lines within 45 deg
of vertical (``|alpha| <= pi/4``), over the columns (``u = i``, ``i`` in
``[0, W)``) for the others: "rows (or columns)" in Fig. 7(b), so that each
entry of the domain holds at most one point of the line.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numba
import numpy as np

from trackbench_foresti.edges import EdgeMap


@dataclass(frozen=True, eq=False)
class HoughLine:
    """One line of the transform with its voters' modulus and domain.

    Attributes
    ----------
    alpha : float
        Normal angle in rad, in ``[-pi/2, pi/2)``, model coordinates.
    rho : float
        Signed distance in px from the image centre along ``(cos alpha, sin alpha)``.
    votes : int
        Votes of the 2 x 2 block of bins the line comes from (:func:`pooled_votes`).
    modulus : float
        Mean gradient modulus ``M`` of the line's voters (0 without voters).
    domain : numpy.ndarray
        ``bool`` array of length ``H`` (row domain) or ``W`` (column domain).
    by_rows : bool
        True when the domain runs over rows (``|alpha| <= pi/4``).
    polarity : int
        +1 when most voters' phases point along ``(cos alpha, sin alpha)``,
        -1 when against it, 0 without voters or on a tie.
    """

    alpha: float
    rho: float
    votes: int
    modulus: float
    domain: np.ndarray
    by_rows: bool
    polarity: int = 0


@dataclass(frozen=True, eq=False)
class Accumulator:
    """The Hough accumulator over ``(alpha, rho)``.

    Attributes
    ----------
    votes : numpy.ndarray
        ``int32`` array of shape ``(n_alpha, n_rho)``.
    alphas : numpy.ndarray
        Bin centres in rad, ``-pi/2 + k * alpha_step``.
    rhos : numpy.ndarray
        Bin centres in px, symmetric about 0: ``(j - n_rho // 2) * rho_step``.
    """

    votes: np.ndarray
    alphas: np.ndarray
    rhos: np.ndarray


@dataclass(frozen=True, eq=False)
class EdgePoints:
    """The edge pixels of an :class:`EdgeMap` as flat arrays.

    Attributes
    ----------
    u, v : numpy.ndarray
        Pixel column and row.
    x, y : numpy.ndarray
        Model coordinates.
    modulus : numpy.ndarray
        Gradient modulus ``M(k)``.
    normal : numpy.ndarray
        Phase ``F(k)`` folded into ``[-pi/2, pi/2)``: the normal angle of
        the line the edge belongs to.  The points are sorted by it, so that
        the edges of one direction are found by bisection.
    step : numpy.ndarray
        +1 where the phase points along ``(cos normal, sin normal)``, -1
        where folding turned it by a half turn.
    size : tuple of int
        Image ``(W, H)`` in px.
    """

    u: np.ndarray
    v: np.ndarray
    x: np.ndarray
    y: np.ndarray
    modulus: np.ndarray
    normal: np.ndarray
    step: np.ndarray
    size: tuple[int, int]

    @classmethod
    def of(cls, edges: EdgeMap) -> EdgePoints:
        """The edge pixels of an edge map."""
        width, height = edges.size
        phase = edges.phase.astype(np.float64)
        normal = fold(phase)
        order = stable_argsort(normal)
        pixels, phase, normal = edges.pixels[order], phase[order], normal[order]
        v, u = np.divmod(pixels, width)
        x = u.astype(np.float64) - (width - 1) / 2.0
        y = (height - 1) / 2.0 - v.astype(np.float64)
        # phase - normal is 0 or a half turn, up to rounding.
        step = np.where(np.abs(phase - normal) < math.pi / 2, 1, -1)
        modulus = edges.modulus[order].astype(np.float64)
        return cls(u, v, x, y, modulus, normal, step, edges.size)


def stable_argsort(values: np.ndarray) -> np.ndarray:
    """The indices that sort ``values`` stably: ``np.argsort(values, kind="stable")``, by a faster route.

    An unstable sort groups equal values; sorting the pairs (group, index) as
    unique integer keys then restores the original order within each group.
    """
    values = np.asarray(values).reshape(-1)
    if values.size < 2:
        return np.arange(values.size)
    order = np.argsort(values)
    ordered = values[order]
    group = np.zeros(values.size, dtype=np.int64)
    np.cumsum(ordered[1:] != ordered[:-1], out=group[1:])
    key = group * values.size + order
    key.sort()
    return key % values.size


def fold(angle: np.ndarray | float) -> np.ndarray:
    """Fold angles modulo ``pi`` into ``[-pi/2, pi/2)``.

    ``np.mod(angle + pi/2, pi) - pi/2``, by the ``fmod`` that ``np.mod`` takes and corrects, at half its cost.
    """
    rest = np.fmod(np.asarray(angle, dtype=np.float64) + math.pi / 2, math.pi)
    return np.where(rest < 0, rest + math.pi, rest) - math.pi / 2


def fold_angle(angle: float) -> float:
    """:func:`fold` of one angle, in Python floats: their ``%`` rounds as ``np.mod`` does."""
    return (angle + math.pi / 2) % math.pi - math.pi / 2


def _angle_bins(alpha_step: float) -> int:
    if not 0 < alpha_step <= math.pi / 4:
        raise ValueError(f"alpha_step must be in (0, pi/4], got {alpha_step}")
    n_alpha = round(math.pi / alpha_step)
    if not math.isclose(n_alpha * alpha_step, math.pi, rel_tol=1e-9):
        raise ValueError(f"alpha_step must divide pi, got {alpha_step}")
    return n_alpha


@numba.njit(cache=True, nogil=True)
def _vote(
    first: np.ndarray,
    x: np.ndarray,
    y: np.ndarray,
    cosines: np.ndarray,
    sines: np.ndarray,
    cells: np.ndarray,
    span: int,
    rho_step: float,
    votes: np.ndarray,
) -> None:
    """Add the votes of each point ``p`` for the table entries ``s`` from ``first[p]`` to ``first[p] + span - 1``.

    Entry ``s`` is an angle bin: the cosine and sine of its angle, and the
    flat index ``cells[s]`` of its ``rho = 0`` cell in ``votes``.  The vote
    goes ``rint((cosines[s] x[p] + sines[s] y[p]) / rho_step)`` cells on.
    """
    for p in range(first.size):
        for s in range(first[p], first[p] + span):
            rho = cosines[s] * x[p] + sines[s] * y[p]
            if rho_step != 1.0:
                rho /= rho_step
            votes[cells[s] + int(np.rint(rho))] += 1


def accumulate(points: EdgePoints, alpha_step: float, rho_step: float, phase_tolerance: float) -> Accumulator:
    """Vote the edges into the ``(alpha, rho)`` accumulator.

    Parameters
    ----------
    points : EdgePoints
        Edge pixels and their folded phases.
    alpha_step : float
        Angle resolution in rad; must divide ``pi``.
    rho_step : float
        Distance resolution in px.
    phase_tolerance : float
        An edge votes for the angle bins up to this many rad from the bin
        nearest its folded phase (at least that bin).

    Returns
    -------
    Accumulator
        Counts per bin; each edge adds at most one vote per angle bin.

    References
    ----------
    seeds/004, section IV and Fig. 7(a) (normal parametrisation).
    """
    n_alpha = _angle_bins(alpha_step)
    if not rho_step > 0:
        raise ValueError(f"rho_step must be positive, got {rho_step}")
    if not 0 <= phase_tolerance <= math.pi / 2:
        raise ValueError(f"phase_tolerance must be in [0, pi/2], got {phase_tolerance}")
    width, height = points.size
    half = math.ceil(math.hypot((width - 1) / 2.0, (height - 1) / 2.0) / rho_step) + 1
    n_rho = 2 * half + 1
    alphas = -math.pi / 2 + alpha_step * np.arange(n_alpha)
    rhos = rho_step * (np.arange(n_rho) - half)
    reach = int(math.floor(phase_tolerance / alpha_step + 1e-9))
    # Entry s of the tables is angle bin s - reach, wrapped (reach <= n_alpha / 2: one wrap at most).
    wrapped = np.mod(np.arange(-reach, n_alpha + 1 + reach), n_alpha)
    centre = np.rint((points.normal + math.pi / 2) / alpha_step).astype(np.int64)
    votes = np.zeros((n_alpha, n_rho), dtype=np.int32)
    cosines, sines = np.cos(alphas)[wrapped], np.sin(alphas)[wrapped]
    cells = wrapped * n_rho + half
    _vote(centre, points.x, points.y, cosines, sines, cells, 2 * reach + 1, float(rho_step), votes.ravel())
    return Accumulator(votes, alphas, rhos)


def pooled_votes(votes: np.ndarray) -> np.ndarray:
    """Sums of the votes over 2 x 2 blocks of bins: ``pooled[k, j] = votes[k:k+2, j:j+2].sum()``.

    The angle axis wraps (bin ``n_alpha`` is bin 0 with ``rho`` flipped);
    the last distance column sums one column.  A line that falls between
    bins splits its votes among up to four of them; their block sum gives
    it back whole, so one vote threshold serves lines on and between bins.
    """
    both = np.empty_like(votes)
    np.add(votes[1:], votes[:-1], out=both[:-1])
    np.add(votes[0, ::-1], votes[-1], out=both[-1])
    pooled = np.empty_like(both)
    np.add(both[:, 1:], both[:, :-1], out=pooled[:, :-1])
    pooled[:, -1] = both[:, -1]
    return pooled


def find_peaks(votes: np.ndarray, min_votes: int, neighbourhood: int) -> tuple[np.ndarray, np.ndarray]:
    """Local maxima of an accumulator.

    Parameters
    ----------
    votes : numpy.ndarray
        Counts of shape ``(n_alpha, n_rho)`` over the bins of an
        :class:`Accumulator` (or their :func:`pooled_votes`).
    min_votes : int
        Smallest vote count of a peak.
    neighbourhood : int
        Half-size ``n`` in bins of the square window a peak dominates; the
        angle axis wraps around (``alpha -> alpha + pi``, ``rho -> -rho``).

    Returns
    -------
    k, j : numpy.ndarray
        Angle and distance bin indices of the peaks, most votes first.

    References
    ----------
    seeds/004, section IV (line extraction by voting [19]).
    """
    if neighbourhood < 0:
        raise ValueError(f"neighbourhood must be >= 0, got {neighbourhood}")
    n_alpha, n_rho = votes.shape
    n = min(neighbourhood, n_alpha)
    k, j = np.divmod(np.flatnonzero(votes >= min_votes), n_rho)
    # A ramp below one vote makes every bin unique, so a plateau yields one peak.
    ramp = float(votes.size + 1)
    peak = _dominant(votes, k, j, n, ramp)
    k, j = k[peak], j[peak]
    order = np.argsort(-(votes[k, j] + (k * n_rho + j).astype(np.float64) / ramp), kind="stable")
    return k[order], j[order]


@numba.njit(cache=True, nogil=True)
def _dominant(votes: np.ndarray, k: np.ndarray, j: np.ndarray, n: int, ramp: float) -> np.ndarray:
    """Whether each bin ``(k[c], j[c])`` ranks at least as high as every bin of its ``(2 n + 1) x (2 n + 1)`` window.

    A bin ranks ``votes + (k n_rho + j) / ramp``.  A row past either end of
    the angle axis is the row a half turn away with ``rho`` flipped; a
    column past either end of the distance axis holds no bin.
    """
    n_alpha, n_rho = votes.shape
    dominant = np.ones(k.size, np.bool_)
    for c in range(k.size):
        rank = votes[k[c], j[c]] + (k[c] * n_rho + j[c]) / ramp
        for row in range(k[c] - n, k[c] + n + 1):
            turned = row < 0 or row >= n_alpha
            wrapped = row % n_alpha
            for col in range(max(j[c] - n, 0), min(j[c] + n + 1, n_rho)):
                flipped = n_rho - 1 - col if turned else col
                if votes[wrapped, flipped] + (wrapped * n_rho + flipped) / ramp > rank:
                    dominant[c] = False
    return dominant


@numba.njit(cache=True, nogil=True)
def _near(
    normal: np.ndarray,
    x: np.ndarray,
    y: np.ndarray,
    alpha: float,
    cosine: float,
    sine: float,
    rho: float,
    tolerance: float,
    phase_tolerance: float,
) -> np.ndarray:
    """Indices of the points within ``tolerance`` of one line whose normal is within ``phase_tolerance`` of its own.

    ``normal`` is sorted, so the points facing the line are the window
    ``[alpha - phase_tolerance, alpha + phase_tolerance]`` of it and the
    copies of that window a half turn up and down (every point once
    ``phase_tolerance`` reaches ``pi / 2``); the indices come window by
    window, increasing in each.
    """
    found = np.empty(normal.size, np.int64)
    count = 0
    whole = phase_tolerance >= math.pi / 2
    for turn in (0.0, math.pi, -math.pi):
        start = 0 if whole else np.searchsorted(normal, alpha - phase_tolerance + turn, side="left")
        stop = normal.size if whole else np.searchsorted(normal, alpha + phase_tolerance + turn, side="right")
        for p in range(start, stop):
            if abs(x[p] * cosine + y[p] * sine - rho) <= tolerance:
                found[count] = p
                count += 1
        if whole:
            break
    return found[:count]


def supporters(
    points: EdgePoints, alphas: np.ndarray, rhos: np.ndarray, tolerance: float, phase_tolerance: float
) -> list[np.ndarray]:
    """The edges that support each line.

    Returns
    -------
    list of numpy.ndarray
        For each line, the indices into ``points`` of the edges within
        ``tolerance`` px of it whose folded phase lies within
        ``phase_tolerance`` rad of its normal.
    """
    return [
        _near(
            points.normal,
            points.x,
            points.y,
            float(alpha),
            math.cos(alpha),
            math.sin(alpha),
            float(rho),
            float(tolerance),
            float(phase_tolerance),
        )
        for alpha, rho in zip(np.reshape(alphas, -1), np.reshape(rhos, -1), strict=True)
    ]


def refine_lines(
    points: EdgePoints, alphas: np.ndarray, rhos: np.ndarray, capture: float, phase_tolerance: float
) -> tuple[np.ndarray, np.ndarray]:
    """Refit lines to the edges near them, by total least squares.

    Parameters
    ----------
    points : EdgePoints
        Edge pixels and folded phases.
    alphas, rhos : numpy.ndarray
        The lines, in the module's normal parametrisation.
    capture : float
        Distance in px within which edges take part in a line's fit.
    phase_tolerance : float
        Largest angle in rad between an edge's folded phase and the line's normal.

    Returns
    -------
    alphas, rhos : numpy.ndarray
        The refitted lines, ``alpha`` in ``[-pi/2, pi/2)``; a line with
        fewer than two such edges is returned unchanged.

    References
    ----------
    seeds/004, section IV (the "improvement of the Hough transform" [19]
    is not described; Tables I-II give ``alpha`` to 0.1 deg).  The refit is ours.
    """
    alphas = np.array(alphas, dtype=np.float64).reshape(-1)
    rhos = np.array(rhos, dtype=np.float64).reshape(-1)
    for i, near in enumerate(supporters(points, alphas, rhos, capture, phase_tolerance)):
        if near.size < 2:
            continue
        x, y = points.x[near], points.y[near]
        mean_x, mean_y = float(x.sum() / x.size), float(y.sum() / y.size)
        dx, dy = x - mean_x, y - mean_y
        sxx, syy, sxy = float(dx @ dx), float(dy @ dy), float(dx @ dy)
        # The normal that minimises the squared distances is the minor axis of the scatter.
        alpha = fold_angle(0.5 * math.atan2(2.0 * sxy, sxx - syy) + math.pi / 2)
        alphas[i], rhos[i] = alpha, mean_x * math.cos(alpha) + mean_y * math.sin(alpha)
    return alphas, rhos


def line_support(
    points: EdgePoints, alphas: np.ndarray, rhos: np.ndarray, tolerance: float, phase_tolerance: float
) -> tuple[np.ndarray, list[np.ndarray], np.ndarray, np.ndarray]:
    """Mean modulus, domain and polarity of lines, from the edges that support them.

    Parameters
    ----------
    points : EdgePoints
        Edge pixels, moduli and folded phases.
    alphas, rhos : numpy.ndarray
        The lines, in the module's normal parametrisation.
    tolerance : float
        Largest distance in px of a voter from its line.
    phase_tolerance : float
        Largest angle in rad between a voter's folded phase and the line's normal.

    Returns
    -------
    modulus : numpy.ndarray
        Mean modulus ``M`` of each line's voters, 0 for a line without voters.
    domains : list of numpy.ndarray
        Each line's ``bool`` domain over rows (length ``H``) or columns (``W``).
    by_rows : numpy.ndarray
        ``bool``: which lines have row domains (``|alpha| <= pi/4``).
    polarity : numpy.ndarray
        ``int``: the sign of the sum of the voters' :attr:`EdgePoints.step`
        (whether the grey level rises or falls across the line along its
        normal), 0 without voters.

    References
    ----------
    seeds/004, section IV, items 2) and 3) and Fig. 7(b).
    """
    alphas = np.asarray(alphas, dtype=np.float64).reshape(-1)
    width, height = points.size
    by_rows = np.abs(fold(alphas)) <= math.pi / 4 + 1e-12
    modulus = np.zeros(alphas.size)
    polarity = np.zeros(alphas.size, dtype=int)
    domains = []
    for i, near in enumerate(supporters(points, alphas, rhos, tolerance, phase_tolerance)):
        if near.size:
            modulus[i] = points.modulus[near].sum() / near.size
            polarity[i] = int(np.sign(points.step[near].sum()))
        domain = np.zeros(height if by_rows[i] else width, dtype=bool)
        domain[points.v[near] if by_rows[i] else points.u[near]] = True
        domains.append(domain)
    return modulus, domains, by_rows, polarity


def _distinct(alphas: np.ndarray, rhos: np.ndarray, alpha_reach: float, rho_reach: float) -> list[int]:
    """Indices of the lines (strongest first) not within reach of an earlier kept line.

    Two lines are within reach when their angles differ by at most
    ``alpha_reach`` and their distances by at most ``rho_reach``, modulo a
    half turn: the angle difference is folded as :func:`fold_angle` does
    (numba's float ``%`` rounds as Python's), and folding it by a half turn
    flips the other line's ``rho``.
    """
    alphas = np.ascontiguousarray(alphas, dtype=np.float64).reshape(-1)
    rhos = np.ascontiguousarray(rhos, dtype=np.float64).reshape(-1)
    return _distinct_kernel(alphas, rhos, float(alpha_reach), float(rho_reach)).tolist()


@numba.njit(cache=True, nogil=True)
def _distinct_kernel(alphas: np.ndarray, rhos: np.ndarray, alpha_reach: float, rho_reach: float) -> np.ndarray:
    """:func:`_distinct` as an array of indices."""
    quarter_turn = math.pi / 2
    kept = np.empty(alphas.size, np.int64)
    count = 0
    for i in range(alphas.size):
        distinct = True
        for c in range(count):
            k = kept[c]
            difference = alphas[i] - alphas[k]
            turn = (difference + quarter_turn) % math.pi - quarter_turn
            other_rho = -rhos[k] if abs(difference - turn) > quarter_turn else rhos[k]
            if abs(turn) <= alpha_reach and abs(rhos[i] - other_rho) <= rho_reach:
                distinct = False
                break
        if distinct:
            kept[count] = i
            count += 1
    return kept[:count]


def hough_lines(
    edges: EdgeMap,
    *,
    alpha_step: float,
    rho_step: float,
    phase_tolerance: float,
    min_votes: int,
    neighbourhood: int,
    tolerance: float,
) -> list[HoughLine]:
    """The straight lines of an edge map, each with its modulus and domain.

    Parameters
    ----------
    edges : EdgeMap
        Canny edges (:func:`trackbench_foresti.edges.canny_edges`).
    alpha_step, rho_step : float
        Accumulator resolution in rad and px.
    phase_tolerance : float
        Half-width in rad of the angles an edge votes for, and of the phase
        agreement of an edge with a line it supports.
    min_votes : int
        Smallest vote count of a line, over a 2 x 2 block of bins.
    neighbourhood : int
        Half-size in bins of the non-maximum suppression window.
    tolerance : float
        Largest distance in px of a voter from its line (domain tolerance).

    Returns
    -------
    list of HoughLine
        Most votes first.

    References
    ----------
    seeds/004, section IV, items 1)-3) and Fig. 7.
    """
    if not tolerance >= 0:
        raise ValueError(f"tolerance must be >= 0, got {tolerance}")
    points = EdgePoints.of(edges)
    accumulator = accumulate(points, alpha_step, rho_step, phase_tolerance)
    pooled = pooled_votes(accumulator.votes)
    k, j = find_peaks(pooled, min_votes, neighbourhood)
    if k.size == 0:
        return []
    # A pooled block's line sits at the corner its four bins share.
    alphas = fold(accumulator.alphas[k] + alpha_step / 2.0)
    rhos = accumulator.rhos[j] + rho_step / 2.0
    width, height = points.size
    stray = 0.5 * math.hypot(width, height) * math.sin(alpha_step / 2.0) + rho_step / 2.0
    alphas, rhos = refine_lines(points, alphas, rhos, tolerance + stray, phase_tolerance)
    kept = _distinct(alphas, rhos, neighbourhood * alpha_step, neighbourhood * rho_step)
    modulus, domains, by_rows, polarity = line_support(points, alphas[kept], rhos[kept], tolerance, phase_tolerance)
    votes = pooled[k[kept], j[kept]]
    lines = zip(alphas[kept], rhos[kept], votes, modulus, domains, by_rows, polarity, strict=True)
    return [
        HoughLine(float(a), float(r), int(n), float(m), dom, bool(rows), int(sign))
        for a, r, n, m, dom, rows, sign in lines
    ]


def compile_kernels() -> None:
    """Compile (or load from numba's cache) the transform's kernels now, on one edge."""
    one, index = np.zeros(1), np.zeros(1, np.int64)
    _vote(index, one, one, one, one, index, 1, 1.0, np.zeros(1, np.int32))
    _dominant(np.zeros((1, 1), np.int32), index, index, 1, 2.0)
    _near(one, one, one, 0.0, 1.0, 0.0, 0.0, 1.0, 0.1)
    _distinct_kernel(one, one, 0.1, 1.0)
