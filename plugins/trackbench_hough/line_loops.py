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

from benchmark.modalities.camera.geometry_kernels import cable_of_borders, python_hypot

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


@numba.njit(cache=True, nogil=True, inline="always")
def model_line(rho: float, theta: float, cu: float, cv: float) -> tuple[float, float, float, float]:
    """:meth:`trackbench_hough.lines.HoughLine.line` of OpenCV's ``(rho, theta)`` as ``(x0, y0, dx, dy)``.

    The steps of :meth:`benchmark.modalities.camera.geometry.Line.from_pixels`
    from the foot of the normal and the point one pixel along the line, with
    CPython's ``hypot`` (:func:`benchmark.modalities.camera.geometry_kernels.python_hypot`).
    """
    c, s = math.cos(theta), math.sin(theta)
    foot_u, foot_v = rho * c, rho * s
    x0, y0 = foot_u - cu, cv - foot_v
    dx, dy = ((foot_u - s) - cu) - x0, (cv - (foot_v + c)) - y0
    norm = python_hypot(dx, dy)
    return x0, y0, dx / norm, dy / norm


@numba.njit(cache=True, nogil=True, inline="always")
def crossing_inside(a: np.ndarray, b: np.ndarray, cu: float, cv: float) -> bool:
    """Whether lines ``a`` and ``b`` ``(x0, y0, dx, dy)`` cross inside the image of half sizes ``(cu, cv)``."""
    det = a[2] * b[3] - a[3] * b[2]
    if abs(det) < 1e-12:
        return False
    s = ((b[0] - a[0]) * b[3] - (b[1] - a[1]) * b[2]) / det
    x, y = a[0] + s * a[2], a[1] + s * a[3]
    return abs(x) <= cu and abs(y) <= cv


@numba.njit(cache=True, nogil=True)
def border_pairs(
    lines: np.ndarray,
    cu: float,
    cv: float,
    anchor_votes: float,
    angle_limit: float,
    max_skew: float,
    max_divergence: float,
    min_width: float,
    max_width: float,
) -> tuple[np.ndarray, np.ndarray]:
    """Index pairs ``(i, j)``, ``i < j`` in order, of rows of ``lines`` that may be two cable borders, and their states.

    The tests of :func:`trackbench_hough.pairing.compatible_pairs`: the
    stronger line has at least ``anchor_votes`` votes, the normals differ by
    at most ``angle_limit``, the lines do not cross inside the image (centre
    ``(cu, cv)``), and the state ``(d, alpha, w, beta)`` they define
    (:func:`benchmark.modalities.camera.geometry_kernels.cable_of_borders`)
    has ``-max_divergence <= beta <= max_skew`` and ``min_width <= w <= max_width``.
    """
    count = lines.shape[0]
    models = np.empty((count, 4))
    for k in range(count):
        models[k, 0], models[k, 1], models[k, 2], models[k, 3] = model_line(lines[k, RHO], lines[k, THETA], cu, cv)
    most = count * (count - 1) // 2 if count > 1 else 0
    pairs = np.empty((most, 2), np.int64)
    states = np.empty((most, 4))
    found = 0
    for i in range(count):
        for j in range(i + 1, count):
            if max(lines[i, VOTES], lines[j, VOTES]) < anchor_votes:
                continue
            if distance(lines[i, R], lines[i, PHI], lines[j, R], lines[j, PHI])[1] > angle_limit:
                continue
            a, b = models[i], models[j]
            if crossing_inside(a, b, cu, cv):
                continue
            d, alpha, w, beta = cable_of_borders(a[0], a[1], a[2], a[3], b[0], b[1], b[2], b[3])
            if not (-max_divergence <= beta <= max_skew and min_width <= w <= max_width):
                continue
            pairs[found, 0], pairs[found, 1] = i, j
            states[found, 0], states[found, 1], states[found, 2], states[found, 3] = d, alpha, w, beta
            found += 1
    return pairs[:found], states[:found]


@numba.njit(cache=True, nogil=True, inline="always")
def window_fit(line: np.ndarray, border: np.ndarray, r_half: float, phi_half: float) -> tuple[bool, float, float]:
    """:meth:`trackbench_hough.window.SearchWindow.fits` of one line row to one border ``(r, phi)``: inside, and the offsets."""
    dr, dphi = distance(line[R], line[PHI], border[0], border[1])
    if dr <= r_half and dphi <= phi_half:
        return True, dr / r_half, dphi / phi_half
    return False, 0.0, 0.0


@numba.njit(cache=True, nogil=True)
def best_pair(
    lines: np.ndarray, pairs: np.ndarray, borders: np.ndarray, r_half: float, phi_half: float, closeness_weight: float
) -> int:
    """Index of the row of ``pairs`` that :func:`trackbench_hough.pairing.choose_pair` chooses, -1 for none.

    A pair scores its two lines' votes; with window ``borders`` (two rows
    ``(r, phi)``; none: no window) it must have one line in the window of
    each border, and its score is scaled by ``1 - closeness_weight * deviation``
    (:meth:`trackbench_hough.window.SearchWindow.deviation_of_fits`).  Ties go
    to the first pair.
    """
    best, best_score = -1, -math.inf
    for k in range(pairs.shape[0]):
        i, j = pairs[k, 0], pairs[k, 1]
        score = lines[i, VOTES] + lines[j, VOTES]
        if borders.shape[0] > 0:
            deviation = -1.0
            for first, second in ((i, j), (j, i)):
                inside_a, r_a, phi_a = window_fit(lines[first], borders[0], r_half, phi_half)
                inside_b, r_b, phi_b = window_fit(lines[second], borders[1], r_half, phi_half)
                if inside_a and inside_b:
                    worst = max(max(r_a, phi_a), max(r_b, phi_b))
                    deviation = worst if deviation < 0.0 else min(deviation, worst)
            if deviation < 0.0:
                continue
            score *= 1.0 - closeness_weight * deviation
        if score > best_score:
            best, best_score = k, score
    return best


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
    pairs, _ = border_pairs(lines, 1.0, 1.0, 0.0, 1.0, 1.0, 1.0, 0.0, 100.0)
    best_pair(lines, pairs, np.zeros((2, 2)), 1.0, 1.0, 0.5)
    voting_strips(np.zeros((2, 2)), 1.0, 4, 4, 2)
