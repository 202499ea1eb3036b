"""The target filter of seeds/002: its whole model compiled, one call a frame.

Table 2's predict and update with the models of this plugin: the motion of
eqs. (5)-(6) with its known input ``B a`` and the process noise of eq. (9)
(:mod:`trackbench_stereo_ekf.motion`), the measurement ``h`` of eq. (11)
and its Jacobian ``H`` of eq. (12) (:mod:`trackbench_stereo_ekf.measurement`).
``A``, ``B a`` and ``R`` depend on the frame interval only and are made
once per interval by those modules' functions; ``h`` and ``H`` are
evaluated inside the compiled step (:mod:`trackbench_stereo_ekf.filter_kernels`),
and so is the algebra of :mod:`benchmark.filters.kalman`, whose results
it reproduces bit for bit.

Each frame's call corrects the prediction made by the previous call, then
predicts one interval ahead, so the next frame's prior (and the measurement
noise the tracker evaluates at it) is ready before that frame's call.  A
frame that comes more than one interval later is predicted again from the
belief over its own interval (:meth:`TargetFilter.predict_over`).
"""

from __future__ import annotations

import numpy as np

from benchmark.filters.kalman import Gaussian
from benchmark.lazy import lazy_module
from benchmark.modalities.stereo.model import ChaseNavigation
from trackbench_stereo_ekf.motion import control_vector, process_noise, transition_matrix

_kernels = lazy_module("trackbench_stereo_ekf.filter_kernels")
"""The compiled steps, loaded from numba's cache on a filter's creation (not on import)."""

STATE_SIZE = 4
"""``[X, Y, X_dot, Y_dot]``, eq. (5)."""
_BLOCK = STATE_SIZE + 1


def measurement_inputs(z: np.ndarray, navigation: ChaseNavigation, noise: np.ndarray) -> np.ndarray:
    """A frame's inputs of :meth:`TargetFilter.advance`: a measurement ``z`` seen from CH with noise ``Q_t``.

    Parameters
    ----------
    z : numpy.ndarray
        ``(x_v, y_v)``, m (eq. 11).
    navigation : ChaseNavigation
        CH's GPS position and heading, which ``h`` (eq. 11) and ``H`` (eq. 12) take.
    noise : numpy.ndarray
        ``Q_t``, shape ``(2, 2)``, m^2, in the camera frame.

    Returns
    -------
    numpy.ndarray
        The flat float vector the compiled step reads.
    """
    north, east = navigation.position_m
    return np.array([1.0, z[0], z[1], north, east, navigation.heading, *np.ravel(noise)], dtype=float)


NO_MEASUREMENT = np.zeros(10)
"""The inputs of a frame without a measurement: the prediction stands."""


class TargetFilter:
    """The EKF of seeds/002, Table 2, on ``[X, Y, X_dot, Y_dot]``, stepped in place by one compiled call a frame.

    Parameters
    ----------
    interval_s : float
        ``T``, the time between two frames.
    acceleration : float
        ``a``, the known input of eq. (5), m/s^2.
    sigma_a : float
        Standard deviation of the acceleration, m/s^2 (eq. 9).

    References
    ----------
    seeds/002, Table 2; eqs. (5)-(6), (9), (11) and (12).
    """

    def __init__(self, interval_s: float, acceleration: float, sigma_a: float) -> None:
        self.acceleration = float(acceleration)
        self.sigma_a = float(sigma_a)
        _kernels.compile_kernels()
        self.state = np.zeros((_kernels.ROWS, STATE_SIZE))
        self._advance = _kernels.advance
        self._predict_ahead = _kernels.predict_ahead
        self.motion = self._motion(interval_s)
        self._set_motion(self.motion)

    def _motion(self, interval_s: float) -> np.ndarray:
        """``[B a; A]`` over ``[0; R]`` for the interval ``interval_s`` (eqs. 5-6 and 9)."""
        block = np.zeros((2 * _BLOCK, STATE_SIZE))
        block[0] = control_vector(interval_s) * self.acceleration
        block[1:_BLOCK] = transition_matrix(interval_s)
        block[_BLOCK + 1 :] = process_noise(interval_s, self.sigma_a)
        return block

    def _set_motion(self, motion: np.ndarray) -> None:
        self.state[_kernels.MOTION : _kernels.NOISE + _BLOCK] = motion

    def start(self, belief: Gaussian) -> None:
        """Start from ``belief``, which is also the prior of the first frame (no prediction before it)."""
        for first in (_kernels.BELIEF, _kernels.AHEAD):
            self.state[first] = belief.mean
            self.state[first + 1 : first + _BLOCK] = belief.covariance

    def predict(self) -> None:
        """Predict the belief one interval ahead: the prior of the next frame (Table 2, lines 2-3)."""
        self._predict_ahead(self.state)

    def predict_over(self, intervals: int) -> None:
        """Predict the belief ``intervals`` frame intervals ahead, in one step of ``intervals T``."""
        if intervals == 1:
            self.predict()
            return
        T = float(self.motion[1, 2])
        self._set_motion(self._motion(intervals * T))
        try:
            self.predict()
        finally:
            self._set_motion(self.motion)

    def advance(self, inputs: np.ndarray) -> None:
        """Correct the prior with a frame's inputs, then predict the next frame's.

        ``inputs`` is :func:`measurement_inputs`, or :data:`NO_MEASUREMENT`
        for a frame without a measurement, whose prior stands.

        References
        ----------
        seeds/002, Table 2, lines 4-6, then lines 2-3 for the next frame.
        """
        self._advance(self.state, inputs)

    @property
    def mean(self) -> np.ndarray:
        """``mu_t``, a view that the next step overwrites."""
        return self.state[_kernels.BELIEF]

    @property
    def ahead_mean(self) -> np.ndarray:
        """``mu_bar`` of the next frame (a copy)."""
        return self.state[_kernels.AHEAD].copy()

    def _gaussian(self, first: int) -> Gaussian:
        return Gaussian(self.state[first].copy(), self.state[first + 1 : first + _BLOCK].copy())

    @property
    def belief(self) -> Gaussian:
        """``mu_t``, ``Sigma_t`` (copies)."""
        return self._gaussian(_kernels.BELIEF)

    @property
    def prior(self) -> Gaussian:
        """``mu_bar``, ``Sigma_bar`` that the latest measurement corrected (copies)."""
        return self._gaussian(_kernels.PRIOR)
