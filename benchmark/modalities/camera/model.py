"""What camera frames hold: the cable state, the camera pose and the truth.

Camera frames are described by the cable model of the thesis (seeds/000,
section 4.2, Table 4.1) in the coordinates fixed by ``conventions.md``
section 1: a :class:`CableState` ``(d, alpha, w, beta)``.  A camera
tracker's estimate is also a :class:`CableState`.  A frame's observation is
a ``uint8`` grey image of shape ``(H, W)``, its truth a :class:`CameraTruth`
and its navigation the :class:`VehicleSpeeds` of seeds/004 eq. (7).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from benchmark.model import Frame


@dataclass(frozen=True, slots=True)
class CableState:
    """A cable in the image, as the thesis parameterises it.

    Attributes
    ----------
    d : float
        Signed distance in px from the image centre to the centreline,
        measured along the unit normal ``n = (cos alpha, sin alpha)``.
    alpha : float
        Angle of the centreline in rad; 0 is a vertical cable, positive
        turns it counter-clockwise.
    w : float
        Cable width in px, measured along ``n`` through the foot point.
    beta : float
        Skew in rad: the angle each border makes with the centreline.  Ground
        truth has ``beta >= 0`` (borders converge towards the top); an
        estimate may report ``beta < 0`` for borders that diverge.

    References
    ----------
    seeds/000, section 4.2 and Table 4.1; conventions.md section 1.
    """

    d: float
    alpha: float
    w: float
    beta: float

    def as_array(self) -> np.ndarray:
        """The state as a float array ``[d, alpha, w, beta]``."""
        return np.array([self.d, self.alpha, self.w, self.beta], dtype=float)

    @classmethod
    def from_array(cls, values: Any) -> CableState:
        """Build a state from any four numbers ``[d, alpha, w, beta]``."""
        d, alpha, w, beta = (float(v) for v in np.asarray(values, dtype=float).reshape(4))
        return cls(d, alpha, w, beta)

    @property
    def is_known(self) -> bool:
        """True when all four parameters are finite (a ``nan`` row is unknown)."""
        return all(math.isfinite(v) for v in (self.d, self.alpha, self.w, self.beta))


UNKNOWN_CABLE = CableState(math.nan, math.nan, math.nan, math.nan)



@dataclass(frozen=True, slots=True)
class CameraPose:
    """Camera pose in the pipeline frame of seeds/004, section II.

    ``Z`` runs along the pipe axis, ``X`` is horizontal and ``Y`` points up;
    the pipe axis is the ``Z`` axis itself.

    Attributes
    ----------
    cx, cy, cz : float
        Camera centre in m.
    theta, phi, xi : float
        Pan, tilt and roll in rad (seeds/004, Fig. 2).
    """

    cx: float
    cy: float
    cz: float
    theta: float
    phi: float
    xi: float


@dataclass(frozen=True, slots=True)
class PosedCableState(CableState):
    """A camera estimate that also reports the camera's pose, as seeds/004's EKF does.

    Scored like any :class:`CableState` by its border lines; where the truth
    knows the pose, the pose errors are scored too
    (:class:`~benchmark.modalities.camera.scoring.CameraScorer`).

    Attributes
    ----------
    pose : CameraPose
        The estimated pose (``cz`` may be 0 when the tracker does not estimate it).
    pose_variance : tuple of float
        Variances of ``cx``, ``cy`` (m^2), ``theta`` and ``phi`` (rad^2): the
        diagonal of the filter's covariance.
    """

    pose: CameraPose | None = None
    pose_variance: tuple[float, float, float, float] | None = None


@dataclass(frozen=True, slots=True)
class VehicleSpeeds:
    """Speeds an inertial sensor reports, in the vehicle frame (m/s).

    These are ``(s_x, s_y, s_z)`` of seeds/004 eq. (7): the camera centre
    moves by ``Psi @ (s_x, s_y, s_z) * tau`` between two frames.
    """

    lateral: float
    vertical: float
    frontal: float


@dataclass(frozen=True, slots=True)
class CameraCalibration:
    """What a camera sequence knows about its optics and its pipe.

    Attributes
    ----------
    focal_px : float
        Focal length over pixel pitch, ``f / delta_x`` (seeds/004 eq. 3).
    pipe_diameter_m : float
        Diameter of the cylinder that is the pipe or cable.
    nominal_tilt : float
        The tilt ``phi`` the camera is mounted at (seeds/004, ``sigma = phi - phi_0``).
    """

    focal_px: float
    pipe_diameter_m: float
    nominal_tilt: float


@dataclass(frozen=True, slots=True)
class CameraTruth:
    """Ground truth of one camera frame.

    Attributes
    ----------
    cable : CableState
        The projected cable; :data:`UNKNOWN_CABLE` when the frame is unlabelled.
    pose : CameraPose or None
        Camera pose, where the data set knows it (rendered scenes do).
    visible_fraction : float or None
        Share of the in-image cable length not hidden by sand, in [0, 1].
    """

    cable: CableState
    pose: CameraPose | None = None
    visible_fraction: float | None = None



CameraFrame = Frame[np.ndarray, CameraTruth]
"""A camera frame: a ``uint8`` grey image ``(H, W)``, a :class:`CameraTruth` or None, and :class:`VehicleSpeeds`."""
