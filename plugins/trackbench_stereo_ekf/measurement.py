"""The measurement model: the target seen from the chase boat's camera.

The stereo camera measures the target relative to the chase boat (CH),
``z = (x_v, y_v)``, ahead and to starboard.  With CH's GPS position
``(X_ch, Y_ch)`` and heading ``psi`` (clockwise from north) the target's
North-East position is eq. (10) of seeds/002, and the measurement model is
its inverse, eq. (11)::

    h(x) = Rot(psi)^T [X - X_ch, Y - Y_ch].

Both are :mod:`benchmark.modalities.stereo.geometry` (:func:`~benchmark.modalities.stereo.geometry.to_north_east`
and :func:`~benchmark.modalities.stereo.geometry.to_camera`), shared with the
simulator.  What is the filter's own is the state they act on:
``h`` is linear in it, so its Jacobian is the rotation on the position
components and zero on the velocities::

    H = [[ cos psi, sin psi, 0, 0],
         [-sin psi, cos psi, 0, 0]]     for x = [X, Y, X_dot, Y_dot].

Eq. (12) prints the same numbers but labels its columns ``x_t, y_t, X_t,
Y_t``; derived for the state of eq. (5) the rotation block belongs to ``X``
and ``Y`` and the zeros to ``X_dot`` and ``Y_dot``, which is what
:func:`observation_jacobian` returns.
"""

from __future__ import annotations

import numpy as np

from benchmark.modalities.stereo.geometry import to_camera, to_camera_jacobian
from benchmark.modalities.stereo.model import ChaseNavigation


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
    return np.array(to_camera(float(state[0]), float(state[1]), navigation.position_m, navigation.heading))


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
    H[:, :2] = to_camera_jacobian(navigation.heading)
    return H
