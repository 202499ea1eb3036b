"""The measurement model: where the pipe's borders cross the first and last image rows.

The EKF of seeds/004 measures ``z = (i_1, i_2, i_3, i_4)``, the columns at
which the left and right borders of the pipe cross the first image row
(``i_1``, ``i_2``) and the last one (``i_3``, ``i_4``), Fig. 4.  Section V-B
approximates the borders by the two lines where the pipe meets the ``XZ``
plane, ``X = -d/2`` and ``X = +d/2`` at ``Y = 0``, and the Appendix writes
``g`` by solving eq. (2b) for the point of each line on a given row and
substituting it in eq. (2a), eqs. (18)-(22).

Here the same function is written through the image of each line: a world
line through ``P_0`` with direction ``e_Z`` projects to the homogeneous
image line ``l = (M P_0 + t) x (M e_Z)`` for ``T = [M | t]``; with
``t = -M C`` and the identity ``(M a) x (M b) = det(M) M^-T (a x b)`` this
is, up to scale,

    l = M^-T n,    n = (P_0 - C) x e_Z = (Y - C_y, C_x - X, 0)

for ``P_0 = (X, Y, 0)`` (``(-C_y, C_x - X, 0)`` on the plane ``Y = 0``),
and the line crosses row ``v`` at ``u = -(l_2 v + l_3) / l_1``.  ``M = K
[h; v; a]`` holds the intrinsics ``K`` (focal length in px, image centre)
and the camera versors of section II.  ``C_z`` drops out, as section V-A
says it must for lines along the pipe.  Written this way the Jacobian ``G``
follows by the chain rule: ``dl = M^-T dn`` for ``C_x``, ``C_y``, and
``dl = -M^-T (K dR)^T l`` for an angle (``dR`` from
:func:`~benchmark.modalities.camera.scenes.projection.camera_axes_derivatives`).
Which ``(X, Y)`` each border passes through, the paper's plane lines or
the pipe's occluding contours, is the camera's border model
(:mod:`trackbench_foresti.borders`), which also gives ``dn``.

The paper's rows and columns: its eqs. (2) put ``i`` on the axis of ``h``
and Fig. 4 draws ``i_1 .. i_4`` along the image's horizontal borders, so
``i`` is the column; the rows are the first (``v = 0``) and last
(``v = h - 1``) as Fig. 4 and eqs. (21)-(22) have them.  The image centre
is ``((W - 1)/2, (H - 1)/2)`` (conventions.md section 1, as in
:func:`~benchmark.modalities.camera.scenes.projection.projection_matrix`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from benchmark.modalities.camera.geometry import Line
from benchmark.modalities.camera.scenes.projection import camera_axes, camera_axes_derivatives, principal_point
from trackbench_foresti.borders import BORDER_MODELS, BorderModelName


@dataclass(frozen=True)
class PipeCamera:
    """What the filter knows of the camera and the pipe.

    Attributes
    ----------
    focal_px : float
        ``f / delta_x`` in px (square pixels).
    size : tuple of int
        Image ``(W, H)`` in px.
    diameter_m : float
        The pipe's diameter ``d``.
    nominal_tilt : float
        ``phi_0`` of eq. (7), rad: the tilt the camera is mounted at.
    frame_interval_s : float
        ``tau`` of eq. (7).
    border_model : str
        Which lines of the pipe are its borders (:data:`trackbench_foresti.borders.BORDER_MODELS`):
        ``"plane"``, the paper's ``X = +-d/2`` at ``Y = 0``, or ``"tangent"``, the occluding contours.
    """

    focal_px: float
    size: tuple[int, int]
    diameter_m: float
    nominal_tilt: float
    frame_interval_s: float
    border_model: BorderModelName = "plane"

    def intrinsics(self) -> np.ndarray:
        """``K``: focal length on the diagonal, the image centre in the last column."""
        u0, v0 = principal_point(self.size)
        return np.array(((self.focal_px, 0.0, u0), (0.0, self.focal_px, v0), (0.0, 0.0, 1.0)))

    @property
    def rows(self) -> np.ndarray:
        """The first and last image rows, ``(0, H - 1)``."""
        return np.array((0.0, self.size[1] - 1.0))


def pose_angles(state: np.ndarray) -> tuple[float, float, float]:
    """Pan ``theta``, tilt ``phi`` and roll ``xi`` of a state ``(C_x, C_y, theta, phi[, xi])``; roll 0 if absent."""
    xi = float(state[4]) if len(state) > 4 else 0.0
    return float(state[2]), float(state[3]), xi


def _image_lines(state: np.ndarray, camera: PipeCamera) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The homogeneous image lines of both borders (rows), ``M^-T``, ``K`` and ``d n / d(C_x, C_y)``.

    ``n`` of the left and right border comes from the camera's border model
    (:mod:`trackbench_foresti.borders`).
    """
    intrinsics = camera.intrinsics()
    inverse_t = np.linalg.inv(intrinsics @ camera_axes(*pose_angles(state))).T
    normals, by_centre = BORDER_MODELS[camera.border_model](float(state[0]), float(state[1]), camera.diameter_m / 2)
    return normals @ inverse_t.T, inverse_t, intrinsics, by_centre


def _crossings(lines: np.ndarray, rows: np.ndarray) -> np.ndarray:
    """``u = -(l_2 v + l_3) / l_1`` of each line (rows of ``lines``) at each row ``v``: ``(lines, rows)``."""
    with np.errstate(divide="ignore", invalid="ignore"):
        return -(lines[:, 1:2] * rows[None, :] + lines[:, 2:3]) / lines[:, 0:1]


def border_abscissae(state: np.ndarray, camera: PipeCamera) -> np.ndarray:
    """``g(x)``: the columns ``(i_1, i_2, i_3, i_4)`` where the borders cross the first and last rows.

    Parameters
    ----------
    state : numpy.ndarray
        ``(C_x, C_y, theta, phi)`` or with roll ``xi`` appended; m and rad.
    camera : PipeCamera
        Intrinsics, image size and pipe diameter.

    Returns
    -------
    numpy.ndarray
        ``(i_1, i_2, i_3, i_4)`` in px: left and right border on row 0, then
        on row ``H - 1``.  A border parallel to the rows gives ``inf``/``nan``.

    References
    ----------
    seeds/004, section V-B, eq. (11), Fig. 4 and the Appendix, eqs. (18)-(22).
    """
    lines, *_ = _image_lines(np.asarray(state, dtype=float), camera)
    return _crossings(lines, camera.rows).T.reshape(4)


def border_jacobian(state: np.ndarray, camera: PipeCamera) -> np.ndarray:
    """``G = dg/dx``, the ``(4, n)`` Jacobian of :func:`border_abscissae` (eq. 14b).

    Columns follow the state: ``C_x``, ``C_y``, ``theta``, ``phi`` and, for a
    five-element state, ``xi``.

    References
    ----------
    seeds/004, eqs. (14b) and (16a); the derivation is in the module docstring.
    """
    state = np.asarray(state, dtype=float)
    return _jacobian(state, camera, *_image_lines(state, camera))


def border_measurement(state: np.ndarray, camera: PipeCamera) -> tuple[np.ndarray, np.ndarray | None]:
    """``g(x)`` and ``G = dg/dx`` at one state: :func:`border_abscissae` and :func:`border_jacobian` at once.

    Returns
    -------
    abscissae : numpy.ndarray
        ``(i_1, i_2, i_3, i_4)`` in px.
    jacobian : numpy.ndarray or None
        ``(4, n)``; None when an abscissa is not finite (a border parallel to the rows).

    References
    ----------
    seeds/004, eqs. (11), (14b) and (16a).
    """
    state = np.asarray(state, dtype=float)
    lines, inverse_t, intrinsics, by_centre = _image_lines(state, camera)
    abscissae = _crossings(lines, camera.rows).T.reshape(4)
    if not np.all(np.isfinite(abscissae)):
        return abscissae, None
    return abscissae, _jacobian(state, camera, lines, inverse_t, intrinsics, by_centre)


def _jacobian(
    state: np.ndarray,
    camera: PipeCamera,
    lines: np.ndarray,
    inverse_t: np.ndarray,
    intrinsics: np.ndarray,
    by_centre: np.ndarray,
) -> np.ndarray:
    """``G`` from the image lines of :func:`_image_lines` at ``state`` and ``d n / d(C_x, C_y)`` of each border."""
    rows = camera.rows
    axes = camera_axes_derivatives(*pose_angles(state))[: len(state) - 2]
    jacobian = np.empty((4, len(state)))
    for border, line in enumerate(lines):
        # Row c of dl is d l / d x_c; for C_x and C_y, dl = M^-T dn.
        by_position = by_centre[border] @ inverse_t.T
        dl = np.array([*by_position, *(-inverse_t @ (intrinsics @ d_axes).T @ line for d_axes in axes)])
        along = line[1] * rows + line[2]
        by_state = -(dl[:, 1:2] * rows + dl[:, 2:3]) / line[0] + along * dl[:, 0:1] / line[0] ** 2
        jacobian[[border, border + 2]] = by_state.T
    return jacobian


def border_lines(abscissae: np.ndarray, size: tuple[int, int]) -> tuple[Line, Line]:
    """The left and right border lines through ``(i_1, 0)``-``(i_3, H-1)`` and ``(i_2, 0)``-``(i_4, H-1)``.

    Raises
    ------
    ValueError
        If an abscissa is not finite.
    """
    i1, i2, i3, i4 = (float(v) for v in abscissae)
    bottom = size[1] - 1.0
    return Line.from_pixels((i1, 0.0), (i3, bottom), size), Line.from_pixels((i2, 0.0), (i4, bottom), size)
