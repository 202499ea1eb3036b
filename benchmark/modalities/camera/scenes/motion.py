"""Camera trajectories and the speeds an inertial sensor reports.

A trajectory samples the six pose variables of seeds/004, section V,
``(Cx, Cy, Cz, theta, phi, xi)``, at every frame.  Each variable but ``Cz``
is a :class:`benchmark.scenes.signal.Signal` evaluated at the frame index: a
deterministic part (mean, slope, tapered sinusoids, smooth steps and
pulses) plus smoothed Gaussian noise drawn from the generator handed in.
``Cz`` integrates the forward speed.

The vehicle speeds follow eq. (7) of seeds/004,

    C_{k+1} = C_k + Psi_k (s_x, s_y, s_z)_k tau,

with ``Psi`` of eq. (12) and ``sigma_k = phi_k - phi_0`` (``phi_0`` the
mounting tilt): :func:`vehicle_speeds` solves it for ``s`` from consecutive
camera centres.  Its columns are ``h`` with the vehicle's pan and roll and
``v``, ``a`` with ``sigma`` in place of ``phi``, so at a level attitude
``s_x`` points to the right, ``s_z`` forward and ``s_y`` downwards.  (Eq.
(8b) prints the ``s_y`` term of ``C_y`` with the opposite sign; we follow
eq. (12), from which (8a)-(8b) are derived.)
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from benchmark.modalities.camera.model import CameraPose
from benchmark.modalities.camera.scenes.spec import MotionSpec
from benchmark.scenes.signal import evaluate_signal

CHANNELS = ("cx_m", "cy_m", "theta_deg", "phi_deg", "xi_deg", "speed_mps")


@dataclass(frozen=True)
class Trajectory:
    """Camera poses at frames ``0 .. n`` (one more than the sequence has).

    The extra sample gives the last frame's motion for eq. (7).  Angles are
    in rad, lengths in m.
    """

    cx: np.ndarray
    cy: np.ndarray
    cz: np.ndarray
    theta: np.ndarray
    phi: np.ndarray
    xi: np.ndarray

    def __len__(self) -> int:
        return len(self.cx)

    def pose(self, k: int) -> CameraPose:
        """The pose at frame ``k``."""
        return CameraPose(
            float(self.cx[k]),
            float(self.cy[k]),
            float(self.cz[k]),
            float(self.theta[k]),
            float(self.phi[k]),
            float(self.xi[k]),
        )

    def centres(self) -> np.ndarray:
        """Camera centres ``C_k``, shape ``(n + 1, 3)``."""
        return np.stack((self.cx, self.cy, self.cz), axis=1)


def build_trajectory(
    motion: MotionSpec, n_frames: int, frame_interval_s: float, rng: np.random.Generator
) -> Trajectory:
    """Sample a trajectory for ``n_frames`` frames (plus one).

    Parameters
    ----------
    motion : MotionSpec
        The signals of the pose and of the forward speed.
    n_frames : int
        Frames in the sequence.
    frame_interval_s : float
        ``tau``, the time between frames.
    rng : numpy.random.Generator
        Source of all trajectory noise; one independent child generator is
        spawned per channel, so changing one channel's noise leaves the
        others' alone.

    Returns
    -------
    Trajectory
        With ``n_frames + 1`` samples.

    References
    ----------
    seeds/004, section V-A: the state ``(Cx, Cy, Cz, theta, phi, xi)``.
    """
    n = n_frames + 1
    streams = dict(zip(CHANNELS, rng.spawn(len(CHANNELS))))
    values = {name: evaluate_signal(getattr(motion, name), n, streams[name]) for name in CHANNELS}
    speed = values["speed_mps"]
    cz = np.concatenate(([0.0], np.cumsum(speed[:-1] * frame_interval_s)))
    return Trajectory(
        cx=values["cx_m"],
        cy=values["cy_m"],
        cz=cz,
        theta=np.radians(values["theta_deg"]),
        phi=np.radians(values["phi_deg"]),
        xi=np.radians(values["xi_deg"]),
    )


def psi_matrix(theta: float, sigma: float, xi: float) -> np.ndarray:
    """The matrix ``Psi`` of seeds/004 eq. (12).

    Parameters
    ----------
    theta, sigma, xi : float
        Pan, ``sigma = phi - phi_0`` and roll in rad.

    Returns
    -------
    numpy.ndarray
        ``3 x 3``; the camera centre moves by ``Psi @ s * tau`` (eq. (7)).

    References
    ----------
    seeds/004, eqs. (7) and (12).
    """
    ct, st = math.cos(theta), math.sin(theta)
    cs, ss = math.cos(sigma), math.sin(sigma)
    cx, sx = math.cos(xi), math.sin(xi)
    return np.array(
        (
            (ct * cx, -ss * st * cx - cs * sx, cs * st * cx - ss * sx),
            (-sx * ct, -cs * cx + ss * st * sx, -ss * cx + st * sx * cs),
            (-st, -ss * ct, cs * ct),
        )
    )


def vehicle_speeds(trajectory: Trajectory, frame_interval_s: float, nominal_tilt: float) -> np.ndarray:
    """True vehicle speeds ``(s_x, s_y, s_z)`` at every frame, from eq. (7).

    Parameters
    ----------
    trajectory : Trajectory
        With ``n + 1`` samples.
    frame_interval_s : float
        ``tau``.
    nominal_tilt : float
        ``phi_0`` in rad, so that ``sigma_k = phi_k - phi_0``.

    Returns
    -------
    numpy.ndarray
        Shape ``(n, 3)``: the speeds ``s_k`` with
        ``C_{k+1} - C_k = Psi_k s_k tau``.

    References
    ----------
    seeds/004, eqs. (7) and (12).
    """
    steps = np.diff(trajectory.centres(), axis=0) / frame_interval_s
    speeds = np.empty_like(steps)
    for k, step in enumerate(steps):
        psi = psi_matrix(trajectory.theta[k], trajectory.phi[k] - nominal_tilt, trajectory.xi[k])
        speeds[k] = np.linalg.solve(psi, step)
    return speeds
