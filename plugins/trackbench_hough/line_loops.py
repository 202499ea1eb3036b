"""The compiled loops of :mod:`trackbench_hough.lines`, :mod:`trackbench_hough.pairing` and :mod:`trackbench_hough.window`.

Kept apart so that listing the trackers does not import numba; the tracker
loads them on its first frame (:func:`compile_kernels` in ``reset``).  Each
loop computes what the Python formulation it replaces computed, operation
by operation in ``float64`` (the same ``libm`` ``cos`` and ``sin``, no
reordered or fused arithmetic), so the same bits; only the objects made
per line are gone.
"""

from __future__ import annotations

import math

import numba
import numpy as np

HALF_TURN = math.pi
QUARTER_TURN = math.pi / 2

RHO, THETA, VOTES, R, PHI = range(5)
"""Columns of the line rows the loops return: OpenCV's ``(rho, theta, votes)`` and the centred ``(r, phi)``."""


@numba.njit(cache=True, nogil=True, inline="always")
def remainder_half_turn(angle: float) -> float:
    """``math.remainder(angle, pi)`` for ``|angle| <= 2 pi``, exactly.

    The quotient ``n`` nearest ``angle / pi`` is 0 for ``|angle| <= pi / 2``
    (a tie at ``pi / 2`` goes to the even 0), else +-1 or +-2.  By
    Sterbenz's lemma ``angle -+ pi`` is exact for ``pi / 2 <= |angle| <= 2 pi``
    and ``angle -+ 2 pi`` for ``pi <= |angle| <= 4 pi``, so the candidates are
    compared exactly; the tie at ``|angle| = 3 pi / 2`` goes to the even +-2,
    as IEEE 754's remainder does, and a zero remainder has the sign of ``angle``.
    """
    if abs(angle) <= QUARTER_TURN:
        return angle
    turn = HALF_TURN if angle > 0 else -HALF_TURN
    once = angle - turn
    if abs(once) >= QUARTER_TURN:
        once = angle - 2.0 * turn
    return math.copysign(0.0, angle) if once == 0.0 else once


@numba.njit(cache=True, nogil=True, inline="always")
def distance(r: float, phi: float, other_r: float, other_phi: float) -> tuple[float, float]:
    """:meth:`trackbench_hough.lines.HoughLine.distance_to` of line ``(r, phi)`` to ``(other_r, other_phi)``."""
    dphi = phi - other_phi
    wrapped = remainder_half_turn(dphi)
    if wrapped == -QUARTER_TURN:
        wrapped = QUARTER_TURN
    if abs(dphi - wrapped) > QUARTER_TURN:
        other_r = -other_r
    return abs(r - other_r), abs(wrapped)


@numba.njit(cache=True, nogil=True)
def most_votes_first(votes: np.ndarray) -> np.ndarray:
    """Indices of ``votes``, most votes first and equal votes in their order: ``argsort(-votes, kind="stable")``.

    An insertion sort: OpenCV gives each interval's lines sorted, so the
    lines of one interval cost one pass and those of two a merge of short
    runs; it compiles in a fraction of the time of numpy's merge sort.
    """
    order = np.arange(votes.size)
    for index in range(1, votes.size):
        current = order[index]
        place = index
        while place > 0 and votes[order[place - 1]] < votes[current]:
            order[place] = order[place - 1]
            place -= 1
        order[place] = current
    return order


@numba.njit(cache=True, nogil=True)
def distinct_lines(
    raw: np.ndarray,
    cu: float,
    cv: float,
    borders: np.ndarray,
    r_half: float,
    phi_half: float,
    r_tolerance: float,
    phi_tolerance: float,
    limit: int,
) -> np.ndarray:
    """Rows ``(rho, theta, votes, r, phi)`` of the strongest lines of ``raw`` that the window admits, no two alike.

    ``raw`` holds OpenCV's ``(rho, theta, votes)``
    (:func:`trackbench_hough.lines.accumulator_maxima`), read in the order
    of :func:`most_votes_first`; ``(cu, cv)`` is the image centre in pixels.  A line is admitted when it lies within
    ``r_half`` and ``phi_half`` of one of the ``borders`` rows ``(r, phi)``
    (every line, without rows); it is kept unless a kept line lies within
    less than ``r_tolerance`` and ``phi_tolerance`` of it; the walk stops
    at ``limit`` kept lines.
    """
    order = most_votes_first(raw[:, 2])
    kept = np.empty((min(limit, raw.shape[0]), 5))
    count = 0
    for index in order:
        if count >= limit:
            break
        rho, theta = np.float64(raw[index, 0]), np.float64(raw[index, 1])
        r = rho - cu * math.cos(theta) - cv * math.sin(theta)
        phi = -theta
        if phi <= -QUARTER_TURN:
            phi, r = phi + HALF_TURN, -r
        admitted = borders.shape[0] == 0
        for border in range(borders.shape[0]):
            dr, dphi = distance(r, phi, borders[border, 0], borders[border, 1])
            if dr <= r_half and dphi <= phi_half:
                admitted = True
                break
        if not admitted:
            continue
        duplicate = False
        for other in range(count):
            dr, dphi = distance(r, phi, kept[other, R], kept[other, PHI])
            if dr < r_tolerance and dphi < phi_tolerance:
                duplicate = True
                break
        if duplicate:
            continue
        kept[count, RHO], kept[count, THETA], kept[count, VOTES] = rho, theta, np.float64(raw[index, 2])
        kept[count, R], kept[count, PHI] = r, phi
        count += 1
    return kept[:count]


@numba.njit(cache=True, nogil=True)
def near_parallel_pairs(lines: np.ndarray, anchor_votes: float, angle_limit: float) -> np.ndarray:
    """Index pairs ``(i, j)``, ``i < j`` in order, of rows of ``lines`` that pass the first two tests of a border pair.

    The stronger of the two has at least ``anchor_votes`` votes, and their
    normals differ by at most ``angle_limit``
    (:func:`trackbench_hough.pairing.compatible_pairs`).
    """
    count = lines.shape[0]
    pairs = np.empty((count * (count - 1) // 2 if count > 1 else 0, 2), np.int64)
    found = 0
    for i in range(count):
        for j in range(i + 1, count):
            if max(lines[i, VOTES], lines[j, VOTES]) < anchor_votes:
                continue
            if distance(lines[i, R], lines[i, PHI], lines[j, R], lines[j, PHI])[1] > angle_limit:
                continue
            pairs[found, 0], pairs[found, 1] = i, j
            found += 1
    return pairs[:found]


@numba.njit(cache=True, nogil=True)
def voting_strips(
    borders: np.ndarray,
    reach: float,
    width: int,
    height: int,
    strip_rows: int,
) -> np.ndarray:
    """Rows ``(row0, row1, col0, col1)`` of the strips of :meth:`trackbench_hough.window.SearchWindow.voting_strips`.

    ``borders`` holds the window's ``(r, phi)``; ``reach`` is the distance
    from a border line within which a pixel can vote for an admitted line.
    Each strip of ``strip_rows`` rows spans the columns of its first and
    last rows within ``reach`` of either border, plus one column each side.
    """
    cu, cv = (width - 1) / 2.0, (height - 1) / 2.0
    strips = np.empty(((height + strip_rows - 1) // strip_rows, 4), np.int64)
    count = 0
    for row0 in range(0, height, strip_rows):
        row1 = min(row0 + strip_rows, height)
        lowest, highest = math.inf, -math.inf
        for border in range(borders.shape[0]):
            r, phi = borders[border, 0], borders[border, 1]
            sin_phi, cos_phi = math.sin(phi), math.cos(phi)
            first, last = r - (cv - row0) * sin_phi, r - (cv - (row1 - 1)) * sin_phi
            if cos_phi > 1e-6:
                for offset in (first, last):
                    for end in ((offset + -reach) / cos_phi + cu, (offset + reach) / cos_phi + cu):
                        lowest, highest = min(lowest, end), max(highest, end)
            elif min(first, last) <= reach + 1.0 and max(first, last) >= -reach - 1.0:
                # A horizontal border: whole rows are near it.
                lowest, highest = -math.inf, math.inf
        if lowest > highest:
            continue
        col0 = max(0, math.floor(lowest) - 1) if math.isfinite(lowest) else 0
        col1 = min(width, math.ceil(highest) + 2) if math.isfinite(highest) else width
        if col0 < col1:
            strips[count, 0], strips[count, 1], strips[count, 2], strips[count, 3] = row0, row1, col0, col1
            count += 1
    return strips[:count]


def compile_kernels() -> None:
    """Compile (or load from numba's cache) the loops now, on a tiny input."""
    raw = np.array([[10.0, 0.1, 5.0], [12.0, 0.2, 6.0]], np.float32)
    lines = distinct_lines(raw, 1.0, 1.0, np.zeros((0, 2)), 1.0, 1.0, 1.0, 1.0, 2)
    near_parallel_pairs(lines, 0.0, 1.0)
    voting_strips(np.zeros((2, 2)), 1.0, 4, 4, 2)
