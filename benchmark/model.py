"""The data model: what flows from a dataset through a tracker into the scores.

A dataset is a :class:`Sequence`: a :class:`SequenceInfo` and a stream of
:class:`Frame` objects, produced one at a time so that nothing holds a whole
video in memory.  Each frame carries the sensor's observation, the navigation
data the platform reports, and the ground truth.

Camera frames are described by the cable model of the thesis (seeds/000,
section 4.2, Table 4.1) in the coordinates fixed by ``conventions.md``
section 1: a :class:`CableState` ``(d, alpha, w, beta)``.  A camera tracker's
estimate is also a :class:`CableState`.

Sonar frames are pings of a multibeam echo sounder looking down at a pipe
(seeds/003): the observation is a :class:`Swath` (where each beam met the
bottom), the truth a :class:`SonarTruth`, and an estimate a
:class:`PipeEstimate`, the pipe's across-track position in the swath.
Across-track positions are in m from the sonar's nadir, starboard
positive; depths are in m below the transducer.

Stereo frames follow a chase boat (CH) that tracks a target boat (TG) with a
stereo camera (seeds/002): the observation is a :class:`StereoMeasurement`,
the navigation CH's :class:`ChaseNavigation`, the truth a
:class:`StereoTruth`, and an estimate a :class:`TargetEstimate`.  Positions
are North-East coordinates in m (``X`` north, ``Y`` east) and headings are
clockwise from north, ``atan2(Y_dot, X_dot)`` (seeds/002, eq. 10, Fig. 3).
"""

from __future__ import annotations

import enum
import math
from abc import ABC, abstractmethod
from collections.abc import Iterator, Mapping
from dataclasses import dataclass, field
from typing import Any, Literal

import numpy as np

Modality = Literal["camera", "sonar", "stereo"]
MODALITIES: tuple[Modality, ...] = ("camera", "sonar", "stereo")


class Outcome(enum.StrEnum):
    """Per-frame detection outcome (seeds/004, section VI-C, Table V)."""

    CORRECT = "correct"
    FALSE = "false"
    MISSED = "missed"


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


@dataclass(frozen=True, slots=True)
class SonarCalibration:
    """The multibeam echo sounder and the pipe of a sonar sequence (seeds/003, section 4).

    Attributes
    ----------
    n_beams : int
        Beams per ping.
    swath_angle : float
        Full across-track opening of the fan, rad; the beams are equiangular
        within it.
    range_sigma_m : float
        Standard deviation of a beam's range measurement.
    pipe_diameter_m : float
        Outer diameter of the pipe the sequence follows (its coating included).
    """

    n_beams: int
    swath_angle: float
    range_sigma_m: float
    pipe_diameter_m: float

    @property
    def beam_spacing(self) -> float:
        """Angle between neighbouring beams, rad."""
        return self.swath_angle / max(self.n_beams - 1, 1)


def beam_footprint(across_m: np.ndarray, depth_m: np.ndarray, beam_spacing: float) -> np.ndarray:
    """Across-track distance between neighbouring beams at points of the swath plane.

    A beam at angle ``theta`` from the vertical meets a level bottom at
    ``x = z tan(theta)``, so beams ``d theta`` apart land ``z d theta /
    cos^2(theta) = (x^2 + z^2) d theta / z`` apart: the sonar's across-track
    resolution there, which :attr:`SonarTruth.resolution_m` gives at the pipe.

    Parameters
    ----------
    across_m, depth_m : numpy.ndarray
        Points, depth positive.
    beam_spacing : float
        ``d theta``, rad (:attr:`SonarCalibration.beam_spacing`).

    Returns
    -------
    numpy.ndarray
        The spacing, m; ``inf`` at or above the transducer.

    References
    ----------
    seeds/003, section 4.1: the accuracy "set by the sensor's resolution".
    """
    x = np.asarray(across_m, dtype=float)
    z = np.asarray(depth_m, dtype=float)
    safe = np.where(z > 0.0, z, 1.0)
    with np.errstate(over="ignore"):
        return np.where(z > 0.0, (x * x + z * z) * beam_spacing / safe, np.inf)


@dataclass(frozen=True, slots=True, eq=False)
class Swath:
    """One ping of a multibeam echo sounder: where each beam met the bottom.

    Beams are in port-to-starboard order.  A beam without a return is
    ``nan`` in both arrays.  Because the beams are equiangular, the
    across-track spacing of the returns grows away from nadir (seeds/003,
    section 2: the reason the detector resamples the scan).

    Attributes
    ----------
    across_m : numpy.ndarray
        Across-track position of each return, shape ``(n_beams,)``.
    depth_m : numpy.ndarray
        Depth of each return below the transducer, shape ``(n_beams,)``.

    Raises
    ------
    ValueError
        If the arrays are not one-dimensional float arrays of one length.
    """

    across_m: np.ndarray
    depth_m: np.ndarray

    def __post_init__(self) -> None:
        for label in ("across_m", "depth_m"):
            values = np.asarray(getattr(self, label), dtype=float)
            if values.ndim != 1:
                raise ValueError(f"swath {label} must be one-dimensional, got shape {values.shape}")
            object.__setattr__(self, label, values)
        if self.across_m.shape != self.depth_m.shape:
            raise ValueError(
                f"swath across_m and depth_m differ in shape: {self.across_m.shape} vs {self.depth_m.shape}"
            )

    @property
    def valid(self) -> np.ndarray:
        """Mask of the beams with a finite return."""
        return np.isfinite(self.across_m) & np.isfinite(self.depth_m)


@dataclass(frozen=True, slots=True)
class SonarTruth:
    """Ground truth of one ping.

    Attributes
    ----------
    across_m : float
        Across-track position of the pipe's axis.
    depth_m : float
        Depth of the pipe's axis below the transducer.
    burial : float
        Share of the pipe's diameter below the surrounding seabed: 0 proud,
        1 fully buried.
    resolution_m : float
        Across-track distance between neighbouring beams at the pipe: the
        sonar's resolution there, and the default tolerance of a correct
        detection (seeds/003, section 4.1).
    """

    across_m: float
    depth_m: float
    burial: float
    resolution_m: float


@dataclass(frozen=True, slots=True)
class PipeEstimate:
    """A sonar tracker's estimate: the pipe's across-track position in the swath, m (seeds/003, eq. 5)."""

    across_m: float


@dataclass(frozen=True, slots=True)
class StereoCalibration:
    """The stereo camera of a stereo sequence (seeds/002, Table 4 and eq. 15).

    Attributes
    ----------
    focal_px : float
        Focal length ``f`` in px.
    baseline_m : float
        Distance ``T_y`` between the two cameras.
    principal_left_px, principal_right_px : float
        Horizontal image coordinate of the principal point, ``C_y`` (left)
        and ``C_y*`` (right).
    width_px : int
        Horizontal resolution of each image.
    range_limit_m : float
        Operational range beyond which measurements are unreliable.
    correlation_accuracy_px : float
        ``m``: standard deviation of the disparity (seeds/002, eq. 19).
    """

    focal_px: float
    baseline_m: float
    principal_left_px: float
    principal_right_px: float
    width_px: int
    range_limit_m: float
    correlation_accuracy_px: float


@dataclass(frozen=True, slots=True)
class StereoMeasurement:
    """What the stereo front end reports about the target in one frame.

    Attributes
    ----------
    left_px, right_px : float
        Horizontal image coordinates ``y_l`` and ``y_r`` of the target in
        the left and right images (seeds/002, eqs. 13 and 15); their
        difference is the disparity ``d = y_l - y_r``.
    relative_m : tuple of float
        ``(x_v, y_v)``: the target relative to the camera by triangulation
        (seeds/002, eq. 15), ``x_v`` ahead, ``y_v`` to starboard.
    """

    left_px: float
    right_px: float
    relative_m: tuple[float, float]


@dataclass(frozen=True, slots=True)
class ChaseNavigation:
    """The chase boat's own sensors: GPS position (North-East, m) and heading (rad)."""

    position_m: tuple[float, float]
    heading: float


@dataclass(frozen=True, slots=True)
class TargetEstimate:
    """Position and velocity of the target boat, North-East (seeds/002, eq. 5 state)."""

    position_m: tuple[float, float]
    velocity_mps: tuple[float, float]

    @property
    def speed_mps(self) -> float:
        return math.hypot(*self.velocity_mps)

    @property
    def heading(self) -> float:
        """Clockwise from north, rad: ``atan2(Y_dot, X_dot)``."""
        return math.atan2(self.velocity_mps[1], self.velocity_mps[0])


@dataclass(frozen=True, slots=True)
class StereoTruth:
    """Ground truth of one stereo frame.

    Attributes
    ----------
    target : TargetEstimate
        The target's true position and velocity (speed and heading follow).
    chase_position_m : tuple of float
        The chase boat's true position.
    chase_heading : float
        The chase boat's true heading, rad.
    """

    target: TargetEstimate
    chase_position_m: tuple[float, float]
    chase_heading: float

    @property
    def range_m(self) -> float:
        """Distance between the boats."""
        return math.dist(self.target.position_m, self.chase_position_m)


@dataclass(frozen=True, slots=True)
class Frame:
    """One time step of a sequence.

    Attributes
    ----------
    index : int
        Position in the sequence, from 0.
    observation : Any
        Camera: a ``uint8`` grey image of shape ``(H, W)``.  Sonar: a
        :class:`Swath`.  Stereo: a
        :class:`StereoMeasurement`, None when the front end lost the target,
        or (image suites) a pair of images ``(left, right)``.
    truth : Any
        Ground truth for the modality (camera: :class:`CameraTruth`,
        sonar: :class:`SonarTruth`, stereo: :class:`StereoTruth`), or None.
    navigation : Any
        Navigation data where the platform has it (camera:
        :class:`VehicleSpeeds`, stereo: :class:`ChaseNavigation`).
    time_s : float
        Time stamp in s from the start of the sequence.
    """

    index: int
    observation: Any
    truth: Any = None
    navigation: Any = None
    time_s: float = 0.0


@dataclass(frozen=True)
class SequenceInfo:
    """What a tracker may know about a sequence before its first frame.

    Attributes
    ----------
    name : str
        Name used in results: ``suite/sequence`` or the path of a file.
    modality : {"camera", "sonar", "stereo"}
        The sensor the frames come from.
    n_frames : int or None
        Number of frames, where known in advance.
    frame_size : tuple of int or None
        Camera: ``(W, H)`` in px.
    frame_interval_s : float or None
        Time between frames.
    calibration : Any
        Camera: a :class:`CameraCalibration` where the data set knows it;
        sonar: a :class:`SonarCalibration`; stereo: a :class:`StereoCalibration`.
    extra : Mapping
        Anything else a data set wants to tell (description, source).
    """

    name: str
    modality: Modality
    n_frames: int | None = None
    frame_size: tuple[int, int] | None = None
    frame_interval_s: float | None = None
    calibration: Any = None
    extra: Mapping[str, Any] = field(default_factory=dict)


class Sequence(ABC):
    """A stream of frames with its :class:`SequenceInfo`.

    Implementations produce frames lazily and must be picklable (cells run in
    worker processes), so they hold a definition or a path, never decoded
    frames.
    """

    @property
    @abstractmethod
    def info(self) -> SequenceInfo:
        """Describe the sequence."""

    @abstractmethod
    def frames(self) -> Iterator[Frame]:
        """Yield the frames in order, one at a time."""

    def __iter__(self) -> Iterator[Frame]:
        return self.frames()

    def __repr__(self) -> str:
        return f"<{type(self).__name__} {self.info.name!r}>"
