"""The evidence of eq. (1) candidate by candidate, compiled: both robust fits in one pass over each window.

:class:`trackbench_sonar.evidence.FootprintLikelihood` fits the seafloor
and the pipe on that seafloor to the returns about every grid position of
a profile.  Written with NumPy arrays of shape (candidates, returns) the
fits spend most of their time on calls of BLAS and LAPACK for 3 x 3 and
4 x 4 systems, one per candidate and round of reweighting, and on the
padding that makes every window as long as the longest.  Here each
candidate is one loop over the returns of its own window: the normal
equations are summed, solved by Gaussian elimination with partial
pivoting, and the residuals reweighted, with nothing allocated but two
small buffers.

The model is the array form's; what differs is the order of the sums
(BLAS's), the solve (LAPACK's), the last bits of ``exp``, ``log1p`` and
``erfc`` (NumPy's and SciPy's SIMD loops), the residuals scaled by ``1 /
k`` rather than divided by ``k``, and the normal distribution's tails
beyond 6.5 standard deviations taken as 0 and 1.  The evidence agrees with
the array form's to ``1e-9`` of the larger of it and 1
(tests/plugins/sonar/test_sonar_evidence_kernel.py; about ``1e-13`` on the
pings of the sonar suites).

A scan read lazily (:class:`trackbench_sonar.evidence.EvidenceScan`)
bounds each candidate's evidence before it fits anything: from running
sums over the returns, the line through every window at once
(:func:`line_bounds`), then the seafloor's cost of the candidates whose
line can matter, then their pipes (:func:`evidence_maximum`,
:func:`evidence_exceeds`).  The values it fits are those of
:func:`footprint_evidence`, the same functions on the same numbers.

References
----------
seeds/003, section 2, eq. (1) and Fig. 2.
"""

from __future__ import annotations

import math

import numba
import numpy as np

_SQRT_HALF = math.sqrt(0.5)
_TAIL_CUT = 6.5
"""Beyond this ``erfc(t) / 2`` is taken as 0 (it is ``1.9e-20`` there, a share of the box nothing fitted resolves)
and ``erfc(-t) / 2`` as 1 (``1 - 1.9e-20`` rounds to 1 in double precision)."""


@numba.njit(cache=True, nogil=True)
def _smoothed_box(v: float, r: float) -> float:  # pragma: no cover - compiled
    """``Phi((v + 1) / r) - Phi((v - 1) / r)`` (:func:`trackbench_sonar.footprint.smoothed_box`)."""
    r = max(r, 1e-9)
    return _upper_tail(-(v + 1.0) / r * _SQRT_HALF) - _upper_tail(-(v - 1.0) / r * _SQRT_HALF)


@numba.njit(cache=True, nogil=True)
def _upper_tail(t: float) -> float:  # pragma: no cover - compiled
    """``erfc(t) / 2``, without calling ``erfc`` in the tails (:data:`_TAIL_CUT`)."""
    if t > _TAIL_CUT:
        return 0.0
    if t < -_TAIL_CUT:
        return 1.0
    return 0.5 * math.erfc(t)


@numba.njit(cache=True, nogil=True)
def _semicircle(
    v: float, row: int, row_share: float, table: np.ndarray, first_offset: float, offset_step: float, reach: float
) -> float:  # pragma: no cover - compiled
    """Bilinear in the table of :func:`trackbench_sonar.footprint.smoothed_semicircle`, for one offset."""
    if not abs(v) < reach:
        return 0.0
    column = min(max((v - first_offset) / offset_step, 0.0), table.shape[1] - 1.000001)
    j = int(column)
    share = column - j
    near = table[row, j] * (1.0 - share) + table[row, j + 1] * share
    far = table[row + 1, j] * (1.0 - share) + table[row + 1, j + 1] * share
    return near * (1.0 - row_share) + far * row_share


@numba.njit(cache=True, nogil=True)
def _solve(normal: np.ndarray, columns: int, coefficients: np.ndarray) -> None:  # pragma: no cover - compiled
    """Solve the normal equations (upper triangle and right-hand side in ``normal``) with a small ridge."""
    trace = 0.0
    for p in range(columns):
        trace += normal[p, p]
        for q in range(p):
            normal[p, q] = normal[q, p]
    ridge = 1e-12 * max(trace, 1.0)
    for p in range(columns):
        normal[p, p] += ridge
    # Gaussian elimination with partial pivoting on the augmented matrix.
    for p in range(columns):
        pivot = p
        for q in range(p + 1, columns):
            if abs(normal[q, p]) > abs(normal[pivot, p]):
                pivot = q
        if pivot != p:
            for c in range(columns + 1):
                normal[p, c], normal[pivot, c] = normal[pivot, c], normal[p, c]
        for q in range(p + 1, columns):
            factor = normal[q, p] / normal[p, p]
            for c in range(p, columns + 1):
                normal[q, c] -= factor * normal[p, c]
    for p in range(columns - 1, -1, -1):
        total = normal[p, columns]
        for c in range(p + 1, columns):
            total -= normal[p, c] * coefficients[c]
        coefficients[p] = total / normal[p, p]


@numba.njit(cache=True, nogil=True)
def _seabed_design(
    x: np.ndarray,
    z: np.ndarray,
    c: float,
    sigma: float,
    first: int,
    n: int,
    half_width: float,
    reach: float,
    relief_widths: float,
    design: np.ndarray,
    target: np.ndarray,
) -> bool:  # pragma: no cover - compiled
    """The seafloor's three columns and the depths of the window ``x[first:first + n]`` about ``c``.

    Returns False, filling nothing, where the window holds no return beyond the pipe's span on one side.
    """
    port = False
    starboard = False
    for j in range(n):
        u = x[first + j] - c
        port |= u <= -half_width
        starboard |= u >= half_width
    if not (port and starboard):
        return False
    relief = relief_widths * math.hypot(half_width, sigma)
    for j in range(n):
        u = x[first + j] - c
        design[0, j] = 1.0
        design[1, j] = u / reach
        design[2, j] = math.exp(-0.5 * (u / relief) ** 2)
        target[j] = z[first + j]
    return True


@numba.njit(cache=True, nogil=True)
def _pipe_design(
    x: np.ndarray,
    c: float,
    sigma: float,
    first: int,
    n: int,
    half_width: float,
    half_height: float,
    table: np.ndarray,
    first_offset: float,
    offset_step: float,
    sigma_step: float,
    table_reach: float,
    design: np.ndarray,
    target: np.ndarray,
    raised: np.ndarray,
) -> None:  # pragma: no cover - compiled
    """The pipe's span as seen (the fourth column) and the depths raised by its arc as seen."""
    r = sigma / half_width
    row_position = min(max(r / sigma_step, 0.0), table.shape[0] - 1.000001)
    row = int(row_position)
    row_share = row_position - row
    for j in range(n):
        v = (x[first + j] - c) / half_width
        design[3, j] = -_smoothed_box(v, r)
        raised[j] = target[j] + half_height * _semicircle(
            v, row, row_share, table, first_offset, offset_step, table_reach
        )


@numba.njit(cache=True, nogil=True)
def _pipe_fit(
    design: np.ndarray,
    raised: np.ndarray,
    n: int,
    floor_cost: float,
    robust_scale: float,
    noise: float,
    iterations: int,
    coefficients: np.ndarray,
    normal: np.ndarray,
) -> tuple[float, float]:  # pragma: no cover - compiled
    """The evidence ``E`` (floored at 0, 0 if not finite) and the pedestal ``s`` of a candidate whose seafloor costs ``floor_cost``."""
    pipe_cost = _fused_fit(design, raised, n, 4, robust_scale, iterations, coefficients, normal)
    height = coefficients[3]
    if not height >= 0.0:
        # s < 0 would put the pipe's centre below the seafloor: fit it resting at s = 0 instead.
        pipe_cost = _fused_fit(design, raised, n, 3, robust_scale, iterations, coefficients, normal)
        height = 0.0
    value = max((floor_cost - pipe_cost) / (noise * noise), 0.0)
    return (value if math.isfinite(value) else 0.0), height


@numba.njit(cache=True, nogil=True)
def _work(low: np.ndarray, high: np.ndarray) -> tuple:  # pragma: no cover - compiled
    """Work space for the widest window: design, target, raised, coefficients, normal equations."""
    widest = 1
    for i in range(low.size):
        widest = max(widest, high[i] - low[i])
    return np.empty((4, widest)), np.empty(widest), np.empty(widest), np.zeros(4), np.empty((4, 5))


@numba.njit(cache=True, nogil=True)
def footprint_evidence(
    x: np.ndarray,
    z: np.ndarray,
    centre: np.ndarray,
    sigma: np.ndarray,
    low: np.ndarray,
    high: np.ndarray,
    half_width: float,
    half_height: float,
    reach: float,
    relief_widths: float,
    robust_scale: float,
    noise: float,
    iterations: int,
    min_returns: int,
    table: np.ndarray,
    first_offset: float,
    offset_step: float,
    sigma_step: float,
    table_reach: float,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:  # pragma: no cover - compiled
    """Evidence, pedestal and whether scored for each candidate centre (see :mod:`trackbench_sonar.evidence`).

    Parameters
    ----------
    x, z : numpy.ndarray
        The returns, sorted by across-track position.
    centre, sigma : numpy.ndarray
        Candidate centres and the footprint's standard deviation at each, m.
    low, high : numpy.ndarray
        Each candidate's window of returns, ``x[low:high]``.
    half_width, half_height : float
        ``M_a / 2`` and ``M_i / 2``.
    reach : float
        Half-width of the window, m (scales the slope's column).
    relief_widths : float
        Width of the seafloor's mound, in half-widths of the pipe as seen.
    robust_scale, noise : float
        The Cauchy loss's scale and ``sigma_m``, m.
    iterations : int
        Rounds of reweighting.
    min_returns : int
        Fewest returns for a candidate to be scored.
    table, first_offset, offset_step, sigma_step, table_reach
        The smoothed semicircle's table and its grid.

    Returns
    -------
    evidence, pedestal : numpy.ndarray
        ``E`` floored at 0 (0 where not scored) and the fitted ``s`` (``nan`` where not scored).
    scored : numpy.ndarray
        Where the candidate was scored.
    """
    count = centre.size
    evidence = np.zeros(count)
    pedestal = np.full(count, np.nan)
    scored = np.zeros(count, dtype=np.bool_)
    design, target, raised, coefficients, normal = _work(low, high)
    for i in range(count):
        n = high[i] - low[i]
        if n < min_returns:
            continue
        if not _seabed_design(x, z, centre[i], sigma[i], low[i], n, half_width, reach, relief_widths, design, target):
            continue
        scored[i] = True
        floor_cost = _fused_fit(design, target, n, 3, robust_scale, iterations, coefficients, normal)
        _pipe_design(
            x, centre[i], sigma[i], low[i], n, half_width, half_height, table, first_offset, offset_step,
            sigma_step, table_reach, design, target, raised,
        )
        evidence[i], pedestal[i] = _pipe_fit(design, raised, n, floor_cost, robust_scale, noise, iterations, coefficients, normal)
    return evidence, pedestal, scored


UNFITTED = -1.0
"""``floor[i]`` of a candidate whose seafloor is not fitted yet (a robust cost is ``>= 0`` or ``nan``)."""
_EPS = 2.220446049250313e-16
_BOUND_SLACK = 1e-9
"""Slack of :func:`line_bounds` for the fits' ridge and rounding: relative, and in ``n (1 + a^2 + (b R)^2)`` m^2."""


@numba.njit(cache=True, nogil=True)
def _seabed_cost(
    i: int,
    x: np.ndarray,
    z: np.ndarray,
    centre: np.ndarray,
    sigma: np.ndarray,
    low: np.ndarray,
    high: np.ndarray,
    settings: np.ndarray,
    work: tuple,
) -> float:  # pragma: no cover - compiled
    """Candidate ``i``'s seafloor cost ``C_floor`` as :func:`footprint_evidence` fits it (``nan``: not scored).

    Leaves the seafloor's design and the depths of the window in ``work`` when the candidate is scored.
    """
    design, target, _, coefficients, normal = work
    n = high[i] - low[i]
    half_width, reach, relief_widths = settings[0], settings[2], settings[3]
    if n < int(settings[7]) or not _seabed_design(
        x, z, centre[i], sigma[i], low[i], n, half_width, reach, relief_widths, design, target
    ):
        return math.nan
    return _fused_fit(design, target, n, 3, settings[4], int(settings[6]), coefficients, normal)


@numba.njit(cache=True, nogil=True)
def seabed_costs(
    x: np.ndarray,
    z: np.ndarray,
    centre: np.ndarray,
    sigma: np.ndarray,
    low: np.ndarray,
    high: np.ndarray,
    settings: np.ndarray,
) -> np.ndarray:  # pragma: no cover - compiled
    """The seafloor's robust cost ``C_floor`` of every candidate, as :func:`footprint_evidence` fits it (``nan``: not scored).

    ``settings`` holds :func:`footprint_evidence`'s numbers: ``half_width, half_height, reach,
    relief_widths, robust_scale, noise, iterations, min_returns, first_offset, offset_step, sigma_step,
    table_reach``.  The cost bounds the evidence from above: ``E = max((C_floor - C_pipe) / sigma^2, 0)``
    with ``C_pipe >= 0``, and rounding is monotone, so ``E <= max(C_floor / sigma^2, 0)`` to the last bit;
    where ``C_floor`` is not finite, ``E`` is 0.
    """
    count = centre.size
    floor = np.empty(count)
    work = _work(low, high)
    for i in range(count):
        floor[i] = _seabed_cost(i, x, z, centre, sigma, low, high, settings, work)
    return floor


@numba.njit(cache=True, nogil=True)
def line_bounds(
    x: np.ndarray, z: np.ndarray, centre: np.ndarray, low: np.ndarray, high: np.ndarray, settings: np.ndarray
) -> np.ndarray:  # pragma: no cover - compiled
    """An upper bound of every candidate's evidence ``E`` from the least-squares line through its window, in O(1) each.

    The seafloor's cost bounds ``E`` (:func:`seabed_costs`), and that cost is bounded by the residual sum
    of squares of the straight line fitted to the window, which running sums over the returns give for
    every window at once:

    * the fit is iteratively reweighted least squares with the Cauchy loss ``rho(r) = k^2 log(1 + r^2 /
      k^2)``, concave in ``r^2``: each round after the first minimises a quadratic that lies above
      ``rho`` and touches it at the previous round's residuals (majorise-minimise), so the cost of the
      last round's coefficients is at most that of the first round's, the ordinary least squares fit;
    * ``rho(r) <= r^2``, so that cost is at most the fit's residual sum of squares, which is at most
      that of any other coefficients of the seafloor, among them the line ``f0 + f1 u`` (``f2 = 0``).

    The chain holds in exact arithmetic for the solves as written, without their ridge ``1e-12`` of the
    trace.  The bound adds a slack for the ridge and the rounding: :data:`_BOUND_SLACK` of the sum of
    squares and of ``n (1 + a^2 + (b R)^2)`` (the line's coefficients ``a``, ``b`` at the window's
    centre, ``R`` the window's half-width; the ridge's own share is ``3e-12 n`` of that per solve), and
    the rounding of the running sums, ``4 (N + 4) eps`` of their totals.  Where the line fits the returns
    exactly the chain has no slack of its own: there the seafloor's cost comes out at up to ``2e-17``
    m^2 above the line's sum of squares (the ridge), against a slack of ``1e-9 n (1 + a^2)``, about
    ``1e-5`` m^2 at 30 m depth (tests/plugins/sonar/test_sonar_evidence_scan.py).  Where the returns in a window
    are too few, or all on one side of the pipe's span, the candidate is not scored and its bound is 0
    (the returns are sorted, so the first and last of the window decide as :func:`_seabed_design`'s
    loop does).  Where the window's positions are all but equal the bound is the sum of squares about the
    mean (the constant's fit).

    ``settings``: as :func:`seabed_costs` takes them.  Returns the bounds of ``E`` (``C / sigma^2``).
    """
    half_width, reach, noise, min_returns = settings[0], settings[2], settings[5], int(settings[7])
    count = centre.size
    bounds = np.zeros(count)
    m = x.size
    if m == 0:
        return bounds
    x0, z0 = x[m // 2], z[m // 2]
    sx = np.zeros(m + 1)
    sz = np.zeros(m + 1)
    sxx = np.zeros(m + 1)
    sxz = np.zeros(m + 1)
    szz = np.zeros(m + 1)
    total_xz = 0.0
    for j in range(m):
        dx, dz = x[j] - x0, z[j] - z0
        sx[j + 1] = sx[j] + dx
        sz[j + 1] = sz[j] + dz
        sxx[j + 1] = sxx[j] + dx * dx
        sxz[j + 1] = sxz[j] + dx * dz
        szz[j + 1] = szz[j] + dz * dz
        total_xz += abs(dx * dz)
    rounding = 4.0 * (m + 4) * _EPS
    scale = noise * noise
    for i in range(count):
        first, last = low[i], high[i]
        n = last - first
        if n < min_returns or n < 2:
            continue
        c = centre[i]
        if not (x[first] - c <= -half_width and x[last - 1] - c >= half_width):
            continue
        mx = (sx[last] - sx[first]) / n
        mz = (sz[last] - sz[first]) / n
        cxx = max((sxx[last] - sxx[first]) - n * mx * mx, 0.0)
        cxz = (sxz[last] - sxz[first]) - n * mx * mz
        czz = max((szz[last] - szz[first]) - n * mz * mz, 0.0)
        slope = 0.0
        residual = czz
        if cxx > rounding * sxx[m]:
            slope = cxz / cxx
            residual = max(czz - slope * cxz, 0.0)
        intercept = z0 + mz + slope * (c - x0 - mx)
        error = rounding * (szz[m] + 2.0 * abs(slope) * total_xz + slope * slope * sxx[m])
        coefficients = n * (1.0 + intercept * intercept + (slope * reach) ** 2)
        bound = ((1.0 + _BOUND_SLACK) * residual + error + _BOUND_SLACK * coefficients) / scale
        bounds[i] = bound if bound >= 0.0 else math.inf
    return bounds


@numba.njit(cache=True, nogil=True)
def _fit_floor(
    i: int, data: tuple, state: tuple, settings: np.ndarray, work: tuple
) -> None:  # pragma: no cover - compiled
    """Candidate ``i``'s seafloor cost into ``floor[i]`` and its bound ``C_floor / sigma^2`` into ``key[i]``."""
    x, z, centre, sigma, low, high = data
    _, _, floor, key = state
    floor[i] = _seabed_cost(i, x, z, centre, sigma, low, high, settings, work)
    key[i] = floor[i] / (settings[5] * settings[5]) if math.isfinite(floor[i]) else 0.0


@numba.njit(cache=True, nogil=True)
def _candidate(
    i: int, data: tuple, state: tuple, settings: np.ndarray, table: np.ndarray, work: tuple
) -> None:  # pragma: no cover - compiled
    """Candidate ``i``'s ``E`` into ``values[i]`` and ``key[i]``, as :func:`footprint_evidence` gives it.

    ``data``: the returns ``x``, ``z``, the candidates' centres, footprint sigmas and windows ``low``,
    ``high``.  ``state``: ``values``, ``known``, ``floor`` (the seafloor costs, :data:`UNFITTED` where
    not fitted yet; fitted here first then) and ``key`` (each candidate's tightest upper bound of ``E``).
    """
    x, z, centre, sigma, low, high = data
    values, known, floor, key = state
    design, target, raised, coefficients, normal = work
    n = high[i] - low[i]
    half_width, half_height, reach, relief_widths = settings[0], settings[1], settings[2], settings[3]
    if floor[i] == UNFITTED:
        _fit_floor(i, data, state, settings, work)
    elif math.isfinite(floor[i]):
        _seabed_design(x, z, centre[i], sigma[i], low[i], n, half_width, reach, relief_widths, design, target)
    known[i] = True
    floor_cost = floor[i]
    if math.isfinite(floor_cost):
        _pipe_design(
            x, centre[i], sigma[i], low[i], n, half_width, half_height, table, settings[8], settings[9],
            settings[10], settings[11], design, target, raised,
        )
        values[i] = _pipe_fit(
            design, raised, n, floor_cost, settings[4], settings[5], int(settings[6]), coefficients, normal
        )[0]
    else:
        values[i] = 0.0
    key[i] = values[i]


@numba.njit(cache=True, nogil=True)
def evidence_at(
    wanted: np.ndarray, data: tuple, state: tuple, settings: np.ndarray, table: np.ndarray
) -> None:  # pragma: no cover - compiled
    """``E`` of the candidates ``wanted`` not yet ``known`` into ``values`` (``data``, ``state``: :func:`_candidate`'s)."""
    known = state[1]
    work = _work(data[4], data[5])
    for i in wanted:
        if not known[i]:
            _candidate(i, data, state, settings, table, work)


@numba.njit(cache=True, nogil=True)
def evidence_around(
    across: np.ndarray, first_position: float, spacing: float, data: tuple, state: tuple, settings: np.ndarray,
    table: np.ndarray,
) -> None:  # pragma: no cover - compiled
    """:func:`evidence_at` of the grid positions about each finite position of ``across``.

    For each, the cells ``k - 1 .. k + 2`` with ``k = floor((across - first_position) / spacing)``,
    clipped into the grid: the two cells interpolation reads lie among them whatever the rounding.
    """
    known = state[1]
    count = known.size
    work = _work(data[4], data[5])
    for a in across:
        if not math.isfinite(a):
            continue
        cell = int(math.floor(min(max((a - first_position) / spacing, -2.0), float(count))))
        for i in range(max(cell - 1, 0), min(cell + 3, count)):
            if not known[i]:
                _candidate(i, data, state, settings, table, work)


@numba.njit(cache=True, nogil=True)
def _sift_down(heap: np.ndarray, start: int, size: int, key: np.ndarray) -> None:  # pragma: no cover - compiled
    """Restore the max-heap of indices ``heap[:size]`` ordered by ``key`` below ``start``."""
    parent = start
    while True:
        child = 2 * parent + 1
        if child >= size:
            return
        if child + 1 < size and key[heap[child + 1]] > key[heap[child]]:
            child += 1
        if not key[heap[child]] > key[heap[parent]]:
            return
        heap[parent], heap[child] = heap[child], heap[parent]
        parent = child


@numba.njit(cache=True, nogil=True)
def _heap_above(key: np.ndarray, level: float) -> np.ndarray:  # pragma: no cover - compiled
    """The candidates whose bound ``key`` is above ``level``, as a max-heap."""
    heap = np.flatnonzero(key > level)
    for start in range(heap.size // 2 - 1, -1, -1):
        _sift_down(heap, start, heap.size, key)
    return heap


@numba.njit(cache=True, nogil=True)
def _settle_top(
    heap: np.ndarray, size: int, data: tuple, state: tuple, settings: np.ndarray, table: np.ndarray, work: tuple
) -> tuple[int, int]:  # pragma: no cover - compiled
    """Tighten the bound of the heap's top candidate one step: ``(i, size)`` when its ``E`` is known, ``(-1, size)`` when not.

    A top bounded by the line through its window has its seafloor fitted and is sifted down with that
    bound; one bounded by its seafloor (or by its ``E``) leaves the heap with its ``E`` computed.
    """
    values, known, floor, key = state
    i = heap[0]
    if not known[i] and floor[i] == UNFITTED:
        _fit_floor(i, data, state, settings, work)
        _sift_down(heap, 0, size, key)
        return -1, size
    size -= 1
    heap[0] = heap[size]
    _sift_down(heap, 0, size, key)
    if not known[i]:
        _candidate(i, data, state, settings, table, work)
    return i, size


@numba.njit(cache=True, nogil=True)
def evidence_maximum(
    data: tuple, state: tuple, settings: np.ndarray, table: np.ndarray
) -> int:  # pragma: no cover - compiled
    """The first candidate of largest ``E`` (-1 when every ``E`` is 0), fitting only what can decide it.

    Every candidate's ``key`` is its tightest bound so far: its ``E`` where known, else ``C_floor /
    sigma^2`` where its seafloor is fitted (0 where that cost is not finite), else :func:`line_bounds`'s.
    The candidates are taken off a max-heap of their bounds (:func:`_settle_top`): one bounded by its
    line has its seafloor fitted and goes back with that tighter bound; one bounded by its seafloor has
    its pipe fitted and its ``E`` may raise the best found.  Once the largest bound left is below the
    best ``E`` found, no candidate left can reach it.  Candidates whose bound equals the best are still
    fitted, so every candidate of largest ``E`` is known and the first of them is returned.
    """
    values, known = state[0], state[1]
    key = state[3]
    heap = _heap_above(key, 0.0)
    size = heap.size
    work = _work(data[4], data[5])
    best = 0.0
    while size > 0 and key[heap[0]] >= best:
        i, size = _settle_top(heap, size, data, state, settings, table, work)
        if i >= 0:
            best = max(best, values[i])
    if not best > 0.0:
        return -1
    for i in range(known.size):
        if known[i] and values[i] == best:
            return i
    return -1


@numba.njit(cache=True, nogil=True)
def evidence_exceeds(
    level: float, data: tuple, state: tuple, settings: np.ndarray, table: np.ndarray
) -> bool:  # pragma: no cover - compiled
    """Whether some candidate's ``E`` is above ``level``, fitting only what can decide it.

    As :func:`evidence_maximum`, with the best found fixed at ``level``: candidates are taken off the heap of
    bounds above it until one's ``E`` is above it (True) or no bound left is (False).
    """
    values, key = state[0], state[3]
    heap = _heap_above(key, level)
    size = heap.size
    work = _work(data[4], data[5])
    while size > 0 and key[heap[0]] > level:
        i, size = _settle_top(heap, size, data, state, settings, table, work)
        if i >= 0 and values[i] > level:
            return True
    return False


@numba.njit(cache=True, nogil=True)
def _fused_fit(
    design: np.ndarray,
    target: np.ndarray,
    n: int,
    columns: int,
    k: float,
    iterations: int,
    coefficients: np.ndarray,
    normal: np.ndarray,
) -> float:  # pragma: no cover - compiled
    """:func:`_robust_fit` in fewer passes over the returns, to the last bit.

    The same products summed in the same order, with the column of ones (``design[0]``, not read)
    multiplied out, which is exact, and each round's reweighting summed straight into the next round's
    normal equations.
    """
    pipe = columns == 4
    inverse = 1.0 / k
    cost = 0.0
    c0 = c1 = c2 = c3 = 0.0
    a00 = a01 = a02 = a03 = a11 = a12 = a13 = a22 = a23 = a33 = 0.0
    b0 = b1 = b2 = b3 = 0.0
    for iteration in range(iterations + 1):
        if iteration > 0:
            normal[0, 0], normal[0, 1], normal[0, 2] = a00, a01, a02
            normal[1, 1], normal[1, 2], normal[2, 2] = a11, a12, a22
            if pipe:
                normal[0, 3], normal[1, 3], normal[2, 3], normal[3, 3] = a03, a13, a23, a33
                normal[3, columns] = b3
            normal[0, columns], normal[1, columns], normal[2, columns] = b0, b1, b2
            _solve(normal, columns, coefficients)
            c0, c1, c2 = coefficients[0], coefficients[1], coefficients[2]
            c3 = coefficients[3] if pipe else 0.0
        last = iteration == iterations
        a00 = a01 = a02 = a03 = a11 = a12 = a13 = a22 = a23 = a33 = 0.0
        b0 = b1 = b2 = b3 = 0.0
        for j in range(n):
            d1, d2, t = design[1, j], design[2, j], target[j]
            w = 1.0
            if iteration > 0:
                fitted = c0 + c1 * d1 + c2 * d2
                if pipe:
                    fitted += c3 * design[3, j]
                scaled = (t - fitted) * inverse
                scaled *= scaled
                if last:
                    cost += math.log1p(scaled)
                    continue
                w = 1.0 / (1.0 + scaled)
            w1, w2 = w * d1, w * d2
            a00 += w
            a01 += w * d1
            a02 += w * d2
            a11 += w1 * d1
            a12 += w1 * d2
            a22 += w2 * d2
            b0 += w * t
            b1 += w1 * t
            b2 += w2 * t
            if pipe:
                d3 = design[3, j]
                w3 = w * d3
                a03 += w * d3
                a13 += w1 * d3
                a23 += w2 * d3
                a33 += w3 * d3
                b3 += w3 * t
    return k * k * cost


@numba.njit(cache=True, nogil=True)
def window_bounds(x: np.ndarray, centre: np.ndarray, reach: float) -> tuple[np.ndarray, np.ndarray]:  # pragma: no cover
    """``numpy.searchsorted(x, centre - reach, side="left")`` and ``numpy.searchsorted(x, centre + reach,
    side="right")``, found by walking up ``x`` (sorted) as the centres (increasing) move on."""
    count, size = centre.size, x.size
    low = np.empty(count, dtype=np.int64)
    high = np.empty(count, dtype=np.int64)
    first = last = 0
    for i in range(count):
        start, end = centre[i] - reach, centre[i] + reach
        while first < size and x[first] < start:
            first += 1
        while last < size and x[last] <= end:
            last += 1
        low[i], high[i] = first, last
    return low, high


@numba.njit(cache=True, nogil=True)
def candidate_windows(
    x: np.ndarray, centre: np.ndarray, depth: np.ndarray, reach: float, beam_width: float, fwhm_per_sigma: float
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:  # pragma: no cover - compiled
    """Each candidate's window of returns ``x[low:high]`` within ``reach`` and the footprint's sigma there.

    As :meth:`~trackbench_sonar.evidence.FootprintLikelihood.windows` gives them: :func:`window_bounds`
    (``x`` sorted and finite), and
    :func:`~trackbench_sonar.footprint.footprint_sigma`'s arithmetic, ``(c^2 + z^2) phi / z`` over
    ``fwhm_per_sigma`` (``inf`` at or above the transducer, 0 for rays).
    """
    count = centre.size
    low, high = window_bounds(x, centre, reach)
    sigma = np.zeros(count)
    if beam_width > 0.0:
        for i in range(centre.size):
            c, z = centre[i], depth[i]
            sigma[i] = ((c * c + z * z) * beam_width / z if z > 0.0 else math.inf) / fwhm_per_sigma
    return low, high, sigma
