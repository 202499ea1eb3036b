"""Stereo geometry of the chase boat's camera: triangulation, projection and the North-East frame.

The chase boat (CH) carries a rectified stereo pair looking along its bow
(seeds/002, Fig. 3).  The left camera's optical centre is the origin of
CH's camera frame, ``x_v`` ahead and ``y_v`` to starboard; the right camera
sits the baseline ``B`` to starboard of it; the horizontal image coordinate
``y`` grows to starboard, as the physical ``y`` does (section 2.2).  A point
at ``(x_v, y_v)`` then appears at

    ``y_l = C_y + f y_v / x_v``  and  ``y_r = C_y* + f (y_v - B) / x_v``

(:func:`project`), and eq. (15) gives it back from ``y_l`` and ``y_r``
(:func:`triangulate`)::

    x_v = f T_y / (C_y - C_y* - d),    y_v = T_y (y_l - C_y) / (C_y - C_y* - d),    d = y_l - y_r.

Sign convention: ``T_y`` is the signed translation of the right camera in
the left camera's frame, Bouguet's and OpenCV's convention, so
``T_y = -B`` (:func:`signed_baseline`).  A target ahead then has
``y_l > y_r``, ``d > 0`` and, for equal principal points, ``x_v = f B / d > 0``
and ``y_v = B (y_l - C_y) / d``.  Lengths are in metres (the paper gives
``T_y`` in cm; only the unit of the result changes).  The denominator
``E = C_y - C_y* - d`` (:func:`triangulation_denominator`) is negative for
a target in front of the camera (:func:`in_front`); eq. (17)'s ``D`` is its
square, and :func:`triangulation_jacobian` is eq. (17).

CH's GPS position ``(X_ch, Y_ch)`` (North, East) and heading ``psi``
(clockwise from north) turn the camera frame into North-East coordinates
by eq. (10) (:func:`to_north_east`); eq. (11) is the inverse
(:func:`to_camera`), and its Jacobian with respect to the target's
``(X, Y)`` is ``Rot(psi)^T`` (:func:`to_camera_jacobian`), the position
block of eq. (12).

Whether an image coordinate falls inside the image completes it
(:func:`in_view`).  Pixel coordinates are continuous; pixel ``i`` covers
``[i - 0.5, i + 0.5)``, so the image spans ``[-0.5, width - 0.5]``.

Every function works elementwise: plain floats give floats (the Kalman
filter's per-frame path stays free of array overhead), numpy arrays give
arrays of their broadcast shape, matrices get two trailing axes.  A pair
such as ``chase_position_m`` is ``(X_ch, Y_ch)`` whose items are floats or
arrays.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any, TypeAlias

import numpy as np
from numpy.typing import ArrayLike

from benchmark.modalities.stereo.model import StereoCalibration

Real: TypeAlias = Any
"""A float or a numpy array of floats; the functions apply elementwise."""


def _cos_sin(angle: Real) -> tuple[Real, Real]:
    """``(cos, sin)`` of an angle: :mod:`math` for a scalar, numpy for an array."""
    if isinstance(angle, np.ndarray):
        return np.cos(angle), np.sin(angle)
    return math.cos(angle), math.sin(angle)


def _matrix(rows: list[list[Real]]) -> np.ndarray:
    """A matrix from nested rows of scalars or equally shaped arrays; the matrix axes come last."""
    matrix = np.array(rows, dtype=float)
    return matrix if matrix.ndim == 2 else np.moveaxis(matrix, (0, 1), (-2, -1))


def signed_baseline(calibration: StereoCalibration) -> float:
    """``T_y`` of eq. (15): the right camera's signed offset, ``-baseline``.

    Parameters
    ----------
    calibration : StereoCalibration
        The stereo camera.

    Returns
    -------
    float
        ``-calibration.baseline_m``, m.

    References
    ----------
    seeds/002, eq. (15); Bradski and Kaehler (2008), the ``T`` of ``cv::stereoRectify``.
    """
    return -float(calibration.baseline_m)


def triangulation_denominator(left_px: Real, right_px: Real, calibration: StereoCalibration) -> Real:
    """``E = C_y - C_y* - (y_l - y_r)``, the denominator of eq. (15).

    Parameters
    ----------
    left_px, right_px : float or numpy.ndarray
        ``y_l`` and ``y_r``, px.
    calibration : StereoCalibration
        Principal points ``C_y`` and ``C_y*``.

    Returns
    -------
    float or numpy.ndarray
        ``E``, px; negative for a target in front of the camera.  ``D`` of
        eq. (17) is ``E^2``.

    References
    ----------
    seeds/002, eqs. (15) and (17).
    """
    return calibration.principal_left_px - calibration.principal_right_px - (left_px - right_px)


def in_front(left_px: Real, right_px: Real, calibration: StereoCalibration) -> Real:
    """Whether eq. (15) puts the point at a finite, positive depth.

    Parameters
    ----------
    left_px, right_px : float or numpy.ndarray
        ``y_l`` and ``y_r``, px.
    calibration : StereoCalibration
        Principal points ``C_y`` and ``C_y*``.

    Returns
    -------
    bool or numpy.ndarray of bool
        True where the denominator ``E`` is finite and negative (false for nan).

    References
    ----------
    seeds/002, eq. (15).
    """
    value = triangulation_denominator(left_px, right_px, calibration)
    return (value < 0.0) & (value > -math.inf)


def triangulate(left_px: Real, right_px: Real, calibration: StereoCalibration) -> tuple[Real, Real]:
    """The point ``(x_v, y_v)`` seen at ``y_l`` and ``y_r``, by eq. (15).

    Parameters
    ----------
    left_px, right_px : float or numpy.ndarray
        Horizontal image coordinates in the left and right images, px.
    calibration : StereoCalibration
        Focal length, baseline and principal points.

    Returns
    -------
    x_v, y_v : float or numpy.ndarray
        Ahead and to starboard of the left camera, m; meaningful where
        :func:`in_front`.  A zero denominator raises ZeroDivisionError for
        floats and gives infinities (with numpy's warning) for arrays.

    References
    ----------
    seeds/002, eq. (15).
    """
    t_y = signed_baseline(calibration)
    denominator = triangulation_denominator(left_px, right_px, calibration)
    return calibration.focal_px * t_y / denominator, t_y * (left_px - calibration.principal_left_px) / denominator


def project(ahead_m: Real, starboard_m: Real, calibration: StereoCalibration) -> tuple[Real, Real]:
    """Horizontal image coordinates of a point in the left and right images: eq. (15) inverted.

    Parameters
    ----------
    ahead_m, starboard_m : float or numpy.ndarray
        ``(x_v, y_v)`` of the point in CH's camera frame, m; ``x_v > 0``.
    calibration : StereoCalibration
        ``f``, ``B``, ``C_y`` and ``C_y*``.

    Returns
    -------
    y_l, y_r : float or numpy.ndarray
        ``C_y + f y_v / x_v`` and ``C_y* + f (y_v - B) / x_v``, px.

    References
    ----------
    seeds/002, eq. (15) and Fig. 4 (the pinhole model it inverts).
    """
    f = calibration.focal_px
    left = calibration.principal_left_px + f * starboard_m / ahead_m
    right = calibration.principal_right_px + f * (starboard_m - calibration.baseline_m) / ahead_m
    return left, right


def triangulation_jacobian(left_px: Real, right_px: Real, calibration: StereoCalibration) -> np.ndarray:
    """``J = dS/dp`` of eq. (17) over ``p = [x_l, y_l, x_r, y_r]`` (eq. 13).

    With ``E`` the denominator of eq. (15), ``dE/dy_l = -1`` and
    ``dE/dy_r = +1``, so::

        dx/dy_l =  f T_y / E^2            dx/dy_r = -f T_y / E^2
        dy/dy_l =  T_y (y_r - C_y*) / E^2 dy/dy_r = -T_y (y_l - C_y) / E^2

    (``dy/dy_l = T_y (E + y_l - C_y) / E^2`` and ``E + y_l - C_y = y_r - C_y*``),
    and zero for the vertical coordinates ``x_l`` and ``x_r``.  This is
    eq. (17) with ``D = E^2 = (C_y - C_y* + y_r - y_l)^2``: the paper's
    definition of ``D`` as a square is the one its eqs. (17) and (18) need.

    Parameters
    ----------
    left_px, right_px : float or numpy.ndarray
        ``y_l`` and ``y_r`` at which to linearise, px.
    calibration : StereoCalibration
        The stereo camera.

    Returns
    -------
    numpy.ndarray
        Shape ``(..., 2, 4)``, m/px: rows ``(x_v, y_v)``, columns
        ``(x_l, y_l, x_r, y_r)``; the columns of ``x_l`` and ``x_r`` are zero.

    References
    ----------
    seeds/002, eqs. (13), (15) and (17).
    """
    f, t_y = calibration.focal_px, signed_baseline(calibration)
    D = triangulation_denominator(left_px, right_px, calibration) ** 2
    depth = f * t_y / D
    zero = 0.0 * D
    return _matrix(
        [
            [zero, depth, zero, -depth],
            [
                zero,
                t_y * (right_px - calibration.principal_right_px) / D,
                zero,
                -t_y * (left_px - calibration.principal_left_px) / D,
            ],
        ]
    )


def rotation(heading: Real) -> np.ndarray:
    """``Rot`` of eq. (10), camera frame (ahead, starboard) to North-East.

    It is also the Jacobian of :func:`to_north_east` with respect to
    ``(x_v, y_v)``, which turns a covariance in the camera frame into
    North-East: ``Rot C Rot^T``.

    Parameters
    ----------
    heading : float or numpy.ndarray
        ``psi_ch``, clockwise from north, rad.

    Returns
    -------
    numpy.ndarray
        Shape ``(..., 2, 2)``: ``[[cos, -sin], [sin, cos]]``.

    References
    ----------
    seeds/002, eq. (10).
    """
    c, s = _cos_sin(heading)
    return _matrix([[c, -s], [s, c]])


def to_north_east(
    ahead_m: Real, starboard_m: Real, chase_position_m: Sequence[Real], chase_heading: Real
) -> tuple[Real, Real]:
    """North-East position of a point seen at ``(x_v, y_v)`` from CH, eq. (10).

    Parameters
    ----------
    ahead_m, starboard_m : float or numpy.ndarray
        ``(x_v, y_v)``, m.
    chase_position_m : pair of float or numpy.ndarray
        CH's ``(X_ch, Y_ch)``, North and East, m.
    chase_heading : float or numpy.ndarray
        ``psi_ch``, clockwise from north, rad.

    Returns
    -------
    north_m, east_m : float or numpy.ndarray
        ``X = cos(psi) x_v - sin(psi) y_v + X_ch`` and
        ``Y = sin(psi) x_v + cos(psi) y_v + Y_ch``, m.

    References
    ----------
    seeds/002, eq. (10) and Fig. 3.
    """
    c, s = _cos_sin(chase_heading)
    chase_north, chase_east = chase_position_m
    return c * ahead_m - s * starboard_m + chase_north, s * ahead_m + c * starboard_m + chase_east


def to_camera(
    north_m: Real, east_m: Real, chase_position_m: Sequence[Real], chase_heading: Real
) -> tuple[Real, Real]:
    """Where CH's camera frame puts a North-East point, eq. (11): the inverse of eq. (10).

    Parameters
    ----------
    north_m, east_m : float or numpy.ndarray
        The point's ``(X, Y)``, m.
    chase_position_m : pair of float or numpy.ndarray
        CH's ``(X_ch, Y_ch)``, m.
    chase_heading : float or numpy.ndarray
        ``psi_ch``, clockwise from north, rad.

    Returns
    -------
    ahead_m, starboard_m : float or numpy.ndarray
        ``x_v = cos(psi) dX + sin(psi) dY`` and ``y_v = -sin(psi) dX + cos(psi) dY``
        with ``(dX, dY) = (X - X_ch, Y - Y_ch)``, m.

    References
    ----------
    seeds/002, eq. (11) (``h(x)`` without its noise).
    """
    c, s = _cos_sin(chase_heading)
    chase_north, chase_east = chase_position_m
    d_north, d_east = north_m - chase_north, east_m - chase_east
    return c * d_north + s * d_east, -s * d_north + c * d_east


def to_camera_jacobian(chase_heading: Real) -> np.ndarray:
    """Jacobian of :func:`to_camera` with respect to the point's ``(X, Y)``: ``Rot(psi)^T``.

    Eq. (12) prints these numbers as the position block of ``H_t`` (its
    column labels aside: the rotation belongs to ``X`` and ``Y``, the zeros
    to the velocities of the state of eq. 5).

    Parameters
    ----------
    chase_heading : float or numpy.ndarray
        ``psi_ch``, rad.

    Returns
    -------
    numpy.ndarray
        Shape ``(..., 2, 2)``: ``[[cos, sin], [-sin, cos]]``.

    References
    ----------
    seeds/002, eqs. (4), (11) and (12).
    """
    return np.swapaxes(rotation(chase_heading), -1, -2)


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
    (:mod:`benchmark.modalities.stereo.scenes.sensors`) loses a target outside either image.
    """
    y = np.asarray(y_px, dtype=float)
    return (y >= -0.5) & (y <= calibration.width_px - 0.5)
