"""The Kalman filter on the cable's position, orientation and width, and the region of interest it predicts.

"For tracking, Ortiz et al. propose to use a Kalman filter to estimate the
cable orientation and position as well as its width.  A region of interest
(ROI) is computed using the predicted cable parameters to limit the search
region" (seeds/000, section 2.3).  The thesis adds that "system dynamics are
not used for this prediction", so the readings made here are

* the state is ``x = (d, alpha, w)`` of the cable model (conventions.md
  section 1) and the motion model is a random walk, ``x_(t+1) = x_t +
  noise`` with diagonal process noise; the measurement is the ``(d, alpha,
  w)`` of the frame's best pair, ``z = x + noise`` with diagonal measurement
  noise (:class:`CableKalman`).  The equations are the shared core
  :mod:`benchmark.filters.kalman`;
* the ROI is the band of the image within ``w/2 + margin`` of the predicted
  centreline, where the margin is ``margin_px`` plus ``n_sigma`` standard
  deviations of a border's lateral position at the top or bottom of the
  image under the predicted covariance (:func:`region_of_interest`); it
  widens by itself while frames go without a measurement, as the
  covariance grows.
"""

from __future__ import annotations

import math

import numpy as np

from benchmark.filters.kalman import Gaussian, predict, update
from benchmark.lazy import lazy_module
from benchmark.modalities.camera.model import CableState

_IDENTITY = np.eye(3)

# The compiled mask loads with the first region of interest, so that listing the trackers does not import numba.
band = lazy_module("trackbench_segmentation.band")


class CableKalman:
    """A random-walk Kalman filter on ``(d, alpha, w)``.

    Parameters
    ----------
    process_var : tuple of float
        Variances of the frame-to-frame change of ``d`` (px^2), ``alpha``
        (rad^2) and ``w`` (px^2).
    measurement_var : tuple of float
        Variances of a measured ``d``, ``alpha`` and ``w``, same units.

    Attributes
    ----------
    belief : Gaussian or None
        The current mean and covariance; None before the first measurement
        and after :meth:`forget`.
    prior : Gaussian or None
        The prediction the latest :meth:`update` corrected, in the form of
        its result (turned with it when the corrected angle was brought back
        into range); None when there was no update since the last
        :meth:`predict`, or the update started the filter.

    References
    ----------
    seeds/000, section 2.3 (a Kalman filter on the cable parameters);
    seeds/002, Table 2 (the filter equations).
    """

    def __init__(self, process_var: tuple[float, float, float], measurement_var: tuple[float, float, float]) -> None:
        self.belief: Gaussian | None = None
        self.prior: Gaussian | None = None
        self.use_noise(process_var, measurement_var)

    def use_noise(self, process_var: tuple[float, float, float], measurement_var: tuple[float, float, float]) -> None:
        """Take these variances from now on (a frame of another size states them in other pixels)."""
        self.process_noise = np.diag(np.asarray(process_var, dtype=float))
        self.measurement_noise = np.diag(np.asarray(measurement_var, dtype=float))

    def forget(self) -> None:
        """Drop the belief: the cable is lost."""
        self.belief = None
        self.prior = None

    def start(self, state: CableState) -> None:
        """Start from one measured state with the measurement's covariance."""
        self.belief = Gaussian(np.array([state.d, state.alpha, state.w]), self.measurement_noise.copy())
        self.prior = None

    def predict(self) -> None:
        """One random-walk step: the mean stays, the covariance grows by the process noise."""
        self.prior = None
        if self.belief is not None:
            self.belief = predict(self.belief, _IDENTITY, None, self.process_noise)

    def aligned(self, state: CableState) -> np.ndarray:
        """A measured ``(d, alpha, w)`` in the form whose angle lies within a quarter turn of the belief's.

        ``(d, alpha)`` and ``(-d, alpha +- pi)`` are the same centreline.
        """
        d, alpha = state.d, state.alpha
        if self.belief is not None:
            reference = float(self.belief.mean[1])
            if abs(alpha - reference) > math.pi / 2:
                d, alpha = -d, alpha - math.copysign(math.pi, alpha - reference)
        return np.array([d, alpha, state.w])

    def distance(self, state: CableState) -> float:
        """Squared Mahalanobis distance of a measured state from the belief: ``nu^T S^-1 nu``.

        ``nu`` is the innovation, the measurement (:meth:`aligned`) less the
        belief's mean, and ``S`` its covariance, the belief's covariance plus
        the measurement noise; 0 while there is no belief.
        """
        if self.belief is None:
            return 0.0
        innovation = self.aligned(state) - self.belief.mean
        spread = self.belief.covariance + self.measurement_noise
        return float(innovation @ np.linalg.solve(spread, innovation))

    def update(self, state: CableState) -> None:
        """Correct the belief with a measured state, or start from it when there is no belief.

        The measurement is first :meth:`aligned` with the belief; a corrected
        angle that leaves ``(-pi/2, pi/2]`` is brought back the same way,
        with the covariance of ``d`` with the other two turned accordingly.
        """
        if self.belief is None:
            self.start(state)
            return
        prior = self.belief
        corrected = update(prior, self.aligned(state), _IDENTITY, None, self.measurement_noise)
        mean = corrected.mean
        if not -math.pi / 2 < mean[1] <= math.pi / 2:
            flip = np.diag([-1.0, 1.0, 1.0])
            turn = math.copysign(math.pi, mean[1])
            mean = np.array([-mean[0], mean[1] - turn, mean[2]])
            corrected = Gaussian(mean, flip @ corrected.covariance @ flip)
            turned = np.array([-prior.mean[0], prior.mean[1] - turn, prior.mean[2]])
            prior = Gaussian(turned, flip @ prior.covariance @ flip)
        self.prior, self.belief = prior, corrected


def lateral_std(covariance: np.ndarray, reach_px: float) -> float:
    """Standard deviation, px, of a border's lateral position ``reach_px`` from the image centre.

    A border lies at ``d -+ w/2`` along the normal; an angle error ``da``
    moves a point ``reach_px`` along the cable by ``reach_px da``.  The
    three are combined as independent.
    """
    return math.sqrt(max(0.0, covariance[0, 0] + 0.25 * covariance[2, 2] + reach_px**2 * covariance[1, 1]))


def region_of_interest(
    belief: Gaussian, size: tuple[int, int], margin_px: float, n_sigma: float
) -> tuple[np.ndarray, float]:
    """The band around the predicted cable where the next search runs.

    Parameters
    ----------
    belief : Gaussian
        The predicted ``(d, alpha, w)`` and its covariance.
    size : tuple of int
        Image ``(W, H)``.
    margin_px : float
        Fixed margin beyond each predicted border, px.
    n_sigma : float
        Further margin in standard deviations of a border's lateral position
        at the image's top or bottom (:func:`lateral_std`).

    Returns
    -------
    mask : numpy.ndarray
        Boolean ``(H, W)``: True inside the ROI.
    half_width : float
        Half-width of the band, px, measured along the cable's normal.

    References
    ----------
    seeds/000, section 2.3: an ROI computed from the predicted parameters.
    """
    width, height = size
    d, alpha, w = (float(value) for value in belief.mean)
    half_width = 0.5 * abs(w) + margin_px + n_sigma * lateral_std(belief.covariance, 0.5 * height)
    return band.band_mask(d, math.cos(alpha), math.sin(alpha), half_width, width, height), half_width
