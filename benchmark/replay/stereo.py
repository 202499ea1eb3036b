"""The stereo modality's replay view: a map of the sea from above, with the image pair above it where there is one.

The map is drawn as :func:`benchmark.modalities.stereo.draw.draw_stereo_frame`
draws it, in the modality's North-East frame (seeds/002, eq. 10, Fig. 3):
north up and east to the right at one scale, around the target, the chase
boat and the measurement, with a grid whose spacing is written in a
corner and the chase boat (CH) in grey.  The state is the filter's
``[X, Y, X_dot, Y_dot]`` (North, East, seeds/002 eq. 5).  The truth and an
estimate are drawn as a boat (a circle and a line along its heading), the
frame's measurement (triangulated, eq. 15, and turned North-East by CH's
own navigation, eq. 10) as a cross, and a Gaussian belief as the 2-sigma
ellipse of its position block.  An image pair (the stereo-images suite) is
shown left and right side by side above the map, each
:data:`PAIR_WIDTH` px wide; its frames have no measurement to mark (finding
the target in them is the tracker's front end).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

import cv2
import numpy as np

from benchmark.drawing import DATA_BGR, Colour, Viewport
from benchmark.errors import DataError
from benchmark.modalities.stereo.draw import draw_boat, map_around, measured_position
from benchmark.modalities.stereo.model import ChaseNavigation, StereoTruth, TargetEstimate
from benchmark.model import Frame
from benchmark.replay.jpeg import encode_jpeg, shrunk_to_width
from benchmark.replay.views import Mark, Picture, PlaneMap

if TYPE_CHECKING:
    from benchmark.replay.record import Belief

MAP_SIZE = (480, 320)
"""Width and height of the map, px."""

PAIR_WIDTH = 240
"""Width of each image of a pair above the map, px."""

BOAT_RADIUS_PX = 5.0
HEADING_PX = 16.0
CROSS_PX = 6.0

GRID_LINES = 6
"""About how many grid lines span the map's width."""

SEA_BGR: Colour = (250, 246, 240)
GRID_BGR: Colour = (225, 215, 205)
LABEL_BGR: Colour = (90, 90, 90)

COVARIANCE_SIGMAS = 2.0
"""The ellipse of a Gaussian belief joins the positions this many standard deviations from its mean (Mahalanobis)."""


class StereoView:
    """The replay view of stereo frames (:class:`~benchmark.replay.views.ReplayView`)."""

    dimensions = ("north_m", "east_m", "north_mps", "east_mps")
    """The target's ``[X, Y, X_dot, Y_dot]``, North-East (seeds/002, eq. 5), the order of the filter's state."""

    def picture(self, frame: Frame) -> Picture:
        """The map of the frame (and its image pair above it, if it has one) as a JPEG, with the measurement's cross."""
        pair = _pair(frame)
        truth = frame.truth if isinstance(frame.truth, StereoTruth) else None
        chase = _chase(frame)
        measured = measured_position(frame)
        shown = [p for p in (truth.target.position_m if truth else None, chase[0] if chase else None, measured) if p]
        width, height = MAP_SIZE
        view = map_around(shown, width, height)
        sea = view.blank(SEA_BGR)
        _draw_grid(sea, view)
        if chase is not None:
            draw_boat(sea, view, chase[0], chase[1], DATA_BGR)
        image = sea if pair is None else np.vstack([pair, sea])
        plane = PlaneMap.of(view, (0, 0 if pair is None else pair.shape[0]))
        marks = []
        if measured is not None:
            marks.append(Mark.cross(*plane.point(measured[1], measured[0]), CROSS_PX, "measurement"))
        jpeg = encode_jpeg(image, f"frame {frame.index}")
        return Picture(jpeg, int(image.shape[1]), int(image.shape[0]), plane=plane, marks=tuple(marks))

    def state(self, value: Any) -> tuple[float, ...] | None:
        """A :class:`StereoTruth`'s target or a :class:`TargetEstimate` as ``(X, Y, X_dot, Y_dot)``; else None."""
        target = value.target if isinstance(value, StereoTruth) else value
        if not isinstance(target, TargetEstimate):
            return None
        return (*(float(v) for v in target.position_m), *(float(v) for v in target.velocity_mps))

    def overlay(self, value: Any, frame: Frame, picture: Picture) -> list[Mark]:
        """The target as a boat on the map: a circle at its position and a line along its heading if it moves."""
        state = self.state(value)
        plane = picture.plane
        if state is None or plane is None or not all(math.isfinite(v) for v in state[:2]):
            return []
        north, east, north_speed, east_speed = state
        u, v = plane.point(east, north)
        marks = [Mark.circle(u, v, BOAT_RADIUS_PX)]
        along = np.array([plane.du * east_speed, plane.dv * north_speed])
        length = float(np.hypot(*along))
        if math.isfinite(length) and length > 0:
            du, dv = along / length * HEADING_PX
            marks.append(Mark.segment((u, v, u + du, v + dv)))
        return marks

    def belief_marks(self, belief: Belief, picture: Picture) -> list[Mark]:
        """A Gaussian's 2-sigma ellipse (:data:`COVARIANCE_SIGMAS`) of its position block, on the map."""
        plane, mean, covariance = picture.plane, belief.mean, belief.covariance
        if plane is None or mean is None or covariance is None or mean.size < 2 or covariance.shape[0] < 2:
            return []
        east_north = [1, 0]
        block = covariance[np.ix_(east_north, east_north)]
        if not (np.all(np.isfinite(block)) and np.all(np.isfinite(mean[:2]))):
            return []
        return [plane.ellipse((mean[1], mean[0]), block, COVARIANCE_SIGMAS, "covariance")]


def _chase(frame: Frame) -> tuple[tuple[float, float], float] | None:
    """CH's position and heading: the truth's, else its own navigation's, else None."""
    if isinstance(frame.truth, StereoTruth):
        return frame.truth.chase_position_m, frame.truth.chase_heading
    if isinstance(frame.navigation, ChaseNavigation):
        return frame.navigation.position_m, frame.navigation.heading
    return None


def _pair(frame: Frame) -> np.ndarray | None:
    """The frame's image pair side by side, each :data:`PAIR_WIDTH` px wide, or None for a frame without images."""
    observation = frame.observation
    if not isinstance(observation, (tuple, list)) or len(observation) != 2:
        return None
    sides = []
    for image in observation:
        image = np.asarray(image)
        if image.ndim == 2:
            image = cv2.cvtColor(image, cv2.COLOR_GRAY2BGR)
        if image.ndim != 3 or image.shape[2] != 3 or image.dtype != np.uint8:
            raise DataError(f"frame {frame.index}: an image of the pair is a {image.dtype} array of {image.shape}")
        sides.append(shrunk_to_width(image, PAIR_WIDTH))
    height = sides[0].shape[0]
    sides = [
        side if side.shape[:2] == (height, PAIR_WIDTH) else cv2.resize(side, (PAIR_WIDTH, height))
        for side in sides
    ]
    return np.hstack(sides)


def grid_step(span_m: float, lines: int = GRID_LINES) -> float:
    """The spacing of 1, 2 or 5 times a power of ten, m, that draws about ``lines`` grid lines over ``span_m``."""
    rough = max(span_m, 1e-9) / lines
    power = 10.0 ** math.floor(math.log10(rough))
    return next(step * power for step in (1.0, 2.0, 5.0, 10.0) if step * power >= rough)


def _draw_grid(image: np.ndarray, view: Viewport) -> None:
    """Lines every :func:`grid_step` metres north and east, its spacing and north written in the top corners."""
    step = grid_step(abs(view.right - view.left))
    for east in np.arange(math.ceil(view.left / step) * step, view.right, step):
        u, _ = view.pixel(float(east), view.top)
        cv2.line(image, (u, 0), (u, view.height - 1), GRID_BGR, 1)
    low, high = sorted((view.top, view.bottom))
    for north in np.arange(math.ceil(low / step) * step, high, step):
        _, v = view.pixel(view.left, float(north))
        cv2.line(image, (0, v), (view.width - 1, v), GRID_BGR, 1)
    font, scale = cv2.FONT_HERSHEY_SIMPLEX, 0.4
    cv2.putText(image, f"grid {step:g} m", (4, 13), font, scale, LABEL_BGR, 1, cv2.LINE_AA)
    cv2.putText(image, "N ^", (view.width - 30, 13), font, scale, LABEL_BGR, 1, cv2.LINE_AA)

    def region_marks(self, region: Any, picture: Picture) -> list[Mark]:
        """None: no first-party stereo tracker declares a search region yet."""
        return []
