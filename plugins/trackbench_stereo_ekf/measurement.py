"""The measurement model: the target seen from the chase boat's camera.

The stereo camera measures the target relative to the chase boat (CH),
``z = (x_v, y_v)``, ahead and to starboard.  With CH's GPS position
``(X_ch, Y_ch)`` and heading ``psi`` (clockwise from north) the target's
North-East position is eq. (10) of seeds/002::

    [X, Y] = Rot(psi) [x_v, y_v] + [X_ch, Y_ch],   Rot = [[cos, -sin], [sin, cos]],

and the measurement model is its inverse, eq. (11)::

    h(x) = Rot(psi)^T [X - X_ch, Y - Y_ch].

``h`` is linear in the state, so its Jacobian is the rotation on the
position components and zero on the velocities::

    H = [[ cos psi, sin psi, 0, 0],
         [-sin psi, cos psi, 0, 0]]     for x = [X, Y, X_dot, Y_dot].

Eq. (12) prints the same numbers but labels its columns ``x_t, y_t, X_t,
Y_t``; derived for the state of eq. (5) the rotation block belongs to ``X``
and ``Y`` and the zeros to ``X_dot`` and ``Y_dot``, which is what
:func:`observation_jacobian` returns.
"""

from __future__ import annotations

import math

import numpy as np

from benchmark.model import ChaseNavigation


def rotation(heading: float) -> np.ndarray:
    """``Rot`` of eq. (10): camera frame (ahead, starboard) to North-East.

    Parameters
    ----------
    heading : float
        ``psi_ch``, clockwise from north, rad.

    Returns
    -------
    numpy.ndarray
        Shape ``(2, 2)``.

    References
    ----------
    seeds/002, eq. (10).
    """
    c, s = math.cos(heading), math.sin(heading)
    return np.array([[c, -s], [s, c]])


def to_north_east(relative_m: np.ndarray, navigation: ChaseNavigation) -> np.ndarray:
    """The target's North-East position from its position relative to CH, eq. (10).

    Parameters
    ----------
    relative_m : array_like
        ``(x_v, y_v)``, m.
    navigation : ChaseNavigation
        CH's GPS position and heading.

    Returns
    -------
    numpy.ndarray
        ``[X, Y]``, m.

    References
    ----------
    seeds/002, eq. (10).
    """
    return rotation(navigation.heading) @ np.asarray(relative_m, dtype=float) + np.asarray(navigation.position_m)


def observe(state: np.ndarray, navigation: ChaseNavigation) -> np.ndarray:
    """``h(x)`` of eq. (11): where the camera should see a target in state ``state``.

    Parameters
    ----------
    state : numpy.ndarray
        ``[X, Y, X_dot, Y_dot]``.
    navigation : ChaseNavigation
        CH's GPS position and heading.

    Returns
    -------
    numpy.ndarray
        ``[x_v, y_v]``, m.

    References
    ----------
    seeds/002, eq. (11).
    """
    return rotation(navigation.heading).T @ (np.asarray(state[:2], dtype=float) - np.asarray(navigation.position_m))


def observation_jacobian(navigation: ChaseNavigation) -> np.ndarray:
    """``H_t`` of eq. (12) for the state ``[X, Y, X_dot, Y_dot]``.

    Parameters
    ----------
    navigation : ChaseNavigation
        CH's heading (the position does not enter).

    Returns
    -------
    numpy.ndarray
        Shape ``(2, 4)``: ``Rot^T`` on the positions, zeros on the velocities.

    References
    ----------
    seeds/002, eqs. (4) and (12).
    """
    H = np.zeros((2, 4))
    H[:, :2] = rotation(navigation.heading).T
    return H
