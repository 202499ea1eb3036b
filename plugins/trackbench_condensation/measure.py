"""The hot loop of the observation model: projected borders, sample points, filter responses.

For every particle ``(d, alpha, w, beta, ...)`` the two hypothetical cable
borders are projected on the image (seeds/000, section 4.5, Fig. 4.6) with
the cable model of conventions.md section 1: with ``n = (cos alpha, sin
alpha)`` and ``t = (-sin alpha, cos alpha)``, the left border passes through
``(d - w/2) n`` with direction ``R(-beta) t``, the right one through
``(d + w/2) n`` with direction ``R(+beta) t``, in model coordinates (``x``
right, ``y`` up, origin at the image centre); pixels are ``u = x + (W-1)/2``
and ``v = (H-1)/2 - y``.

Sample points.  Along each border, points lie every ``spacing`` px on a grid
anchored at the border's point nearest to the image centre (``s = k
spacing`` for integer ``k``), so that a small move of a particle adds or
drops points only at the ends of the border rather than shifting all of
them.  A point is used when the whole filter window around it lies inside
the image: the point is at least ``r`` px (the filter's half size) from
every image edge.  A border that misses this inner rectangle has no points
and scores 0.

Filter orientation.  Each border's filter runs along the border's unit
normal ``m = R(-+beta) n``, the one that points from left to right across
the cable, for both borders.  For the left border ``m`` points inside, to
the centreline; for the right border it points outside.  With the taps of
:mod:`trackbench_condensation.kernel` (positive when the image is brighter
behind ``m`` than ahead) a dark cable on bright ground gives the left border
a positive and the right border a negative score, a bright cable the
reverse, exactly the sign pattern eq. (4.11) asks of the two border counts
``c_l`` and ``c_r``.  Each score is the sum of the filter responses of the
border's sample points (section 4.5).

Reading the image.  By default each sample point is rounded to its nearest
pixel, and the taps are read at the pixels ``round(x m)`` from it, a digital
normal shared by all the points of a border: every tap is within one pixel
of its exact position in each coordinate, the filter's own smoothing (sigma ~ 1.6 px) makes
that matter little at the accuracy the detection rule asks (5 px, 3 deg),
and the read costs one memory access per tap.  ``bilinear`` reads every tap
at its exact position instead, four pixels per tap, for comparison.

The functions are compiled with numba (``cache=True``) and loop over
particles x borders x sample points x taps; the image may be ``uint8`` or
``float32``.  :func:`particle_weights` is the observation model's whole
measurement in one pass; :func:`border_scores` and :func:`centre_contrast`
are its parts; :func:`line_scores` and :func:`best_pairs` serve the
re-detection of :mod:`trackbench_condensation.detect`, and
:func:`compass_ascent` its local ascent of eq. (4.11), every round of it in
compiled code.
"""

from __future__ import annotations

import math

import numba
import numpy as np

_PARALLEL_EPS = 1e-12


@numba.njit(cache=True, nogil=True, inline="always")
def _finite_state(states: np.ndarray, i: int) -> bool:
    """Whether the cable part ``(d, alpha, w, beta)`` of particle ``i`` is finite."""
    return (
        math.isfinite(states[i, 0])
        and math.isfinite(states[i, 1])
        and math.isfinite(states[i, 2])
        and math.isfinite(states[i, 3])
    )


@numba.njit(cache=True, nogil=True, inline="always")
def _sample_range(
    u0: float, v0: float, du: float, dv: float, lo: float, hi_u: float, hi_v: float, spacing: float
) -> tuple[int, int]:
    """Integer ``k`` range of the points ``(u0, v0) + k spacing (du, dv)`` inside ``[lo, hi_u] x [lo, hi_v]``."""
    s_lo = -math.inf
    s_hi = math.inf
    if abs(du) < _PARALLEL_EPS:
        if u0 < lo or u0 > hi_u:
            return 0, -1
    else:
        a = (lo - u0) / du
        b = (hi_u - u0) / du
        s_lo = max(s_lo, min(a, b))
        s_hi = min(s_hi, max(a, b))
    if abs(dv) < _PARALLEL_EPS:
        if v0 < lo or v0 > hi_v:
            return 0, -1
    else:
        a = (lo - v0) / dv
        b = (hi_v - v0) / dv
        s_lo = max(s_lo, min(a, b))
        s_hi = min(s_hi, max(a, b))
    if not s_lo <= s_hi:
        return 0, -1
    return int(math.ceil(s_lo / spacing)), int(math.floor(s_hi / spacing))


@numba.njit(cache=True, nogil=True, inline="always")
def _border(
    d: float, w: float, side: int, nx: float, ny: float, cb: float, sb: float, cu: float, cv: float
) -> tuple[float, float, float, float, float, float]:
    """One border in pixels: its point nearest the image centre, direction and normal.

    ``side`` is -1 for the left and +1 for the right border; ``(nx, ny)`` is
    ``(cos alpha, sin alpha)`` and ``(cb, sb)`` is ``(cos beta, sin beta)``.
    Returns ``(u0, v0, du, dv, mu, mv)``; ``(mu, mv)`` is the left-to-right
    normal.
    """
    tx = -ny
    ty = nx
    sbs = side * sb
    dx = cb * tx - sbs * ty
    dy = sbs * tx + cb * ty
    offset = d + side * 0.5 * w
    px = offset * nx
    py = offset * ny
    along = px * dx + py * dy
    fx = px - along * dx
    fy = py - along * dy
    # Model (x, y) -> pixel (x + cu, cv - y): directions flip their y; the
    # model normal (dy, -dx) becomes (dy, dx).
    return fx + cu, cv - fy, dx, -dy, dy, dx


@numba.njit(cache=True, nogil=True, inline="always")
def _read(image: np.ndarray, u: float, v: float, bilinear: bool) -> float:
    """Grey level at pixel ``(u, v)``, which must lie in ``[0, W-1] x [0, H-1]``."""
    if not bilinear:
        return float(image[int(v + 0.5), int(u + 0.5)])
    height, width = image.shape
    i0 = min(max(int(v), 0), height - 1)
    j0 = min(max(int(u), 0), width - 1)
    i1 = min(i0 + 1, height - 1)
    j1 = min(j0 + 1, width - 1)
    fv = v - i0
    fu = u - j0
    top = (1.0 - fu) * image[i0, j0] + fu * image[i0, j1]
    bottom = (1.0 - fu) * image[i1, j0] + fu * image[i1, j1]
    return (1.0 - fv) * top + fv * bottom


@numba.njit(cache=True, nogil=True, inline="always")
def _bases(width: int, height: int, spacing: float) -> np.ndarray:
    """A buffer for the flat pixel indices of the sample points of one line."""
    return np.empty(int(math.hypot(width, height) / spacing) + 3, dtype=np.uint64)


@numba.njit(cache=True, nogil=True, inline="always")
def _line_sum(
    flat: np.ndarray,
    width: int,
    u0: float,
    v0: float,
    du: float,
    dv: float,
    mu: float,
    mv: float,
    k0: int,
    k1: int,
    spacing: float,
    lo: float,
    hi_u: float,
    hi_v: float,
    half: np.ndarray,
    bases: np.ndarray,
) -> float:
    """Summed filter responses at the sample points ``k0..k1`` of one line, nearest-pixel reads.

    The taps are odd, tap ``-x`` is minus tap ``+x`` and the centre tap is 0,
    so the sum is ``sum_x f(-x) sum_k (I(p_k - x m) - I(p_k + x m))``: for
    each offset ``x`` the grey-level differences of all points are added up
    exactly (in integers for an integer image) and weighted once.
    """
    radius = half.shape[0] - 1
    row = np.uint64(width)
    count = 0
    for k in range(k0, k1 + 1):
        s = k * spacing
        u = min(max(u0 + s * du, lo), hi_u)
        v = min(max(v0 + s * dv, lo), hi_v)
        bases[count] = np.uint64(v + 0.5) * row + np.uint64(u + 0.5)
        count += 1
    total = 0.0
    for x in range(1, radius + 1):
        # Unsigned offsets wrap modulo 2**64, so base - o and base + o are
        # exact; unsigned indices also skip numba's negative-index test.
        offset = np.uint64(np.int64(round(x * mv)) * width + np.int64(round(x * mu)))
        acc = flat[0] * 0
        for j in range(count):
            acc += flat[bases[j] - offset]
            acc -= flat[bases[j] + offset]
        total += half[x] * acc
    return total


@numba.njit(cache=True, nogil=True)
def border_scores(
    states: np.ndarray, image: np.ndarray, taps: np.ndarray, spacing: float, bilinear: bool
) -> tuple[np.ndarray, np.ndarray]:
    """Border counts ``c_l``, ``c_r`` of every particle (seeds/000, section 4.5).

    Parameters
    ----------
    states : numpy.ndarray
        ``(N, D)`` particle states, ``D >= 4``, the first four columns
        ``(d, alpha, w, beta)`` in px and rad.
    image : numpy.ndarray
        C-contiguous grey image ``(H, W)``, ``uint8`` or ``float32``.
    taps : numpy.ndarray
        Odd number of filter taps, odd-symmetric
        (:func:`trackbench_condensation.kernel.dog_taps`).
    spacing : float
        Distance between sample points along a border, px (> 0).
    bilinear : bool
        Read every tap bilinearly at its exact position instead of on the
        digital normal through the nearest pixel.

    Returns
    -------
    scores : numpy.ndarray
        ``(N, 2)``: the summed filter responses of the left and right border.
    counts : numpy.ndarray
        ``(N, 2)`` int: the number of sample points of each border.

    References
    ----------
    seeds/000, section 4.5, eq. (4.10), Figs. 4.6-4.7.
    """
    n = states.shape[0]
    height, width = image.shape
    radius = (taps.shape[0] - 1) // 2
    cu = 0.5 * (width - 1)
    cv = 0.5 * (height - 1)
    lo = float(radius)
    hi_u = width - 1.0 - radius
    hi_v = height - 1.0 - radius
    scores = np.zeros((n, 2))
    counts = np.zeros((n, 2), dtype=np.int64)
    flat = image.ravel()
    half = np.empty(radius + 1)
    for x in range(1, radius + 1):
        half[x] = taps[radius - x]
    bases = _bases(width, height, spacing)
    for i in range(n):
        if not _finite_state(states, i):
            continue
        d, alpha, w, beta = states[i, 0], states[i, 1], states[i, 2], states[i, 3]
        nx = math.cos(alpha)
        ny = math.sin(alpha)
        cb = math.cos(beta)
        sb = math.sin(beta)
        for column in range(2):
            u0, v0, du, dv, mu, mv = _border(d, w, 2 * column - 1, nx, ny, cb, sb, cu, cv)
            k0, k1 = _sample_range(u0, v0, du, dv, lo, hi_u, hi_v, spacing)
            if k1 < k0:
                continue
            if bilinear:
                total = 0.0
                for k in range(k0, k1 + 1):
                    s = k * spacing
                    u = min(max(u0 + s * du, lo), hi_u)
                    v = min(max(v0 + s * dv, lo), hi_v)
                    for x in range(1, radius + 1):
                        behind = _read(image, u - x * mu, v - x * mv, True)
                        ahead = _read(image, u + x * mu, v + x * mv, True)
                        total += half[x] * (behind - ahead)
            else:
                total = _line_sum(
                    flat, width, u0, v0, du, dv, mu, mv, k0, k1, spacing, lo, hi_u, hi_v, half, bases
                )
            scores[i, column] = total
            counts[i, column] = k1 - k0 + 1
    return scores, counts


@numba.njit(cache=True, nogil=True)
def centre_contrast(states: np.ndarray, image: np.ndarray, spacing: float, bilinear: bool) -> np.ndarray:
    """Summed centre-minus-flank grey-level contrast along each particle's centreline.

    Along the centreline, from its foot point ``c0 = d n`` and every
    ``spacing`` px (the grid of the border points), a point ``c`` at distance
    ``s`` along ``t`` has the local half width ``h = w/2 - s tan(beta)``
    (the borders converge towards ``+t``).  Its contrast is

        I(c) - (I(c - (h/2) n) + I(c + (h/2) n)) / 2,

    the grey level on the centreline minus the mean of the two points half
    way to the borders, all three inside the cable.  Points with ``h < 2``
    px or any of the three reads outside the image are skipped.

    Parameters
    ----------
    states : numpy.ndarray
        ``(N, D)`` particle states, ``D >= 4``.
    image : numpy.ndarray
        Grey image ``(H, W)``, ``uint8`` or ``float32``.
    spacing : float
        Distance between points along the centreline, px.
    bilinear : bool
        Read the image bilinearly instead of at the nearest pixel.

    Returns
    -------
    numpy.ndarray
        ``(N,)`` sums of the contrasts, grey levels.

    References
    ----------
    seeds/000, section 6.1 (observation model): "the cable's center is
    mostly brighter than the rest of the cable".
    """
    n = states.shape[0]
    height, width = image.shape
    cu = 0.5 * (width - 1)
    cv = 0.5 * (height - 1)
    hi_u = width - 1.0
    hi_v = height - 1.0
    out = np.zeros(n)
    for i in range(n):
        if not _finite_state(states, i):
            continue
        d, alpha, w, beta = states[i, 0], states[i, 1], states[i, 2], states[i, 3]
        nx = math.cos(alpha)
        ny = math.sin(alpha)
        # Centreline in pixels: foot point, direction t and normal n, y flipped.
        u0 = d * nx + cu
        v0 = cv - d * ny
        du = -ny
        dv = -nx
        mu = nx
        mv = -ny
        slope = math.tan(beta)
        k0, k1 = _sample_range(u0, v0, du, dv, 0.0, hi_u, hi_v, spacing)
        total = 0.0
        for k in range(k0, k1 + 1):
            s = k * spacing
            quarter = 0.25 * w - 0.5 * s * slope
            if quarter < 1.0:
                continue
            u = u0 + s * du
            v = v0 + s * dv
            ua = u - quarter * mu
            va = v - quarter * mv
            ub = u + quarter * mu
            vb = v + quarter * mv
            if not (0.0 <= ua <= hi_u and 0.0 <= va <= hi_v and 0.0 <= ub <= hi_u and 0.0 <= vb <= hi_v):
                continue
            u = min(max(u, 0.0), hi_u)
            v = min(max(v, 0.0), hi_v)
            flanks = _read(image, ua, va, bilinear) + _read(image, ub, vb, bilinear)
            total += _read(image, u, v, bilinear) - 0.5 * flanks
        out[i] = total
    return out


@numba.njit(cache=True, nogil=True)
def line_scores(
    image: np.ndarray, taps: np.ndarray, spacing: float, alphas: np.ndarray, lines: np.ndarray
) -> np.ndarray:
    """Filter responses summed along a grid of straight lines ``{p : p . n(alpha) = o}``.

    Each line is scored as one border of :func:`border_scores` is (same
    sample points, filter along ``n = (cos alpha, sin alpha)``, nearest-pixel
    digital normal): positive when the image is brighter on the ``-n`` side.

    Parameters
    ----------
    image : numpy.ndarray
        C-contiguous grey image ``(H, W)``, ``uint8`` or ``float32``.
    taps : numpy.ndarray
        Odd-symmetric filter taps.
    spacing : float
        Distance between sample points along a line, px.
    alphas : numpy.ndarray
        ``(A,)`` line angles in rad (the centreline angle of the cable model).
    lines : numpy.ndarray
        ``(M,)`` signed distances ``o`` of the lines from the image centre, px.

    Returns
    -------
    numpy.ndarray
        ``(A, M)`` summed responses.

    References
    ----------
    seeds/000, section 4.5 (the border count of one line).
    """
    height, width = image.shape
    radius = (taps.shape[0] - 1) // 2
    cu = 0.5 * (width - 1)
    cv = 0.5 * (height - 1)
    lo = float(radius)
    hi_u = width - 1.0 - radius
    hi_v = height - 1.0 - radius
    flat = image.ravel()
    half = np.empty(radius + 1)
    for x in range(1, radius + 1):
        half[x] = taps[radius - x]
    bases = _bases(width, height, spacing)
    out = np.zeros((alphas.shape[0], lines.shape[0]))
    for a in range(alphas.shape[0]):
        nx = math.cos(alphas[a])
        ny = math.sin(alphas[a])
        for m in range(lines.shape[0]):
            u0, v0, du, dv, mu, mv = _border(lines[m], 0.0, 1, nx, ny, 1.0, 0.0, cu, cv)
            k0, k1 = _sample_range(u0, v0, du, dv, lo, hi_u, hi_v, spacing)
            total = 0.0
            if k1 >= k0:
                total = _line_sum(
                    flat, width, u0, v0, du, dv, mu, mv, k0, k1, spacing, lo, hi_u, hi_v, half, bases
                )
            out[a, m] = total
    return out


@numba.njit(cache=True, nogil=True)
def border_line_scores(
    image: np.ndarray,
    taps: np.ndarray,
    spacing: float,
    alpha_left: float,
    alpha_right: float,
    line_left: float,
    line_right: float,
) -> tuple[float, float]:
    """The :func:`line_scores` of two single lines, a cable's left and right border, in one call.

    Parameters
    ----------
    image, taps, spacing
        As for :func:`line_scores`.
    alpha_left, alpha_right : float
        Angles of the borders' normals, rad (``alpha -+ beta``).
    line_left, line_right : float
        Their signed distances from the image centre, px.

    Returns
    -------
    tuple of float
        The left and the right border's summed responses, ``c_l`` and ``c_r``.

    References
    ----------
    seeds/000, section 4.5, eq. (4.11).
    """
    alphas = np.empty(1)
    lines = np.empty(1)
    alphas[0] = alpha_left
    lines[0] = line_left
    left = line_scores(image, taps, spacing, alphas, lines)[0, 0]
    alphas[0] = alpha_right
    lines[0] = line_right
    right = line_scores(image, taps, spacing, alphas, lines)[0, 0]
    return left, right


@numba.njit(cache=True, nogil=True)
def best_pairs(
    scores: np.ndarray, offsets: np.ndarray, min_width: float, max_width: float, keep: int
) -> tuple[np.ndarray, np.ndarray]:
    """The strongest pairs of lines of one angle whose responses have opposite signs.

    For each row of ``scores`` (one angle) the local extrema of the
    responses over the offsets are paired, left line first, when their
    signs are opposite (eq. 4.11's test) and their distance lies in
    ``[min_width, max_width]``; a pair scores ``|c_left| + |c_right|``.

    Parameters
    ----------
    scores : numpy.ndarray
        ``(A, M)`` line responses (:func:`line_scores`).
    offsets : numpy.ndarray
        ``(M,)`` increasing line offsets, px.
    min_width, max_width : float
        Range of the distance between the two lines, px.
    keep : int
        Number of pairs returned per angle, at most.

    Returns
    -------
    pairs : numpy.ndarray
        ``(P, 3)`` int rows ``(angle index, left offset index, right offset index)``,
        strongest first within each angle.
    values : numpy.ndarray
        ``(P,)`` pair scores.

    References
    ----------
    seeds/000, eq. (4.11).
    """
    n_angles, n_offsets = scores.shape
    rows = np.zeros((n_angles * keep, 3), dtype=np.int64)
    values = np.full(n_angles * keep, -1.0)
    # The local maxima (positive) and minima (negative) in ascending offset: a pair
    # takes one of each, so each left extremum runs only over those of the other sign.
    extrema = np.empty((2, n_offsets), dtype=np.int64)
    counts = np.zeros(2, dtype=np.int64)
    for a in range(n_angles):
        c = scores[a]
        counts[:] = 0
        for m in range(n_offsets):
            here = c[m]
            before = c[m - 1] if m > 0 else 0.0
            after = c[m + 1] if m + 1 < n_offsets else 0.0
            if (here > 0 and here >= before and here >= after) or (here < 0 and here <= before and here <= after):
                sign = 0 if here > 0 else 1
                extrema[sign, counts[sign]] = m
                counts[sign] += 1
        base = a * keep
        # For each left extremum, in ascending offset, the first opposite one to its right.
        first_right = np.zeros(2, dtype=np.int64)
        taken = np.zeros(2, dtype=np.int64)
        for _ in range(counts[0] + counts[1]):
            # The next left extremum is the lower offset of the two signs' next ones.
            if taken[0] < counts[0] and (taken[1] >= counts[1] or extrema[0, taken[0]] < extrema[1, taken[1]]):
                sign = 0
            else:
                sign = 1
            left = extrema[sign, taken[sign]]
            taken[sign] += 1
            other = 1 - sign
            while first_right[other] < counts[other] and extrema[other, first_right[other]] < left:
                first_right[other] += 1
            for j in range(first_right[other], counts[other]):
                right = extrema[other, j]
                gap = offsets[right] - offsets[left]
                if gap < min_width:
                    continue
                if gap > max_width:
                    break
                if c[left] * c[right] >= 0:
                    continue
                value = abs(c[left]) + abs(c[right])
                # Insert into this angle's sorted list of the best ``keep``.
                if value <= values[base + keep - 1]:
                    continue
                slot = keep - 1
                while slot > 0 and values[base + slot - 1] < value:
                    values[base + slot] = values[base + slot - 1]
                    rows[base + slot] = rows[base + slot - 1]
                    slot -= 1
                values[base + slot] = value
                rows[base + slot, 0] = a
                rows[base + slot, 1] = left
                rows[base + slot, 2] = right
    found = values > 0
    return rows[found], values[found]


@numba.njit(cache=True, nogil=True)
def particle_weights(
    states: np.ndarray,
    image: np.ndarray,
    taps: np.ndarray,
    spacing: float,
    bilinear: bool,
    epsilon: float,
    centre_weight: float,
    exponent: float,
) -> np.ndarray:
    """Eq. (4.11) weights of every particle in one compiled pass, optionally powered.

    Parameters
    ----------
    states, image, taps, spacing, bilinear
        As for :func:`border_scores`.
    epsilon : float
        Weight of a particle whose border counts do not have strictly
        opposite signs, or whose width is not positive.
    centre_weight : float
        ``lambda`` of the brighter-centre term (:func:`centre_contrast`); 0: off.
    exponent : float
        Power the weights are raised to.

    Returns
    -------
    numpy.ndarray
        ``(N,)`` weights ``max(pi', epsilon) ** exponent`` with
        ``pi' = |c_l - c_r| + lambda max(0, C)`` for accepted particles.

    References
    ----------
    seeds/000, eq. (4.11); section 6.1 (brighter centre).
    """
    n = states.shape[0]
    scores, _ = border_scores(states, image, taps, spacing, bilinear)
    if centre_weight > 0:
        centre = centre_contrast(states, image, spacing, bilinear)
    else:
        centre = np.zeros(n)
    out = np.empty(n)
    for i in range(n):
        left = scores[i, 0]
        right = scores[i, 1]
        value = epsilon
        if states[i, 2] > 0 and ((left > 0 and right < 0) or (left < 0 and right > 0)):
            value = max(abs(left - right) + centre_weight * max(centre[i], 0.0), epsilon)
        out[i] = value if exponent == 1.0 else value**exponent
    return out


@numba.njit(cache=True, nogil=True, inline="always")
def _clip(value: float, low: float, high: float) -> float:
    """``value`` clipped to ``[low, high]`` as ``numpy.clip`` does it.

    The larger of value and low, then the smaller of that and high, written
    out so that a ``-0.0`` at a bound of ``0.0`` becomes the bound, as there.
    """
    above = value if value > low else low
    return above if above < high else high


@numba.njit(cache=True, nogil=True)
def compass_ascent(
    states: np.ndarray,
    image: np.ndarray,
    taps: np.ndarray,
    spacing: float,
    bilinear: bool,
    epsilon: float,
    centre_weight: float,
    low: np.ndarray,
    high: np.ndarray,
    first_steps: np.ndarray,
    smallest: float,
    max_rounds: int,
) -> tuple[np.ndarray, np.ndarray]:
    """A compass search of the eq. (4.11) score (:func:`particle_weights`, no exponent) from each state.

    Per state and round, the eight moves of ``+-step`` along one of ``d``,
    ``alpha``, ``w`` and ``beta`` are clipped to ``[low, high]`` and scored;
    the first best move is taken when it scores strictly higher, otherwise
    all four steps are halved.  A state stops when its ``d`` step falls
    below ``smallest`` or after ``max_rounds`` rounds.  This is
    :meth:`trackbench_condensation.detect.LocalAscent.refine` on the score of
    the observation model, the same arithmetic in the same order, so that
    both give the same states and scores bit for bit.

    Parameters
    ----------
    states : numpy.ndarray
        ``(K, 4)`` starting states ``(d, alpha, w, beta)``, px and rad.
    image, taps, spacing, bilinear, epsilon, centre_weight
        As for :func:`particle_weights`.
    low, high : numpy.ndarray
        ``(4,)`` bounds of the states.
    first_steps : numpy.ndarray
        ``(4,)`` first steps, px and rad.
    smallest : float
        The ``d`` step below which a state stops, px.
    max_rounds : int
        Upper bound on the rounds of each state.

    Returns
    -------
    states : numpy.ndarray
        ``(K, 4)`` refined states.
    scores : numpy.ndarray
        ``(K,)`` their eq. (4.11) scores.

    References
    ----------
    seeds/000, section 4.5, eq. (4.11).
    """
    count = states.shape[0]
    current = np.empty((count, 4))
    for i in range(count):
        for j in range(4):
            current[i, j] = _clip(states[i, j], low[j], high[j])
    values = particle_weights(current, image, taps, spacing, bilinear, epsilon, centre_weight, 1.0)
    moves = np.concatenate((np.eye(4), -np.eye(4)))
    trial = np.empty((moves.shape[0], 4))
    steps = np.empty(4)
    for i in range(count):
        steps[:] = first_steps
        for _ in range(max_rounds):
            if not steps[0] >= smallest:
                break
            for m in range(moves.shape[0]):
                for j in range(4):
                    trial[m, j] = _clip(current[i, j] + moves[m, j] * steps[j], low[j], high[j])
            trial_values = particle_weights(trial, image, taps, spacing, bilinear, epsilon, centre_weight, 1.0)
            best = np.argmax(trial_values)
            if trial_values[best] > values[i]:
                current[i] = trial[best]
                values[i] = trial_values[best]
            else:
                steps *= 0.5
    return current, values
