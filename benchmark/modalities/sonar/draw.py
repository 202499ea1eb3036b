"""Pictures of sonar pings: the swath's profile with the true pipe and the estimated position.

A ping is drawn in the swath plane, across-track to the right (starboard)
and depth downwards, each axis stretched to fit the returns and the pipe
(the scales differ: a swath is far wider than it is deep).  The beams'
returns are grey points, the pipe's axis a green circle, and the tracker's
across-track estimate (seeds/003, eq. 5) a red vertical line, at the edge
of the picture when it lies outside the swath.
"""

from __future__ import annotations

import math

import cv2
import numpy as np

from benchmark.drawing import DATA_BGR, ESTIMATE_BGR, TRUTH_BGR, Viewport
from benchmark.modalities.sonar.model import PipeEstimate, SonarTruth, Swath
from benchmark.model import Frame

PICTURE_SIZE = (320, 160)
"""Width and height of a sonar picture, px."""

PIPE_RADIUS_PX = 5
"""Radius of the circle around the true pipe's axis, px."""


def draw_sonar_frame(frame: Frame, estimate: PipeEstimate | None) -> np.ndarray:
    """The ping's returns with the true pipe in green and the estimated across-track position in red.

    Parameters
    ----------
    frame : Frame
        A sonar frame: a :class:`~benchmark.modalities.sonar.model.Swath`
        and a :class:`~benchmark.modalities.sonar.model.SonarTruth` or None.
    estimate : PipeEstimate or None
        The tracker's estimate; None draws nothing for it.

    Returns
    -------
    numpy.ndarray
        A ``uint8`` BGR picture of :data:`PICTURE_SIZE`.

    References
    ----------
    seeds/003, section 2 (the swath) and eq. 5 (the across-track position).
    """
    swath: Swath = frame.observation
    valid = swath.valid
    across, depth = swath.across_m[valid], swath.depth_m[valid]
    truth = frame.truth if isinstance(frame.truth, SonarTruth) else None
    pipe = (truth.across_m, truth.depth_m) if truth is not None else (math.nan, math.nan)
    width, height = PICTURE_SIZE
    view = Viewport.around([*across, pipe[0]], [*depth, pipe[1]], width, height)
    picture = view.blank()
    for point in zip(across, depth):
        cv2.circle(picture, view.pixel(*point), 1, DATA_BGR, -1)
    if all(math.isfinite(value) for value in pipe):
        cv2.circle(picture, view.pixel(*pipe), PIPE_RADIUS_PX, TRUTH_BGR, 1)
    if estimate is not None:
        column, _ = view.pixel(estimate.across_m, view.top)
        cv2.line(picture, (column, 0), (column, height - 1), ESTIMATE_BGR, 1)
    return picture
