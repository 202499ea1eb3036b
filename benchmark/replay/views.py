"""What a replay shows of a frame, per modality: its picture, its states as numbers and the lines drawn on it.

A :class:`ReplayView` turns one modality's frames, truths and estimates
into what the page draws: a JPEG of the observation, each state as a
vector with named components, and the overlay lines of a state in the
picture's pixels.  :data:`VIEWS` holds one view per modality name; the
camera's is the first (:mod:`benchmark.replay.camera`), sonar and stereo
views are still to come.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any, Protocol

from benchmark.errors import TrackbenchError
from benchmark.model import Frame

Segment = tuple[float, float, float, float]
"""A line segment ``(u1, v1, u2, v2)`` in the pixels of a frame's picture."""


@dataclass(frozen=True)
class Picture:
    """A frame's picture as the page shows it.

    Attributes
    ----------
    jpeg : bytes
        The JPEG file.
    width, height : int
        Its size in px.
    """

    jpeg: bytes
    width: int
    height: int


class ReplayView(Protocol):
    """How the replay page shows the frames of one modality."""

    dimensions: tuple[str, ...]
    """Names (with units) of the components of a state, in the order of a tracker's belief."""

    def picture(self, frame: Frame) -> Picture:
        """The frame's observation as a small JPEG."""

    def state(self, value: Any) -> tuple[float, ...] | None:
        """A truth or an estimate as the vector of :attr:`dimensions`; None for none or an unknown state."""

    def overlay(self, value: Any, frame: Frame, picture: Picture) -> list[Segment]:
        """The lines that draw a truth or an estimate on ``picture``; empty for none."""


class NoViewError(TrackbenchError):
    """The replay has no view of a modality yet."""


def _views() -> Mapping[str, ReplayView]:
    from benchmark.replay.camera import CameraView

    return {"camera": CameraView()}


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
