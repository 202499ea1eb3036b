"""Pictures of stereo frames: a North-East map of the boats, the measurement and the estimate.

A frame is drawn as a small map, north up and east to the right at one
scale: the chase boat's true position and heading in grey, the target's
true position and heading in green, the target as the frame's measurement
puts it (triangulated and turned into North-East by the chase boat's own
navigation, seeds/002 eqs. 10 and 15) as a yellow cross, and the tracker's
estimated position and heading in red.  An image pair is not measured here
(that is the tracker's front end), so its frames show no cross.  An
estimate farther than :data:`REACH_M` from the true target (or, without a
truth, from the measurement) is drawn at the edge.
"""

from __future__ import annotations

import math

import cv2
import numpy as np

from benchmark.drawing import DATA_BGR, ESTIMATE_BGR, TRUTH_BGR, Colour, Viewport
from benchmark.modalities.stereo.geometry import to_north_east
from benchmark.modalities.stereo.model import ChaseNavigation, StereoMeasurement, StereoTruth, TargetEstimate
from benchmark.model import Frame

PICTURE_SIZE = 240
"""Side of a stereo picture, px."""

MIN_SPAN_M = 10.0
"""Smallest stretch of sea a picture shows, m."""

REACH_M = 1000.0
"""Farthest an estimate may be from the true target and still widen the map to its place, m."""

MEASUREMENT_BGR: Colour = (0, 255, 255)
"""Yellow: the target where the frame's measurement puts it."""

_HEADING_PX = 14


def draw_stereo_frame(frame: Frame, estimate: TargetEstimate | None) -> np.ndarray:
    """A map of the true boats in green and grey, the measurement in yellow and the estimate in red.

    Parameters
    ----------
    frame : Frame
        A stereo frame: a measurement, None or an image pair, a
        :class:`~benchmark.modalities.stereo.model.StereoTruth` or None and
        the chase boat's :class:`~benchmark.modalities.stereo.model.ChaseNavigation`.
    estimate : TargetEstimate or None
        The tracker's estimate; None draws nothing for it.

    Returns
    -------
    numpy.ndarray
        A square ``uint8`` BGR picture of side :data:`PICTURE_SIZE`.

    References
    ----------
    seeds/002, eq. (10) (camera frame to North-East) and Fig. 3 (headings
    clockwise from north).
    """
    truth = frame.truth if isinstance(frame.truth, StereoTruth) else None
    measured = measured_position(frame)
    known: list[tuple[float, float]] = []
    if truth is not None:
        known += [truth.target.position_m, truth.chase_position_m]
    if measured is not None:
        known.append(measured)
    shown = list(known)
    if estimate is not None:
        shown.append(_within(estimate.position_m, known[0], REACH_M) if known else estimate.position_m)
    view = map_around(shown, PICTURE_SIZE, PICTURE_SIZE)
    picture = view.blank()
    if truth is not None:
        draw_boat(picture, view, truth.chase_position_m, truth.chase_heading, DATA_BGR)
    if measured is not None:
        cv2.drawMarker(picture, view.pixel(measured[1], measured[0]), MEASUREMENT_BGR, cv2.MARKER_CROSS, 9)
    if truth is not None:
        target = truth.target
        draw_boat(picture, view, target.position_m, target.heading if target.speed_mps > 0 else None, TRUTH_BGR)
    if estimate is not None:
        heading = estimate.heading if estimate.speed_mps > 0 else None
        draw_boat(picture, view, estimate.position_m, heading, ESTIMATE_BGR)
    return picture


def map_around(positions: list[tuple[float, float]], width: int, height: int) -> Viewport:
    """The map of the North-East ``positions`` (north up, one scale, at least :data:`MIN_SPAN_M` across)."""
    return Viewport.around(
        [east for _, east in positions],
        [north for north, _ in positions],
        width,
        height,
        min_span=MIN_SPAN_M,
        y_up=True,
        equal_scale=True,
    )


def measured_position(frame: Frame) -> tuple[float, float] | None:
    """North-East position of the target by the frame's measurement and navigation, if it has both."""
    if not (isinstance(frame.observation, StereoMeasurement) and isinstance(frame.navigation, ChaseNavigation)):
        return None
    ahead, starboard = frame.observation.relative_m
    north, east = to_north_east(ahead, starboard, frame.navigation.position_m, frame.navigation.heading)
    return (north, east) if math.isfinite(north) and math.isfinite(east) else None


def _within(point: tuple[float, float], centre: tuple[float, float], reach: float) -> tuple[float, float]:
    """``point`` with each coordinate clipped to ``reach`` of ``centre``."""
    return (
        min(max(point[0], centre[0] - reach), centre[0] + reach),
        min(max(point[1], centre[1] - reach), centre[1] + reach),
    )


def draw_boat(
    picture: np.ndarray, view: Viewport, position_m: tuple[float, float], heading: float | None, colour: Colour
) -> None:
    """A circle at a North-East position and, given a heading (clockwise from north), a line along it."""
    u, v = view.pixel(position_m[1], position_m[0])
    cv2.circle(picture, (u, v), 4, colour, 1)
    if heading is not None and math.isfinite(heading):
        tip = (round(u + _HEADING_PX * math.sin(heading)), round(v - _HEADING_PX * math.cos(heading)))
        cv2.line(picture, (u, v), tip, colour, 1)
