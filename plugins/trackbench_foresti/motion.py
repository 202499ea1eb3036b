"""The system model: the camera moves with the inertial speeds, its angles stay put.

Between two frames the camera centre moves by eq. (7),

    C_(k+1) = C_k + Psi_k (s_x, s_y, s_z)_k tau,

with ``Psi`` of eq. (12) at pan ``theta_k``, ``sigma_k = phi_k - phi_0`` and
roll ``xi_k``; only ``C_x`` and ``C_y`` are in the state (``C_z`` drops out
of the measurement, section V-A), giving eqs. (8a)-(8b).  The angles keep
their values, eqs. (9a)-(9c).  Eqs. (8c)-(8d) are (8a)-(8b) with ``s_y = 0``;
the speeds here are whatever the frame's navigation reports, so a vehicle
that changes depth is followed too, and with ``s_y = 0`` the two agree.
(Eq. (8b) prints the ``s_y`` term with the opposite sign to eq. (12), from
which it is derived; eq. (12) is used, as the scenes' speeds are defined by
it: :func:`benchmark.modalities.camera.scenes.motion.vehicle_speeds`.)

The columns of ``Psi`` are the versors ``h``, ``v``, ``a`` of section II at
``(theta, sigma, xi)``, so the Jacobian ``F`` of eq. (14a) is the identity
plus the derivatives of ``Psi s tau`` along the angles
(:func:`~benchmark.modalities.camera.scenes.projection.camera_axes_derivatives`).
"""

from __future__ import annotations

import numpy as np

from benchmark.modalities.camera.model import VehicleSpeeds
from benchmark.modalities.camera.scenes.motion import psi_matrix
from benchmark.modalities.camera.scenes.projection import camera_axes_derivatives
from trackbench_foresti.measurement import PipeCamera, pose_angles


def speed_vector(speeds: VehicleSpeeds) -> np.ndarray:
    """``(s_x, s_y, s_z)`` of eq. (7) from a frame's navigation."""
    return np.array((speeds.lateral, speeds.vertical, speeds.frontal), dtype=float)


def advance(state: np.ndarray, speeds: np.ndarray, camera: PipeCamera) -> np.ndarray:
    """``f(x, u)``: the state one frame later, eqs. (7)-(10).

    Parameters
    ----------
    state : numpy.ndarray
        ``(C_x, C_y, theta, phi[, xi])``, m and rad.
    speeds : numpy.ndarray
        ``(s_x, s_y, s_z)`` in m/s, the vehicle frame.
    camera : PipeCamera
        For ``phi_0`` and ``tau``.

    References
    ----------
    seeds/004, eqs. (7), (8a)-(8b), (9a)-(9c), (10) and (12).
    """
    state = np.asarray(state, dtype=float)
    theta, phi, xi = pose_angles(state)
    moved = state.copy()
    moved[:2] += (psi_matrix(theta, phi - camera.nominal_tilt, xi) @ speeds)[:2] * camera.frame_interval_s
    return moved


def advance_jacobian(state: np.ndarray, speeds: np.ndarray, camera: PipeCamera) -> np.ndarray:
    """``F = df/dx`` of :func:`advance` at ``state`` (eq. 14a).

    References
    ----------
    seeds/004, eqs. (8a)-(8b), (12) and (14a).
    """
    state = np.asarray(state, dtype=float)
    theta, phi, xi = pose_angles(state)
    jacobian = np.eye(len(state))
    # Psi = axes(theta, sigma, xi)^T, and d sigma / d phi = 1.
    by_angle = camera_axes_derivatives(theta, phi - camera.nominal_tilt, xi)[: len(state) - 2]
    for column, d_axes in enumerate(by_angle, start=2):
        jacobian[:2, column] = (d_axes.T @ speeds)[:2] * camera.frame_interval_s
    return jacobian
