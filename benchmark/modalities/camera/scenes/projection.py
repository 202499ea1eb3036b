"""The pinhole camera of Foresti's scene model (seeds/004, section II).

The world frame is the pipeline frame of seeds/004: ``Z`` runs along the pipe
axis, which is the ``Z`` axis itself, ``Y`` points up and ``X`` is
horizontal, to the right of an observer who looks along ``+Z`` with ``Y``
up.  A camera at ``C = (Cx, Cy, Cz)`` with pan ``theta``, tilt ``phi`` and
roll ``xi`` has three versors: ``h`` (image right), ``v`` (image down) and
``a`` (the optical axis), given by the formulas printed at the end of
section II and implemented verbatim in :func:`camera_axes`.  Tilt ``phi``
is the angle between the optical axis and the ``XZ`` plane, so
``phi = 90 deg`` looks straight down with the top of the image towards
``+Z``.

A world point ``P`` maps to the pixel

    u = u0 + (f/dx) (P - C).h / (P - C).a     (column, image right)
    v = v0 + (f/dy) (P - C).v / (P - C).a     (row, image down)

which is eqs. (1)-(3) written out.  Two misprints of the paper are resolved
here:

* eqs. (3d) and (3h) print ``+ i0 C.a`` and ``+ j0 C.a``; with (3l),
  ``T11 = -C.a``, only ``- i0 C.a`` and ``- j0 C.a`` make (2a) and (2b) the
  perspective projection above, so :func:`projection_matrix` uses the minus
  sign;
* eqs. (2) put the index ``i`` on the axis of ``h`` (horizontal) while
  eqs. (4) put ``j`` there.  We follow eqs. (1)-(3): the first row of ``T``
  gives the column ``u`` and the second row the row ``v``, in OpenCV's pixel
  convention with ``(u0, v0) = ((W-1)/2, (H-1)/2)`` (conventions.md
  section 1).

The printed versors are orthonormal whenever pan or roll is zero; with both
non-zero they drift slightly from orthonormal.  Nothing here relies on
orthonormality: the projection stays a central projection from ``C``, and
:func:`pixel_rays` inverts the matrix ``[h; v; a]`` rather than transposing
it, so rendering and ground truth agree exactly.
"""

from __future__ import annotations

import math

import numpy as np

from benchmark.modalities.camera.model import CameraPose

ImageSize = tuple[int, int]
"""``(W, H)`` in px."""


def _cos_sin(*angles: float) -> list[tuple[float, float]]:
    """``(cos, sin)`` of each angle."""
    return [(math.cos(angle), math.sin(angle)) for angle in angles]


def camera_axes(theta: float, phi: float, xi: float) -> np.ndarray:
    """The camera versors of seeds/004, section II, as the rows of a matrix.

    Parameters
    ----------
    theta, phi, xi : float
        Pan, tilt and roll in rad.

    Returns
    -------
    numpy.ndarray
        A ``3 x 3`` array whose rows are ``h`` (image right), ``v`` (image
        down) and ``a`` (optical axis) in world coordinates.

    References
    ----------
    seeds/004, section II, the versors ``h``, ``v``, ``a`` following Fig. 2.
    """
    (ct, st), (cp, sp), (cx, sx) = _cos_sin(theta, phi, xi)
    h = (ct * cx, -sx * ct, -st)
    v = (-sp * st * cx - cp * sx, -cp * cx + sp * st * sx, -sp * ct)
    a = (cp * st * cx - sp * sx, -sp * cx + st * sx * cp, cp * ct)
    return np.array((h, v, a), dtype=float)


def camera_axes_derivatives(theta: float, phi: float, xi: float) -> np.ndarray:
    """The derivatives of :func:`camera_axes` with respect to pan, tilt and roll.

    Parameters
    ----------
    theta, phi, xi : float
        Pan, tilt and roll in rad.

    Returns
    -------
    numpy.ndarray
        Shape ``(3, 3, 3)``: entry ``[k]`` is the derivative of the ``3 x 3``
        matrix of rows ``h``, ``v``, ``a`` with respect to ``theta``
        (``k = 0``), ``phi`` (1) and ``xi`` (2).

    References
    ----------
    seeds/004, section II: the versors ``h``, ``v``, ``a``, differentiated term by term.
    """
    (ct, st), (cp, sp), (cx, sx) = _cos_sin(theta, phi, xi)
    by_theta = (
        (-st * cx, sx * st, -ct),
        (-sp * ct * cx, sp * ct * sx, sp * st),
        (cp * ct * cx, ct * sx * cp, -cp * st),
    )
    by_phi = (
        (0.0, 0.0, 0.0),
        (-cp * st * cx + sp * sx, sp * cx + cp * st * sx, -cp * ct),
        (-sp * st * cx - cp * sx, -cp * cx - st * sx * sp, -sp * ct),
    )
    by_xi = (
        (-ct * sx, -cx * ct, 0.0),
        (sp * st * sx - cp * cx, cp * sx + sp * st * cx, 0.0),
        (-cp * st * sx - sp * cx, sp * sx + st * cx * cp, 0.0),
    )
    return np.array((by_theta, by_phi, by_xi), dtype=float)


def pose_axes(pose: CameraPose) -> np.ndarray:
    """:func:`camera_axes` of a pose."""
    return camera_axes(pose.theta, pose.phi, pose.xi)


def principal_point(size: ImageSize) -> tuple[float, float]:
    """The image centre ``(u0, v0) = ((W-1)/2, (H-1)/2)`` in pixel coordinates."""
    return (size[0] - 1) / 2.0, (size[1] - 1) / 2.0


def projection_matrix(pose: CameraPose, focal_px: float, size: ImageSize) -> np.ndarray:
    """The ``3 x 4`` perspective transformation matrix ``T`` of eqs. (1) and (3).

    Parameters
    ----------
    pose : CameraPose
        Camera centre and pan, tilt, roll.
    focal_px : float
        ``f / dx``, taken equal to ``f / dy`` (square pixels).
    size : tuple of int
        Image ``(W, H)``; the image centre is ``((W-1)/2, (H-1)/2)``.

    Returns
    -------
    numpy.ndarray
        ``T`` with rows ``(T0..T3)``, ``(T4..T7)``, ``(T8..T11)``.  For a world
        point ``P``, ``T @ (P, 1) = w (u, v, 1)`` with ``u`` the column and
        ``v`` the row.

    References
    ----------
    seeds/004, eqs. (1)-(3), with ``T3 = -(f/dx) C.h - i0 C.a`` and
    ``T7 = -(f/dy) C.v - j0 C.a`` (the sign of the last term corrected to
    agree with (3l)).
    """
    h, v, a = pose_axes(pose)
    centre = np.array((pose.cx, pose.cy, pose.cz), dtype=float)
    u0, v0 = principal_point(size)
    t = np.empty((3, 4), dtype=float)
    t[0, :3] = focal_px * h + u0 * a
    t[0, 3] = -focal_px * centre @ h - u0 * centre @ a
    t[1, :3] = focal_px * v + v0 * a
    t[1, 3] = -focal_px * centre @ v - v0 * centre @ a
    t[2, :3] = a
    t[2, 3] = -centre @ a
    return t


def project_points(matrix: np.ndarray, points: np.ndarray) -> np.ndarray:
    """Pixels ``(u, v)`` of world points through a matrix ``T``, eqs. (2a)-(2b).

    Parameters
    ----------
    matrix : numpy.ndarray
        A ``3 x 4`` matrix from :func:`projection_matrix`.
    points : numpy.ndarray
        World points, shape ``(..., 3)``.

    Returns
    -------
    numpy.ndarray
        Pixel coordinates, shape ``(..., 2)``; points on the focal plane give
        infinities.

    References
    ----------
    seeds/004, eqs. (2a) and (2b).
    """
    pts = np.asarray(points, dtype=float)
    homogeneous = pts @ matrix[:, :3].T + matrix[:, 3]
    with np.errstate(divide="ignore", invalid="ignore"):
        return homogeneous[..., :2] / homogeneous[..., 2:3]


def pixel_rays(focal_px: float, size: ImageSize) -> tuple[np.ndarray, np.ndarray]:
    """Per-pixel ray coordinates in the camera frame.

    The ray through pixel ``(u, v)`` is ``q = (qx, qy, 1)`` in the basis
    ``(h, v, a)``, with ``qx = (u - u0) / f`` and ``qy = (v - v0) / f``.  Its
    world direction is ``D = [h; v; a]^-1 q``, normalised so that
    ``D.a = 1``: a ray parameter ``t`` along ``D`` is the depth along the
    optical axis.

    Parameters
    ----------
    focal_px : float
        ``f / dx`` in px.
    size : tuple of int
        Image ``(W, H)``.

    Returns
    -------
    qx, qy : numpy.ndarray
        ``float32`` arrays of shape ``(H, W)``.

    References
    ----------
    seeds/004, eqs. (2a)-(2b) solved for the direction of ``P - C``.
    """
    width, height = size
    u0, v0 = principal_point(size)
    qx = (np.arange(width, dtype=np.float32) - np.float32(u0)) / np.float32(focal_px)
    qy = (np.arange(height, dtype=np.float32) - np.float32(v0)) / np.float32(focal_px)
    return np.broadcast_to(qx, (height, width)).copy(), np.broadcast_to(qy[:, None], (height, width)).copy()


def homogeneous_line(matrix: np.ndarray, point: np.ndarray, direction: np.ndarray) -> np.ndarray:
    """The image of a 3-D line as a homogeneous pixel line ``(a, b, c)``.

    The line ``{point + s direction}`` projects to ``{(u, v): a u + b v + c =
    0}``: the cross product of the images of one of its points and of its
    point at infinity (its vanishing point), which stays valid when the
    direction is parallel to the image plane or part of the line is behind
    the camera.

    References
    ----------
    seeds/004, eq. (1) applied to homogeneous points.
    """
    p1, p2, p3 = matrix[:, :3] @ np.asarray(point, dtype=float) + matrix[:, 3]
    q1, q2, q3 = matrix[:, :3] @ np.asarray(direction, dtype=float)
    return np.array((p2 * q3 - p3 * q2, p3 * q1 - p1 * q3, p1 * q2 - p2 * q1))
