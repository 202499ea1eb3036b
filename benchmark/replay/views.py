"""What a replay shows of a frame, per modality: its picture, its states as numbers and the marks drawn on it.

A :class:`ReplayView` turns one modality's frames, truths, estimates and
beliefs into what the page draws: a JPEG of the observation, each state as
a vector with named components, and :class:`Mark` shapes in the picture's
pixels.  A mark has a role (truth, estimate, the frame's measurement, a
particle, an estimate's covariance) that the page's one drawing routine
turns into a colour; the marks of a truth or an estimate take their role
from the state they draw.  Where the picture draws a plane (a swath's
profile, a map of the sea), its :class:`PlaneMap` says where that plane's
points land, so that marks can be placed from states and beliefs.
The registry (:func:`view_of`) holds one view per modality name: the camera's
(:mod:`benchmark.replay.camera`), the sonar's (:mod:`benchmark.replay.sonar`)
and the stereo camera's (:mod:`benchmark.replay.stereo`).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Literal, Protocol

import numpy as np

from benchmark.errors import TrackbenchError
from benchmark.model import Frame

if TYPE_CHECKING:
    from benchmark.drawing import Viewport
    from benchmark.replay.record import Belief

Segment = tuple[float, float, float, float]
"""A line segment ``(u1, v1, u2, v2)`` in the pixels of a frame's picture."""

Shape = Literal["segment", "ellipse", "cross", "ticks", "strokes"]
"""How a mark's points are drawn; see :class:`Mark`."""

Role = Literal["truth", "estimate", "measurement", "particle", "covariance", "window"]
"""What a mark shows; the page gives each role its colour (truth green, estimate red)."""

MAX_RADIUS_PX = 1e5
"""Largest radius of an ellipse mark, px: a covariance beyond it is drawn at it."""


@dataclass(frozen=True)
class Mark:
    """A shape drawn on a frame's picture, in its canvas coordinates (pixel edges at integers).

    Attributes
    ----------
    shape : Shape
        ``"segment"``: points ``(u1, v1, u2, v2)``.
        ``"ellipse"``: ``(u, v, radius_u, radius_v, angle)``, the angle (rad)
        turning the first axis from ``+u`` towards ``+v``.
        ``"cross"``: ``(u, v, half_size)``.
        ``"ticks"``: ``(v, length, u_1, w_1, u_2, w_2, ...)``, one vertical
        tick per ``(u_k, w_k)`` from row ``v`` over ``length * w_k`` px
        (down for a positive length), ``w_k`` in ``[0, 1]`` also its opacity.
        ``"strokes"``: ``(w_1, u1_1, v1_1, u2_1, v2_1, w_2, ...)``, one line
        per five numbers, ``w_k`` in ``[0, 1]`` its opacity.
    points : tuple of float
        The shape's numbers.
    role : Role or None
        What it shows; None for the truth or estimate whose overlay it is.
    """

    shape: Shape
    points: tuple[float, ...]
    role: Role | None = None

    @classmethod
    def segment(cls, segment: Segment, role: Role | None = None) -> Mark:
        """A line from ``(u1, v1)`` to ``(u2, v2)``."""
        return cls("segment", tuple(float(p) for p in segment), role)

    @classmethod
    def circle(cls, u: float, v: float, radius: float, role: Role | None = None) -> Mark:
        """A circle of ``radius`` px around ``(u, v)``."""
        return cls("ellipse", (float(u), float(v), float(radius), float(radius), 0.0), role)

    @classmethod
    def cross(cls, u: float, v: float, half_size: float, role: Role | None = None) -> Mark:
        """An upright cross centred on ``(u, v)``."""
        return cls("cross", (float(u), float(v), float(half_size)), role)

    @property
    def finite(self) -> bool:
        """Whether every number of the mark is finite (a page draws only those)."""
        return all(math.isfinite(p) for p in self.points)


@dataclass(frozen=True)
class PlaneMap:
    """Where the points of a plane land on a picture: ``u = u0 + du x``, ``v = v0 + dv y`` (canvas coordinates).

    Attributes
    ----------
    u0, du, v0, dv : float
        The affine map; ``du``, ``dv`` are px per unit of the plane, negative
        where the picture's axis runs against the plane's (north up).
    box : tuple of float
        ``(u_low, v_low, u_high, v_high)``: the part of the picture that
        shows the plane; points are placed within it.
    """

    u0: float
    du: float
    v0: float
    dv: float
    box: tuple[float, float, float, float]

    @classmethod
    def of(cls, viewport: Viewport, offset: tuple[int, int] = (0, 0)) -> PlaneMap:
        """The map a :class:`~benchmark.drawing.Viewport` draws with, its picture pasted at ``offset`` (px)."""
        du = (viewport.width - 1) / (viewport.right - viewport.left)
        dv = (viewport.height - 1) / (viewport.bottom - viewport.top)
        u0 = offset[0] + 0.5 - viewport.left * du
        v0 = offset[1] + 0.5 - viewport.top * dv
        u, v = float(offset[0]), float(offset[1])
        box = (u, v, u + viewport.width, v + viewport.height)
        return cls(u0, du, v0, dv, box)

    def point(self, x: float, y: float) -> tuple[float, float]:
        """The canvas point of the plane point ``(x, y)``, moved into :attr:`box` when it lies outside."""
        u_low, v_low, u_high, v_high = self.box
        u, v = self.u0 + self.du * x, self.v0 + self.dv * y
        return min(max(u, u_low), u_high), min(max(v, v_low), v_high)

    def ellipse(
        self, centre: tuple[float, float], covariance: np.ndarray, sigmas: float = 2.0, role: Role | None = None
    ) -> Mark:
        """The ``sigmas``-sigma ellipse of a Gaussian of the plane, ``covariance`` ``(2, 2)`` in ``(x, y)``.

        The covariance maps to the canvas as ``J C J^T`` with ``J = diag(du, dv)``;
        its eigenvectors are the ellipse's axes and ``sigmas`` times the
        square roots of its eigenvalues their half-lengths: the points at
        Mahalanobis distance ``sigmas`` from the centre.  The centre is not
        moved into :attr:`box` (the page clips the ellipse to it).
        """
        jacobian = np.diag([self.du, self.dv])
        pixels = jacobian @ np.asarray(covariance, dtype=float) @ jacobian.T
        values, vectors = np.linalg.eigh((pixels + pixels.T) / 2)
        radii = sigmas * np.sqrt(np.clip(values, 0.0, None))
        angle = math.atan2(vectors[1, 1], vectors[0, 1])  # the axis of the larger eigenvalue
        u, v = self.u0 + self.du * centre[0], self.v0 + self.dv * centre[1]
        major, minor = (min(float(r), MAX_RADIUS_PX) for r in radii[::-1])
        return Mark("ellipse", (u, v, major, minor, angle), role)


@dataclass(frozen=True)
class Picture:
    """A frame's picture as the page shows it.

    Attributes
    ----------
    jpeg : bytes
        The JPEG file.
    width, height : int
        Its size in px.
    plane : PlaneMap or None
        Where the plane the picture draws (if it draws one) lands on it.
    marks : tuple of Mark
        What the frame itself shows beside its picture: its measurement.
    source_size : tuple of int or None
        ``(W, H)`` of the image the picture shows, where it is one (it may be scaled down).
    """

    jpeg: bytes
    width: int
    height: int
    plane: PlaneMap | None = None
    marks: tuple[Mark, ...] = ()
    source_size: tuple[int, int] | None = None


class ReplayView(Protocol):
    """How the replay page shows the frames of one modality."""

    dimensions: tuple[str, ...]
    """Names (with units) of the components of a state, in the order of a tracker's belief."""

    def picture(self, frame: Frame) -> Picture:
        """The frame's observation as a small JPEG."""

    def state(self, value: Any) -> tuple[float, ...] | None:
        """A truth or an estimate as the vector of :attr:`dimensions`; None for none or an unknown state."""

    def overlay(self, value: Any, frame: Frame, picture: Picture) -> list[Mark]:
        """The marks that draw a truth or an estimate on ``picture`` (role None); empty for none."""

    def belief_marks(self, belief: Belief, picture: Picture) -> list[Mark]:
        """The marks that draw a tracker's belief on ``picture`` (particles, a covariance); empty if it draws none."""

    def region_marks(self, region: Any, picture: Picture) -> list[Mark]:
        """The marks (role ``"window"``) that draw the part of the frame a tracker searched
        (:class:`~benchmark.tracker.Searches`); empty if the view draws none."""


class NoViewError(TrackbenchError):
    """The replay has no view of a modality yet."""


def _views() -> Mapping[str, ReplayView]:
    from benchmark.replay.camera import CameraView
    from benchmark.replay.sonar import SonarView
    from benchmark.replay.stereo import StereoView

    return {"camera": CameraView(), "sonar": SonarView(), "stereo": StereoView()}


def view_of(modality: str) -> ReplayView:
    """The view of the modality named ``modality``.

    Raises
    ------
    NoViewError
        For a modality without a view, naming those that have one.
    """
    views = _views()
    if modality not in views:
        raise NoViewError(f"replay cannot show {modality} frames yet (it shows: {', '.join(sorted(views))})")
    return views[modality]
