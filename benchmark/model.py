"""The data model: what flows from a dataset through a tracker into the scores.

A dataset is a :class:`Sequence`: a :class:`SequenceInfo` and a stream of
:class:`Frame` objects, produced one at a time so that nothing holds a whole
video in memory.  Each frame carries the sensor's observation, the navigation
data the platform reports, and the ground truth.

Camera frames are described by the cable model of the thesis (seeds/000,
section 4.2, Table 4.1) in the coordinates fixed by ``conventions.md``
section 1: a :class:`CableState` ``(d, alpha, w, beta)``.  A camera tracker's
estimate is also a :class:`CableState`.  Sonar and stereo modalities add
their own truth and estimate types beside these.
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
class Frame:
    """One time step of a sequence.

    Attributes
    ----------
    index : int
        Position in the sequence, from 0.
    observation : numpy.ndarray
        Camera: a ``uint8`` grey image of shape ``(H, W)``.
    truth : Any
        Ground truth for the modality (camera: :class:`CameraTruth`), or None.
    navigation : Any
        Navigation data where the platform has it (camera: :class:`VehicleSpeeds`).
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
        Camera: a :class:`CameraCalibration` where the data set knows it.
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
