"""The target's motion model: nearly constant velocity in the North-East plane.

seeds/002, section 2.1, models the target boat by its state
``x = [X, Y, X_dot, Y_dot]`` (north, east, and their rates) moving with a
small constant acceleration ``a`` whose uncertainty ``sigma_a`` lets the
filter follow changes of speed (eqs. 5-6)::

    x_t = A x_(t-1) + B a + eps(R_t),    B = [T^2/2, T^2/2, T, T]^T.

The control input is applied as printed: the same ``a`` along north and
east, on positions and velocities alike, whatever the target's heading.
With Table 5's ``a = 0.003 m/s^2`` it is a bias of 0.6 mm/s per 0.2 s step
that each measurement corrects; it is kept for fidelity to eq. (5).

The process noise replaces ``a`` by ``sigma_a`` (eq. 8): per axis the noise
on ``(position, velocity)`` is ``[T^2/2, T] sigma_a``, whose covariance is
``sigma_a^2 [[T^4/4, T^3/2], [T^3/2, T^2]]``.  Eq. (9) prints ``T^(3/2)`` for
the cross terms; ``T^3/2`` is the covariance of that noise, and with
``T^(3/2)`` the matrix would not even be positive semi-definite for
``T = 0.2 s`` (``T^4/4 * T^2 < T^3``), so :func:`process_noise` uses
``T^3/2``.  The north and east axes are independent, as eq. (9) assumes.
"""

from __future__ import annotations

import numpy as np


def transition_matrix(interval_s: float) -> np.ndarray:
    """``A_t`` of eq. (6): positions advance by velocity times ``T``.

    Parameters
    ----------
    interval_s : float
        ``T``, the time between the two states.

    Returns
    -------
    numpy.ndarray
        Shape ``(4, 4)``, for the state ``[X, Y, X_dot, Y_dot]``.

    References
    ----------
    seeds/002, eqs. (5)-(6).
    """
    A = np.eye(4)
    A[0, 2] = A[1, 3] = interval_s
    return A


def control_vector(interval_s: float) -> np.ndarray:
    """``B_t`` of eq. (6), ``[T^2/2, T^2/2, T, T]``, the effect of a unit acceleration.

    Parameters
    ----------
    interval_s : float
        ``T``.

    Returns
    -------
    numpy.ndarray
        Shape ``(4,)``.

    References
    ----------
    seeds/002, eqs. (5)-(6).
    """
    half_square = interval_s**2 / 2.0
    return np.array([half_square, half_square, interval_s, interval_s])


def process_noise(interval_s: float, sigma_a: float) -> np.ndarray:
    """``R_t`` of eq. (9), with ``T^3/2`` for the position-velocity covariance.

    Parameters
    ----------
    interval_s : float
        ``T``.
    sigma_a : float
        Standard deviation of the acceleration, m/s^2 (Table 5: 0.40).

    Returns
    -------
    numpy.ndarray
        Shape ``(4, 4)``, symmetric positive semi-definite.

    References
    ----------
    seeds/002, eqs. (7)-(9).
    """
    T = interval_s
    R = np.zeros((4, 4))
    R[0, 0] = R[1, 1] = T**4 / 4.0
    R[2, 2] = R[3, 3] = T**2
    R[0, 2] = R[2, 0] = R[1, 3] = R[3, 1] = T**3 / 2.0
    return R * sigma_a**2


def propagate(state: np.ndarray, interval_s: float, acceleration: float) -> np.ndarray:
    """``A x + B a``: the mean of eq. (5) one interval later.

    Parameters
    ----------
    state : numpy.ndarray
        ``[X, Y, X_dot, Y_dot]``.
    interval_s : float
        ``T``.
    acceleration : float
        ``a``, the control input (Table 5: 0.003 m/s^2).

    Returns
    -------
    numpy.ndarray
        The predicted state.

    References
    ----------
    seeds/002, eqs. (5)-(6).
    """
    return transition_matrix(interval_s) @ state + control_vector(interval_s) * acceleration
