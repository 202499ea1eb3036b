"""The compiled steps of the target filter (:mod:`trackbench_stereo_ekf.target_filter`) on its one state array.

The state is a C-contiguous ``(ROWS, 4)`` float array of blocks at fixed
rows; a block of a Gaussian is its mean (one row) over its covariance (four
rows):

* ``BELIEF``: ``mu_t``, ``Sigma_t``, the filter's estimate;
* ``PRIOR``: ``mu_bar``, ``Sigma_bar`` that the latest update corrected;
* ``AHEAD``: the belief predicted one frame interval ahead, what the next
  frame's update corrects (Table 2, lines 2-3, done one call early);
* ``MOTION``: the known input ``B a`` over ``A`` (eqs. 5-6), ``NOISE``: an
  unused row over ``R`` (eq. 9), both for one frame interval;
* ``H`` (eq. 12), ``h(mu_bar)`` (eq. 11) and ``Q_t``, written by the update,
  and the update's temporaries.

A frame's inputs are one float vector (:data:`INPUTS`): whether it has a
measurement, ``z = (x_v, y_v)``, CH's ``(X_ch, Y_ch)`` and heading ``psi``,
and ``Q_t`` row by row.  :func:`advance` corrects ``AHEAD`` with them (or
takes it as it is, without a measurement) into ``BELIEF`` and predicts the
next ``AHEAD``: a frame's whole filter step is one compiled call.

The algebra is that of :func:`benchmark.filters.kalman.predict` and
:func:`~benchmark.filters.kalman.update` (:mod:`benchmark.filters.kalman_kernels`),
every sum in the same order, so both give the same numbers bit for bit; it
is written again here for this filter's fixed sizes (4 states, 2
measurements) on fixed rows, which the compiler unrolls: the generic
kernels, sized at run time, take five times as long for this filter.

The entry points are compiled (or loaded from numba's cache) by
:func:`compile_kernels`, which a filter calls when it is created: before the
first timed step, not when this module is imported.  A test process imports
it while it collects (Hypothesis reads every loaded module), and explicit
signatures, which compile on import, had every pytest-xdist worker compile
the same kernels at once; they made no step faster (1.35 us a frame either
way, ``trackbench speed``).
"""

from __future__ import annotations

import math

import numba
import numpy as np

N, M = 4, 2
"""``[X, Y, X_dot, Y_dot]`` (eq. 5) and ``z = [x_v, y_v]`` (eq. 11)."""
BLOCK = N + 1
"""Rows of a Gaussian block: the mean over the covariance."""
BELIEF, PRIOR, AHEAD, MOTION, NOISE = (index * BLOCK for index in range(5))
"""First rows of the blocks."""
H_ROWS = 5 * BLOCK
"""``H`` (eq. 12), ``M`` rows."""
HX_ROW, INNOVATION_ROW = H_ROWS + M, H_ROWS + M + 1
"""``h(mu_bar)`` (eq. 11) and ``z - h(mu_bar)``, in the first ``M`` columns."""
Q_ROWS, S_ROWS, L_ROWS, Y_ROW = (INNOVATION_ROW + 1 + M * index for index in range(4))
"""``Q_t``, ``S = H Sigma_bar H^T + Q_t``, its Cholesky factor ``L`` and the solve's ``y``, first ``M`` columns."""
GAIN_ROWS = Y_ROW + 1
"""``K``, ``N`` rows, first ``M`` columns."""
I_KH_ROWS, PRODUCT_ROWS = GAIN_ROWS + N, GAIN_ROWS + 2 * N
"""``I - K H`` and the product ``G P`` of a sandwich ``G P G^T``, ``N`` rows each."""
ROWS = PRODUCT_ROWS + N
"""Rows of the state array."""

HAS_MEASUREMENT, Z, CHASE_POSITION, CHASE_HEADING, NOISE_ENTRIES = 0, 1, 3, 5, 6
"""Offsets in a frame's inputs: a flag (nonzero: measured), ``z``, ``(X_ch, Y_ch)``, ``psi``, ``Q_t``."""
INPUTS = NOISE_ENTRIES + M * M
"""Length of a frame's inputs."""


@numba.njit(cache=True, nogil=True, inline="always")
def _sandwich_add(a: np.ndarray, g: int, p: int, out: int, rows: int, cols: int) -> None:
    """Add ``G P G^T`` to the block at row ``out``: ``G`` (``rows x cols``) at row ``g``, ``P`` at row ``p``.

    :func:`benchmark.filters.kalman_kernels.sandwich_add`'s sums in its
    order, on blocks of ``a``; the product ``G P`` goes to ``PRODUCT_ROWS``.
    """
    for i in range(rows):
        for j in range(cols):
            a[PRODUCT_ROWS + i, j] = 0.0
    for i in range(rows):
        for k in range(cols):
            factor = a[g + i, k]
            for j in range(cols):
                a[PRODUCT_ROWS + i, j] += factor * a[p + k, j]
    for i in range(rows):
        for j in range(rows):
            s = 0.0
            for k in range(cols):
                s += a[PRODUCT_ROWS + i, k] * a[g + j, k]
            a[out + i, j] += s


@numba.njit(cache=True, nogil=True, inline="always")
def _mirror(a: np.ndarray, first: int, n: int) -> None:
    """Make the ``n x n`` block at row ``first`` symmetric, each mirrored pair their mean."""
    for i in range(n):
        for j in range(i + 1, n):
            c = 0.5 * (a[first + i, j] + a[first + j, i])
            a[first + i, j] = c
            a[first + j, i] = c


@numba.njit(cache=True, nogil=True, inline="always")
def _predict_ahead(state: np.ndarray) -> None:
    """``AHEAD`` = ``BELIEF`` moved by ``MOTION`` with noise ``NOISE`` (eqs. 5-6, 9; Table 2, lines 2-3)."""
    for i in range(N):
        for j in range(N):
            state[AHEAD + 1 + i, j] = state[NOISE + 1 + i, j]
    _sandwich_add(state, MOTION + 1, BELIEF + 1, AHEAD + 1, N, N)
    _mirror(state, AHEAD + 1, N)
    for i in range(N):
        s = 0.0
        for k in range(N):
            s += state[MOTION + 1 + i, k] * state[BELIEF, k]
        state[AHEAD, i] = s + state[MOTION, i]


@numba.njit(cache=True, nogil=True, inline="always")
def _correct(state: np.ndarray, inputs: np.ndarray) -> None:
    """``BELIEF`` = ``PRIOR`` corrected by the frame's measurement (Table 2, lines 4-6, Joseph form)."""
    heading = inputs[CHASE_HEADING]
    c, s = math.cos(heading), math.sin(heading)
    state[H_ROWS, 0], state[H_ROWS, 1], state[H_ROWS, 2], state[H_ROWS, 3] = c, s, 0.0, 0.0
    state[H_ROWS + 1, 0], state[H_ROWS + 1, 1], state[H_ROWS + 1, 2], state[H_ROWS + 1, 3] = -s, c, 0.0, 0.0
    d_north = state[PRIOR, 0] - inputs[CHASE_POSITION]
    d_east = state[PRIOR, 1] - inputs[CHASE_POSITION + 1]
    state[HX_ROW, 0] = c * d_north + s * d_east
    state[HX_ROW, 1] = -s * d_north + c * d_east
    for i in range(M):
        state[INNOVATION_ROW, i] = inputs[Z + i] - state[HX_ROW, i]
        for j in range(M):
            state[Q_ROWS + i, j] = inputs[NOISE_ENTRIES + M * i + j]
            state[S_ROWS + i, j] = inputs[NOISE_ENTRIES + M * i + j]
            state[L_ROWS + i, j] = 0.0

    # S = H P H^T + Q = L L^T; K = P H^T S^-1, row by row: L y = (P H^T)[r], L^T K[r] = y.
    _sandwich_add(state, H_ROWS, PRIOR + 1, S_ROWS, M, N)
    _mirror(state, S_ROWS, M)
    for j in range(M):
        d = state[S_ROWS + j, j]
        for k in range(j):
            d -= state[L_ROWS + j, k] * state[L_ROWS + j, k]
        if not d > 0.0:
            raise ValueError("the innovation covariance H P H^T + measurement_noise is not positive definite")
        state[L_ROWS + j, j] = np.sqrt(d)
        for i in range(j + 1, M):
            t = state[S_ROWS + i, j]
            for k in range(j):
                t -= state[L_ROWS + i, k] * state[L_ROWS + j, k]
            state[L_ROWS + i, j] = t / state[L_ROWS + j, j]
    for r in range(N):
        for i in range(M):
            t = 0.0
            for k in range(N):
                t += state[PRIOR + 1 + r, k] * state[H_ROWS + i, k]
            for k in range(i):
                t -= state[L_ROWS + i, k] * state[Y_ROW, k]
            state[Y_ROW, i] = t / state[L_ROWS + i, i]
        for i in range(M - 1, -1, -1):
            t = state[Y_ROW, i]
            for k in range(i + 1, M):
                t -= state[L_ROWS + k, i] * state[GAIN_ROWS + r, k]
            state[GAIN_ROWS + r, i] = t / state[L_ROWS + i, i]

    # Joseph form: (I - K H) P (I - K H)^T + K Q K^T.
    for i in range(N):
        for j in range(N):
            t = 1.0 if i == j else 0.0
            for k in range(M):
                t -= state[GAIN_ROWS + i, k] * state[H_ROWS + k, j]
            state[I_KH_ROWS + i, j] = t
            state[BELIEF + 1 + i, j] = 0.0
    _sandwich_add(state, I_KH_ROWS, PRIOR + 1, BELIEF + 1, N, N)
    _sandwich_add(state, GAIN_ROWS, Q_ROWS, BELIEF + 1, N, M)
    _mirror(state, BELIEF + 1, N)
    for i in range(N):
        t = state[PRIOR, i]
        for j in range(M):
            t += state[GAIN_ROWS + i, j] * state[INNOVATION_ROW, j]
        state[BELIEF, i] = t


@numba.njit(cache=True, nogil=True, inline="always")
def _check_state(state: np.ndarray) -> None:
    if state.shape[0] != ROWS or state.shape[1] != N:
        raise ValueError("the target filter's state array has the wrong shape")


@numba.njit(cache=True, nogil=True)
def predict_ahead(state: np.ndarray) -> None:
    """Write the prediction of ``BELIEF`` one interval of ``MOTION`` ahead into ``AHEAD``.

    References
    ----------
    seeds/002, Table 2, lines 2-3; eqs. (5)-(6) and (9).
    """
    _check_state(state)
    _predict_ahead(state)


@numba.njit(cache=True, nogil=True)
def advance(state: np.ndarray, inputs: np.ndarray) -> None:
    """One frame: ``BELIEF`` = ``AHEAD`` corrected by the frame's measurement, if any; then predict ``AHEAD``.

    With a measurement, ``AHEAD`` is kept as ``PRIOR`` and corrected with
    ``h(x) = Rot(psi)^T [X - X_ch, Y - Y_ch]`` (eq. 11) and its Jacobian
    ``H`` (eq. 12) at ``mu_bar``, and ``Q_t`` from the inputs (Table 2,
    lines 4-6, Joseph form).  Without one, ``BELIEF`` is ``AHEAD``.

    Raises
    ------
    ValueError
        If the state or the inputs have the wrong shape, or ``H Sigma_bar H^T + Q_t``
        is not positive definite (the belief is then left as it was).

    References
    ----------
    seeds/002, Table 2; eqs. (5)-(6), (9), (11) and (12).
    """
    _check_state(state)
    if inputs.shape[0] != INPUTS:
        raise ValueError("a frame's inputs of the target filter have the wrong length")
    if inputs[HAS_MEASUREMENT] == 0.0:
        for i in range(BLOCK):
            for j in range(N):
                state[BELIEF + i, j] = state[AHEAD + i, j]
    else:
        for i in range(BLOCK):
            for j in range(N):
                state[PRIOR + i, j] = state[AHEAD + i, j]
        _correct(state, inputs)
    _predict_ahead(state)


def compile_kernels() -> None:
    """Compile (or load from numba's cache) :func:`predict_ahead` and :func:`advance` now, on a zero state.

    Their argument types are those of every filter: ``float64``
    C-contiguous arrays, the state ``(ROWS, N)`` and the inputs ``(INPUTS,)``.
    """
    state = np.zeros((ROWS, N))
    predict_ahead(state)
    advance(state, np.zeros(INPUTS))
