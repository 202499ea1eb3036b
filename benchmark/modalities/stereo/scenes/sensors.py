"""The sensors of the stereo simulations: front end, GPS and compass, with their errors.

Seeds/002, section 3 simulates the measurements as follows: the true
relative position of TG is projected into both images (eq. 15), each pixel
coordinate gets zero-mean Gaussian noise of variance ``Q_f = m^2 / 2``
(eq. 19), and the relative position is triangulated again from the noisy
coordinates; CH's GPS position gets Gaussian noise as well.
:func:`stereo_measurements` does the first part and adds what a real
front end does besides: it loses the target (reason in :class:`Loss`) when

* the target is behind the camera, or either noisy image coordinate falls
  outside its image (outside the horizontal field of view);
* the measured disparity, corrected for the principal points, is at most a
  small minimum (the match is lost in quantisation; 0.3 px is about 56 m);
* the detector misses it for no geometric reason, in short bursts
  (:func:`burst_dropouts`).

Ranges beyond the operational limit of 16 m are still measured, only
noisier: a filter must learn to weigh them less (seeds/002, section 3.2).
"""

from __future__ import annotations

import enum
import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from benchmark.modalities.stereo.geometry import in_view, project, triangulate
from benchmark.modalities.stereo.model import StereoCalibration


class Loss(enum.IntEnum):
    """Why the front end reported nothing in a frame (``KEPT`` when it reported a measurement)."""

    KEPT = 0
    OUT_OF_VIEW = 1
    LOW_DISPARITY = 2
    DROPOUT = 3


def correlated_noise(
    rng: np.random.Generator, shape: tuple[int, ...], sigma: float, correlation_steps: float
) -> np.ndarray:
    """Stationary Gaussian noise along axis 0: a first-order Gauss-Markov (AR(1)) process.

    Parameters
    ----------
    rng : numpy.random.Generator
        Source of the white noise; always ``prod(shape)`` normal draws.
    shape : tuple of int
        Output shape; axis 0 is time.
    sigma : float
        Stationary standard deviation.
    correlation_steps : float
        Correlation time in steps: consecutive samples correlate by
        ``exp(-1 / correlation_steps)``; 0 gives white noise.

    Returns
    -------
    numpy.ndarray
        Noise of the given shape.
    """
    white = rng.standard_normal(shape)
    if correlation_steps <= 0 or shape[0] == 0:
        return sigma * white
    rho = math.exp(-1.0 / correlation_steps)
    innovation = math.sqrt(1.0 - rho * rho)
    out = np.empty(shape)
    out[0] = white[0]
    for k in range(1, shape[0]):
        out[k] = rho * out[k - 1] + innovation * white[k]
    return sigma * out


def burst_dropouts(rng: np.random.Generator, n: int, rate: float, mean_burst: float) -> np.ndarray:
    """Frames a detector misses, in bursts: a two-state Markov chain (the Gilbert model).

    A kept frame is followed by a missed one with probability
    ``p = rate / ((1 - rate) mean_burst)``, a missed one by a kept one with
    probability ``1 / mean_burst``; the first state is drawn from the
    stationary distribution.  So in the long run a share ``rate`` of the
    frames are missed, in runs of geometric length with mean ``mean_burst``.

    Parameters
    ----------
    rng : numpy.random.Generator
        Always ``n`` uniform draws.
    n : int
        Number of frames.
    rate : float
        Long-run share of missed frames, in [0, 1).
    mean_burst : float
        Mean run length of missed frames, ``>= 1``.

    Returns
    -------
    numpy.ndarray of bool
        True where the frame is missed.
    """
    if not (0 <= rate < 1 and mean_burst >= 1):
        raise ValueError(f"need 0 <= rate < 1 and mean_burst >= 1, got {rate}, {mean_burst}")
    draws = rng.random(n)
    missed = np.zeros(n, dtype=bool)
    if rate == 0 or n == 0:
        return missed
    enter, leave = rate / ((1.0 - rate) * mean_burst), 1.0 / mean_burst
    state = bool(draws[0] < rate)
    missed[0] = state
    for k in range(1, n):
        state = draws[k] >= leave if state else draws[k] < enter
        missed[k] = state
    return missed


@dataclass(frozen=True)
class MeasurementArrays:
    """What the front end reports over a sequence, one entry per frame.

    Attributes
    ----------
    left_px, right_px : numpy.ndarray
        Noisy ``y_l`` and ``y_r``; ``nan`` where the target is behind the camera.
    ahead_m, starboard_m : numpy.ndarray
        ``(x_v, y_v)`` triangulated from them by eq. (15); meaningful where kept.
    loss : numpy.ndarray
        :class:`Loss` codes (``int8``).
    """

    left_px: np.ndarray
    right_px: np.ndarray
    ahead_m: np.ndarray
    starboard_m: np.ndarray
    loss: np.ndarray

    @property
    def kept(self) -> np.ndarray:
        """True where the front end reported a measurement."""
        return self.loss == Loss.KEPT


def stereo_measurements(
    ahead_m: ArrayLike,
    starboard_m: ArrayLike,
    calibration: StereoCalibration,
    pixel_noise: np.ndarray,
    min_disparity_px: float,
    dropped: np.ndarray,
) -> MeasurementArrays:
    """Simulate the stereo front end from the true relative positions.

    Parameters
    ----------
    ahead_m, starboard_m : array_like
        True ``(x_v, y_v)`` of TG in CH's camera frame, shape ``(n,)``.
    calibration : StereoCalibration
    pixel_noise : numpy.ndarray
        Shape ``(n, 2)``: the errors added to ``y_l`` and ``y_r``, px; draw
        them with standard deviation ``sqrt(Q_f) = m / sqrt(2)``.
    min_disparity_px : float
        Disparities (corrected for the principal points) at or below this
        lose the target.
    dropped : numpy.ndarray of bool
        Frames the detector misses anyway (:func:`burst_dropouts`).

    Returns
    -------
    MeasurementArrays
        Geometric losses take precedence over dropouts in ``loss``.

    References
    ----------
    seeds/002, section 3 (simulated measurements), eqs. (15) and (19).
    """
    x = np.asarray(ahead_m, dtype=float)
    y = np.asarray(starboard_m, dtype=float)
    front = x > 0
    safe_x = np.where(front, x, 1.0)
    true_l, true_r = project(safe_x, y, calibration)
    left = np.where(front, true_l + pixel_noise[:, 0], np.nan)
    right = np.where(front, true_r + pixel_noise[:, 1], np.nan)
    disparity = (left - calibration.principal_left_px) - (right - calibration.principal_right_px)
    loss = np.full(x.shape, Loss.KEPT, dtype=np.int8)
    loss[np.asarray(dropped, dtype=bool)] = Loss.DROPOUT
    loss[front & ~(disparity > min_disparity_px)] = Loss.LOW_DISPARITY
    loss[~front | ~(in_view(left, calibration) & in_view(right, calibration))] = Loss.OUT_OF_VIEW
    usable = front & (disparity > 0)
    with np.errstate(divide="ignore", invalid="ignore"):
        ahead, starboard = triangulate(left, right, calibration)
    return MeasurementArrays(
        left_px=left,
        right_px=right,
        ahead_m=np.where(usable, ahead, np.nan),
        starboard_m=np.where(usable, starboard, np.nan),
        loss=loss,
    )
