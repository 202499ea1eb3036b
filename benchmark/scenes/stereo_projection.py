"""The rectified stereo pair: projection, triangulation (eq. 15) and depth accuracy.

Both cameras of the pair look along CH's bow.  The left camera's optical
centre is the origin of CH's camera frame (``x_v`` ahead, ``y_v`` to
starboard, seeds/002 Fig. 3), and the right camera sits ``B`` (the
baseline) to starboard of it.  The horizontal image coordinate ``y``
grows to starboard, so a point at ``(x_v, y_v)`` appears at

    ``y_l = C_y + f y_v / x_v``  and  ``y_r = C_y* + f (y_v - B) / x_v``,

and its disparity ``d = y_l - y_r = C_y - C_y* + f B / x_v`` falls with
range (seeds/002, Table 3: 1 px at 16.9 m for the Bumblebee2 at 320 px).
:func:`triangulate` inverts this with eq. (15).  Pixel coordinates are
continuous; pixel ``i`` covers ``[i - 0.5, i + 0.5)``, so the image spans
``[-0.5, width - 0.5]``.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from benchmark.model import StereoCalibration


def project(
    ahead_m: ArrayLike, starboard_m: ArrayLike, calibration: StereoCalibration
) -> tuple[np.ndarray, np.ndarray]:
    """Horizontal image coordinates of a point in the left and right images.

    Parameters
    ----------
    ahead_m, starboard_m : array_like
        ``(x_v, y_v)`` of the point in CH's camera frame; ``x_v > 0``.
    calibration : StereoCalibration
        ``f``, ``B``, ``C_y`` and ``C_y*``.

    Returns
    -------
    y_l, y_r : numpy.ndarray
        In px.

    References
    ----------
    seeds/002, eq. (15) and Fig. 4 (the pinhole model it inverts).
    """
    x = np.asarray(ahead_m, dtype=float)
    y = np.asarray(starboard_m, dtype=float)
    f, baseline = calibration.focal_px, calibration.baseline_m
    y_l = calibration.principal_left_px + f * y / x
    y_r = calibration.principal_right_px + f * (y - baseline) / x
    return y_l, y_r


def triangulate(y_l: ArrayLike, y_r: ArrayLike, calibration: StereoCalibration) -> tuple[np.ndarray, np.ndarray]:
    """The point ``(x_v, y_v)`` seen at ``y_l`` and ``y_r``, by eq. (15).

    Parameters
    ----------
    y_l, y_r : array_like
        Horizontal image coordinates in the left and right images, px.
    calibration : StereoCalibration
        ``f``, ``B``, ``C_y`` and ``C_y*``.

    Returns
    -------
    x_v, y_v : numpy.ndarray
        Ahead and to starboard, m; meaningful where the disparity
        ``y_l - y_r`` exceeds ``C_y - C_y*``.

    References
    ----------
    seeds/002, eq. (15).
    """
    y_l = np.asarray(y_l, dtype=float)
    y_r = np.asarray(y_r, dtype=float)
    # Eq. (15) as printed, with T_y the signed translation of the right camera in
    # the left camera's frame (Bouguet's and OpenCV's convention): the right camera
    # is B to starboard and y grows to starboard, so T_y = -B.  A target ahead then
    # has y_l > y_r, d > 0, x_v = f B / d > 0 and y_v = B (y_l - C_y) / d.
    t_y = -calibration.baseline_m
    c_l, c_r = calibration.principal_left_px, calibration.principal_right_px
    denominator = c_l - c_r - (y_l - y_r)
    return calibration.focal_px * t_y / denominator, t_y * (y_l - c_l) / denominator


def depth_from_disparity(disparity_px: ArrayLike, calibration: StereoCalibration) -> np.ndarray:
    """Range ahead ``Z = f B / d`` for disparities corrected for the principal points.

    Parameters
    ----------
    disparity_px : array_like
        ``d - (C_y - C_y*)``, px.
    calibration : StereoCalibration

    Returns
    -------
    numpy.ndarray
        ``Z`` in m (seeds/002, Table 3, column "Z").
    """
    return calibration.focal_px * calibration.baseline_m / np.asarray(disparity_px, dtype=float)


def depth_accuracy(depth_m: ArrayLike, calibration: StereoCalibration, disparity_error_px: float) -> np.ndarray:
    """Depth error caused by a disparity error, linearised: ``Z^2 / (f B) * delta_d``.

    Parameters
    ----------
    depth_m : array_like
        ``Z``, m.
    calibration : StereoCalibration
    disparity_error_px : float
        ``delta_d``; Table 3 uses the correlation accuracy of Table 4, 0.2 px.

    Returns
    -------
    numpy.ndarray
        In m (seeds/002, Table 3, column "Z accuracy"; Fig. 5).
    """
    z = np.asarray(depth_m, dtype=float)
    return z**2 / (calibration.focal_px * calibration.baseline_m) * disparity_error_px


def in_view(y_px: ArrayLike, calibration: StereoCalibration) -> np.ndarray:
    """Whether image coordinates fall inside the image, ``[-0.5, width - 0.5]``.

    Parameters
    ----------
    y_px : array_like
        Horizontal image coordinates, px.
    calibration : StereoCalibration

    Returns
    -------
    numpy.ndarray of bool
    """
    y = np.asarray(y_px, dtype=float)
    return (y >= -0.5) & (y <= calibration.width_px - 0.5)
