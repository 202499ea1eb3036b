"""The compiled kernels of :mod:`benchmark.filters.kalman`: the matrix algebra of a predict and a correct step.

Kept apart from the public steps so that importing :mod:`benchmark.filters.kalman`
(every Kalman-filter tracker does, for :class:`~benchmark.filters.kalman.Gaussian`)
does not import numba: a plugin is listed without it, and this module is
loaded on a filter's first step.  The kernels check every shape before
they index (numba does not).
"""

from __future__ import annotations

import numba
import numpy as np
from numba.core.errors import TypingError

__all__ = ["TypingError", "correct_step", "mirror", "predict_step", "sandwich_add"]



@numba.njit(cache=True, nogil=True)
def mirror(C: np.ndarray, n: int) -> None:
    """Make the leading ``n x n`` block of ``C`` symmetric: each mirrored pair becomes its mean."""
    for i in range(n):
        for j in range(i + 1, n):
            c = 0.5 * (C[i, j] + C[j, i])
            C[i, j] = c
            C[j, i] = c


@numba.njit(cache=True, nogil=True)
def sandwich_add(G: np.ndarray, P: np.ndarray, out: np.ndarray) -> None:
    """Add ``G P G^T`` (``G`` is ``a x b``, ``P`` is ``b x b``) to the leading ``a x a`` block of ``out``."""
    a, b = G.shape
    GP = np.zeros((a, b))
    for i in range(a):
        for k in range(b):
            g = G[i, k]
            for j in range(b):
                GP[i, j] += g * P[k, j]
    for i in range(a):
        for j in range(a):
            s = 0.0
            for k in range(b):
                s += GP[i, k] * G[j, k]
            out[i, j] += s


@numba.njit(cache=True, nogil=True)
def predict_step(
    G: np.ndarray,
    x: np.ndarray,
    P: np.ndarray,
    R: np.ndarray,
    predicted: np.ndarray,
    control: np.ndarray,
    covariance: np.ndarray,
    mean: np.ndarray,
) -> None:
    """Write ``G P G^T + R`` into ``covariance`` and the predicted mean into ``mean`` (seeds/002 Table 2, lines 2-3).

    The mean is ``predicted + control``, or ``G x + control`` when
    ``predicted`` is empty (a linear model); an empty ``control`` adds
    nothing.  The caller allocates the outputs: an array made here would
    cost more to hand back to Python than the whole step of a small filter.
    """
    n = x.shape[0]
    if G.shape[0] != n or G.shape[1] != n:
        raise ValueError("the transition matrix (or Jacobian) does not match the state size")
    if R.shape[0] != n or R.shape[1] != n:
        raise ValueError("process_noise does not match the state size")
    if covariance.shape[0] != n or covariance.shape[1] != n or mean.shape[0] != n:
        raise ValueError("the output arrays do not match the state size")
    for i in range(n):
        for j in range(n):
            covariance[i, j] = R[i, j]
    sandwich_add(G, P, covariance)
    mirror(covariance, n)
    if predicted.shape[0] == 0:
        for i in range(n):
            s = 0.0
            for k in range(n):
                s += G[i, k] * x[k]
            mean[i] = s
    elif predicted.shape[0] == n:
        for i in range(n):
            mean[i] = predicted[i]
    else:
        raise ValueError("the transition function does not return a state of the belief's size")
    if control.shape[0] == n:
        for i in range(n):
            mean[i] += control[i]
    elif control.shape[0] != 0:
        raise ValueError("control does not match the state size")


@numba.njit(cache=True, nogil=True)
def correct_step(
    x: np.ndarray,
    P: np.ndarray,
    H: np.ndarray,
    Q: np.ndarray,
    z: np.ndarray,
    hx: np.ndarray,
    covariance: np.ndarray,
    mean: np.ndarray,
) -> None:
    """Write the Joseph-form covariance into ``covariance`` and the mean into ``mean`` (seeds/002 Table 2, lines 4-6).

    ``hx`` is ``h(x)``, or empty for a linear model ``h(x) = H x``.  The
    caller allocates the outputs, as for :func:`predict_step`.
    """
    n = x.shape[0]
    m = H.shape[0]
    if H.shape[1] != n:
        raise ValueError("the measurement matrix (or Jacobian) does not match the state size")
    if Q.shape[0] != m or Q.shape[1] != m:
        raise ValueError("measurement_noise does not match the measurement size")
    if z.shape[0] != m:
        raise ValueError("the measurement does not match the measurement model")
    if covariance.shape[0] != n or covariance.shape[1] != n or mean.shape[0] != n:
        raise ValueError("the output arrays do not match the state size")
    innovation = np.empty(m)
    for i in range(m):
        innovation[i] = z[i]
        if hx.shape[0] == 0:
            for k in range(n):
                innovation[i] -= H[i, k] * x[k]
        elif hx.shape[0] == m:
            innovation[i] -= hx[i]
        else:
            raise ValueError("the predicted measurement h(mean) does not match the measurement Jacobian")

    # S = H P H^T + Q = L L^T; K = P H^T S^-1, row by row: L y = (P H^T)[r], L^T K[r] = y.
    S = np.empty((m, m))
    for i in range(m):
        for j in range(m):
            S[i, j] = Q[i, j]
    sandwich_add(H, P, S)
    mirror(S, m)
    L = np.zeros((m, m))
    for j in range(m):
        d = S[j, j]
        for k in range(j):
            d -= L[j, k] * L[j, k]
        if not d > 0.0:
            raise ValueError("the innovation covariance H P H^T + measurement_noise is not positive definite")
        L[j, j] = np.sqrt(d)
        for i in range(j + 1, m):
            s = S[i, j]
            for k in range(j):
                s -= L[i, k] * L[j, k]
            L[i, j] = s / L[j, j]
    K = np.empty((n, m))
    y = np.empty(m)
    for r in range(n):
        for i in range(m):
            s = 0.0
            for k in range(n):
                s += P[r, k] * H[i, k]
            for k in range(i):
                s -= L[i, k] * y[k]
            y[i] = s / L[i, i]
        for i in range(m - 1, -1, -1):
            s = y[i]
            for k in range(i + 1, m):
                s -= L[k, i] * K[r, k]
            K[r, i] = s / L[i, i]

    # Joseph form: (I - K H) P (I - K H)^T + K Q K^T.
    I_KH = np.empty((n, n))
    for i in range(n):
        for j in range(n):
            s = 1.0 if i == j else 0.0
            for k in range(m):
                s -= K[i, k] * H[k, j]
            I_KH[i, j] = s
    for i in range(n):
        for j in range(n):
            covariance[i, j] = 0.0
    sandwich_add(I_KH, P, covariance)
    sandwich_add(K, Q, covariance)
    mirror(covariance, n)
    for i in range(n):
        s = x[i]
        for j in range(m):
            s += K[i, j] * innovation[j]
        mean[i] = s
