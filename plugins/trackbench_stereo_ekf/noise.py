"""The measurement noise ``Q_t``: pixel matching errors carried into metres.

seeds/002, section 2.2, models the errors of the matched image coordinates
as independent, zero-mean and of variance ``Q_f`` each (eqs. 13-14), and
carries them through the linearised triangulation (eq. 16)::

    Q_t = Q_f J J^T,

``J`` being the Jacobian of eq. (17) (:func:`benchmark.modalities.stereo.geometry.triangulation_jacobian`).
Eq. (16) writes ``Q_f J N_t J^T`` after "factoring out" ``Q_f``, that is with
``N_t`` the identity; eq. (18) confirms one factor ``Q_f`` only.  With
``D = E^2`` the square of the triangulation denominator the entries are
eq. (18)::

    Q_1 = 2 f^2 T_y^2 / D^2,     Q_2 = Q_3 = f T_y^2 (y_r - C_y* + y_l - C_y) / D^2,
    Q_4 = T_y^2 ((y_r - C_y*)^2 + (y_l - C_y)^2) / D^2.

The standard deviation of ``x`` is then ``sqrt(2 Q_f) x^2 / (f B)``, which
with ``sqrt(2 Q_f) = m`` is the manufacturer's depth accuracy of Table 3
(there for ``m = 0.2`` px): the variance grows as the fourth power of the
range, which is how far measurements come to weigh less than the motion
model (section 3.2).

Section 3.1 replaces eq. (18) by the diagonal eq. (20): the same ``x``
variance and a constant ``y`` variance ``Q_f k`` with ``k = 2 m^2``.  Read
with ``m`` the correlation accuracy in px, ``Q_f k = m^4`` would be in px^4,
not a variance in metres.  The reading that keeps units is ``k = 2``
m^2/px^2, so that ``Q_f k = m^2``: with ``m = 0.11`` px a lateral standard
deviation of 0.11 m, which is the size eq. (18) gives for a target about
10 m ahead and 2 m abeam.  ``k`` is a parameter of :func:`measurement_noise`.
"""

from __future__ import annotations

from typing import Literal

import numpy as np

from benchmark.modalities.stereo.geometry import signed_baseline, triangulation_denominator, triangulation_jacobian
from benchmark.modalities.stereo.model import StereoCalibration

CovarianceForm = Literal["eq18", "eq20"]
COVARIANCE_FORMS: tuple[CovarianceForm, ...] = ("eq18", "eq20")


def full_covariance(
    left_px: float, right_px: float, calibration: StereoCalibration, pixel_variance: float
) -> np.ndarray:
    """``Q_t`` of eq. (18), ``Q_f J J^T``, in the camera frame.

    Parameters
    ----------
    left_px, right_px : float
        The measured ``y_l`` and ``y_r``, px.
    calibration : StereoCalibration
        The stereo camera.
    pixel_variance : float
        ``Q_f``, px^2 (Table 5: 0.11^2 / 2).

    Returns
    -------
    numpy.ndarray
        Shape ``(2, 2)``, m^2, over ``(x_v, y_v)``.

    References
    ----------
    seeds/002, eqs. (14), (16)-(18).
    """
    J = triangulation_jacobian(left_px, right_px, calibration)
    return pixel_variance * (J @ J.T)


def modified_covariance(
    left_px: float, right_px: float, calibration: StereoCalibration, pixel_variance: float, lateral_k: float
) -> np.ndarray:
    """``Q_t`` of eq. (20): eq. (18)'s ``x`` variance, a constant ``y`` variance, no correlation.

    Parameters
    ----------
    left_px, right_px : float
        The measured ``y_l`` and ``y_r``, px.
    calibration : StereoCalibration
        The stereo camera.
    pixel_variance : float
        ``Q_f``, px^2.
    lateral_k : float
        ``k``, m^2/px^2 (the module docstring explains the reading of ``k = 2 m^2``).

    Returns
    -------
    numpy.ndarray
        ``diag(Q_f 2 f^2 T_y^2 / D^2, Q_f k)``, m^2.

    References
    ----------
    seeds/002, section 3.1, eq. (20).
    """
    D = triangulation_denominator(left_px, right_px, calibration) ** 2
    x_variance = 2.0 * calibration.focal_px**2 * signed_baseline(calibration) ** 2 / D**2
    return pixel_variance * np.diag([x_variance, lateral_k])


def measurement_noise(
    left_px: float,
    right_px: float,
    calibration: StereoCalibration,
    pixel_variance: float,
    form: CovarianceForm = "eq20",
    lateral_k: float = 2.0,
) -> np.ndarray:
    """``Q_t`` by eq. (18) or eq. (20), evaluated at the measured pixel coordinates.

    Parameters
    ----------
    left_px, right_px : float
        ``y_l`` and ``y_r``, px.
    calibration : StereoCalibration
        The stereo camera.
    pixel_variance : float
        ``Q_f``, px^2.
    form : {"eq20", "eq18"}
        The modified (default, as section 3.1 concludes) or the full covariance.
    lateral_k : float
        ``k`` of eq. (20); unused by eq. (18).

    Returns
    -------
    numpy.ndarray
        Shape ``(2, 2)``, m^2, in the camera frame ``(x_v, y_v)`` of eq. (11).

    References
    ----------
    seeds/002, eqs. (18) and (20).
    """
    if form == "eq18":
        return full_covariance(left_px, right_px, calibration, pixel_variance)
    if form == "eq20":
        return modified_covariance(left_px, right_px, calibration, pixel_variance, lateral_k)
    raise ValueError(f"unknown covariance form {form!r}; expected one of {COVARIANCE_FORMS}")


def navigation_noise(relative_m: np.ndarray, gps_std_m: float, compass_std: float) -> np.ndarray:
    """Covariance the chase boat's GPS and compass errors add to ``z`` through ``h`` (eq. 11).

    ``h = Rot(psi)^T (X - X_ch)``: a GPS error moves ``z`` by ``-Rot^T dX_ch``
    (covariance ``sigma_gps^2 I``, the GPS axes being independent and
    equal), and a heading error ``dpsi`` turns ``z`` by ``dpsi`` about CH,
    ``dz = dpsi (y_v, -x_v)``.

    Parameters
    ----------
    relative_m : array_like
        The measured ``(x_v, y_v)``, m.
    gps_std_m : float
        Standard deviation of each GPS coordinate, m.
    compass_std : float
        Standard deviation of the heading, rad.

    Returns
    -------
    numpy.ndarray
        Shape ``(2, 2)``, m^2, in the camera frame.

    References
    ----------
    seeds/002, eqs. (10)-(11) and section 3 (GPS noise in the simulations).
    """
    x, y = (float(v) for v in relative_m)
    turn = np.array([y, -x])
    return gps_std_m**2 * np.eye(2) + compass_std**2 * np.outer(turn, turn)
