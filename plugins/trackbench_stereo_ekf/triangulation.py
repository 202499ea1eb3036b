"""Stereo triangulation in the horizontal plane and its Jacobian.

Bouguet's triangulation as seeds/002 prints it in eq. (15) gives the target
relative to the left camera from the horizontal image coordinates ``y_l``
and ``y_r`` of its projections::

    x = f T_y / (C_y - C_y* - d),    y = T_y (y_l - C_y) / (C_y - C_y* - d),    d = y_l - y_r.

``T_y`` is read as the signed translation of the right camera in the left
camera's frame, OpenCV's convention, so ``T_y = -baseline``; with the image
coordinate ``y`` growing to starboard a target ahead has ``y_l > y_r``,
``d > 0`` and ``x = f B / d > 0`` for equal principal points.  Lengths are in
metres (the paper gives ``T_y`` in cm; only the unit of the result changes).

Writing ``E = C_y - C_y* - d`` for the denominator, the Jacobian with respect
to ``p = [x_l, y_l, x_r, y_r]`` (eq. 13) is, since ``dE/dy_l = -1`` and
``dE/dy_r = +1``::

    dx/dy_l =  f T_y / E^2            dx/dy_r = -f T_y / E^2
    dy/dy_l =  T_y (y_r - C_y*) / E^2 dy/dy_r = -T_y (y_l - C_y) / E^2

(``dy/dy_l = T_y / E + T_y (y_l - C_y) / E^2 = T_y (E + y_l - C_y) / E^2``
and ``E + y_l - C_y = y_r - C_y*``), and zero for the vertical coordinates.
This is eq. (17) with ``D = E^2 = (C_y - C_y* + y_r - y_l)^2``: the paper's
definition of ``D`` as a square is the one its eqs. (17) and (18) need.
"""

from __future__ import annotations

import numpy as np

from benchmark.model import StereoCalibration


def signed_baseline(calibration: StereoCalibration) -> float:
    """``T_y`` of eq. (15): the right camera's signed offset, ``-baseline``.

    Parameters
    ----------
    calibration : StereoCalibration
        The stereo camera.

    Returns
    -------
    float
        ``-calibration.baseline_m``.

    References
    ----------
    seeds/002, eq. (15); Bradski and Kaehler (2008), the ``T`` of ``cv::stereoRectify``.
    """
    return -float(calibration.baseline_m)


def denominator(left_px: float, right_px: float, calibration: StereoCalibration) -> float:
    """``E = C_y - C_y* - (y_l - y_r)``, negative for a target in front of the camera.

    Parameters
    ----------
    left_px, right_px : float
        ``y_l`` and ``y_r``.
    calibration : StereoCalibration
        Principal points ``C_y`` and ``C_y*``.

    Returns
    -------
    float
        The denominator of eq. (15); ``D`` of eq. (17) is its square.

    References
    ----------
    seeds/002, eqs. (15) and (17).
    """
    return calibration.principal_left_px - calibration.principal_right_px - (left_px - right_px)


def in_front(left_px: float, right_px: float, calibration: StereoCalibration) -> bool:
    """True when eq. (15) puts the target at a finite, positive depth."""
    value = denominator(left_px, right_px, calibration)
    return bool(np.isfinite(value) and value < 0.0)


def triangulate(left_px: float, right_px: float, calibration: StereoCalibration) -> np.ndarray:
    """The target relative to the camera, ``[x_v, y_v]`` (ahead, starboard), by eq. (15).

    Parameters
    ----------
    left_px, right_px : float
        ``y_l`` and ``y_r``, horizontal image coordinates in px.
    calibration : StereoCalibration
        Focal length, baseline and principal points.

    Returns
    -------
    numpy.ndarray
        ``[x, y]`` in m; infinite or behind the camera unless :func:`in_front`.

    References
    ----------
    seeds/002, eq. (15).
    """
    t_y = signed_baseline(calibration)
    e = denominator(left_px, right_px, calibration)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.array([calibration.focal_px * t_y / e, t_y * (left_px - calibration.principal_left_px) / e])


def project(relative_m: np.ndarray, calibration: StereoCalibration) -> tuple[float, float]:
    """Image coordinates ``(y_l, y_r)`` of a point ahead of the camera: eq. (15) inverted.

    Parameters
    ----------
    relative_m : array_like
        ``(x_v, y_v)`` with ``x_v > 0``, m.
    calibration : StereoCalibration
        The stereo camera.

    Returns
    -------
    tuple of float
        ``y_l = C_y + f y / x`` and ``y_r = y_l - (C_y - C_y*) - f B / x``.

    References
    ----------
    seeds/002, eq. (15).
    """
    x, y = (float(v) for v in relative_m)
    left = calibration.principal_left_px + calibration.focal_px * y / x
    e = calibration.focal_px * signed_baseline(calibration) / x
    return left, left - (calibration.principal_left_px - calibration.principal_right_px - e)


def triangulation_jacobian(left_px: float, right_px: float, calibration: StereoCalibration) -> np.ndarray:
    """``J = dS/dp`` of eq. (17), a 2 x 4 matrix over ``p = [x_l, y_l, x_r, y_r]``.

    Parameters
    ----------
    left_px, right_px : float
        ``y_l`` and ``y_r`` at which to linearise, px.
    calibration : StereoCalibration
        The stereo camera.

    Returns
    -------
    numpy.ndarray
        Shape ``(2, 4)``, in m/px; the columns of the vertical coordinates
        ``x_l`` and ``x_r`` are zero.

    References
    ----------
    seeds/002, eqs. (13), (15) and (17).
    """
    f = calibration.focal_px
    t_y = signed_baseline(calibration)
    D = denominator(left_px, right_px, calibration) ** 2
    return np.array(
        [
            [0.0, f * t_y / D, 0.0, -f * t_y / D],
            [
                0.0,
                t_y * (right_px - calibration.principal_right_px) / D,
                0.0,
                -t_y * (left_px - calibration.principal_left_px) / D,
            ],
        ]
    )
