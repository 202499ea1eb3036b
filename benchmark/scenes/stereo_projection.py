"""What the simulated stereo camera can see, and how precisely: field of view and Table 3.

The geometry of the pair (projection, triangulation by eq. 15, the
North-East frame) is :mod:`benchmark.stereo_geometry`, shared with the
trackers.  This module adds what only the simulation and its tests need:
the range ``Z = f B / d`` of a disparity and its linearised error
(seeds/002, Table 3 and Fig. 5), and whether an image coordinate falls
inside the image.  Pixel coordinates are continuous; pixel ``i`` covers
``[i - 0.5, i + 0.5)``, so the image spans ``[-0.5, width - 0.5]``.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from benchmark.model import StereoCalibration


def depth_from_disparity(disparity_px: ArrayLike, calibration: StereoCalibration) -> np.ndarray:
    """Range ahead ``Z = f B / d`` for disparities corrected for the principal points.

    Parameters
    ----------
    disparity_px : array_like
        ``d - (C_y - C_y*)``, px.
    calibration : StereoCalibration
        Focal length ``f`` and baseline ``B``.

    Returns
    -------
    numpy.ndarray
        ``Z`` in m.

    References
    ----------
    seeds/002, Table 3 (column "Z") and eq. (15) with ``C_y = C_y*``.
    """
    return calibration.focal_px * calibration.baseline_m / np.asarray(disparity_px, dtype=float)


def depth_accuracy(depth_m: ArrayLike, calibration: StereoCalibration, disparity_error_px: float) -> np.ndarray:
    """Depth error caused by a disparity error, linearised: ``Z^2 / (f B) * delta_d``.

    Parameters
    ----------
    depth_m : array_like
        ``Z``, m.
    calibration : StereoCalibration
        Focal length ``f`` and baseline ``B``.
    disparity_error_px : float
        ``delta_d``; Table 3 uses the correlation accuracy of Table 4, 0.2 px.

    Returns
    -------
    numpy.ndarray
        In m.

    References
    ----------
    seeds/002, Table 3 (column "Z accuracy") and Fig. 5.
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
        The image width ``width_px``.

    Returns
    -------
    numpy.ndarray of bool

    References
    ----------
    seeds/002, Table 4 (the 320 px stereo resolution); the simulated front end
    (:mod:`benchmark.scenes.stereo_sensors`) loses a target outside either image.
    """
    y = np.asarray(y_px, dtype=float)
    return (y >= -0.5) & (y <= calibration.width_px - 0.5)
