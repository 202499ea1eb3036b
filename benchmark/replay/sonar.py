"""The sonar modality's replay view: the ping's swath profile, the pipe's truth and estimate, the particles.

A ping (seeds/003, section 2) is drawn in the swath plane as
:func:`benchmark.modalities.sonar.draw.draw_sonar_frame` draws it,
across-track to the right (starboard) and depth downwards, each axis
stretched to fit the returns and the pipe: the water light, the seabed
below the profile the returns trace filled in sand, each return a dark
dot, the ends of both axes written in the corners.  The state is the
pipe's across-track position, the quantity of eq. (5) and of a sonar
tracker's belief; the truth is drawn as a circle around the pipe's axis,
an estimate as a vertical line at its across-track position (below the
band of the particles' ticks, which it would hide), and the
particles of a particle belief (seeds/003, eqs. 3-4) as ticks hanging
from the top edge at their across-track positions, as long and as opaque
as their weight relative to the heaviest.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

import cv2
import numpy as np

from benchmark.drawing import Colour, Viewport
from benchmark.modalities.sonar.draw import PIPE_RADIUS_PX
from benchmark.modalities.sonar.model import PipeEstimate, SonarTruth, Swath
from benchmark.model import Frame
from benchmark.replay.jpeg import encode_jpeg
from benchmark.replay.views import Mark, Picture, PlaneMap

if TYPE_CHECKING:
    from benchmark.replay.record import Belief

PICTURE_SIZE = (480, 240)
"""Width and height of a sonar picture, px."""

TICK_LENGTH_PX = 48.0
"""Length of the tick of the heaviest particle, px."""

WATER_BGR: Colour = (248, 240, 228)
SEABED_BGR: Colour = (150, 190, 222)
RETURN_BGR: Colour = (40, 40, 40)
LABEL_BGR: Colour = (70, 70, 70)


class SonarView:
    """The replay view of sonar pings (:class:`~benchmark.replay.views.ReplayView`)."""

    dimensions = ("across_m",)
    """The pipe's across-track position from the nadir, starboard positive (seeds/003, eq. 5)."""

    def picture(self, frame: Frame) -> Picture:
        """The ping's swath profile as a JPEG of :data:`PICTURE_SIZE`, with the map of its plane."""
        swath: Swath = frame.observation
        valid = swath.valid
        across, depth = swath.across_m[valid], swath.depth_m[valid]
        pipe = _pipe(frame.truth)
        width, height = PICTURE_SIZE
        view = Viewport.around([*across, pipe[0]], [*depth, pipe[1]], width, height)
        image = view.blank(WATER_BGR)
        _fill_seabed(image, view, across, depth)
        for point in zip(across, depth):
            cv2.circle(image, view.pixel(*point), 1, RETURN_BGR, -1)
        _label_axes(image, view)
        return Picture(encode_jpeg(image, f"ping {frame.index}"), width, height, plane=PlaneMap.of(view))

    def state(self, value: Any) -> tuple[float, ...] | None:
        """A :class:`SonarTruth`'s or a :class:`PipeEstimate`'s across-track position; None if not finite."""
        if not isinstance(value, (SonarTruth, PipeEstimate)) or not math.isfinite(value.across_m):
            return None
        return (float(value.across_m),)

    def overlay(self, value: Any, frame: Frame, picture: Picture) -> list[Mark]:
        """A circle around the true pipe's axis; a vertical line through the profile at an estimate's position."""
        plane = picture.plane
        if plane is None or self.state(value) is None:
            return []
        if isinstance(value, SonarTruth):
            if not math.isfinite(value.depth_m):
                return []
            return [Mark.circle(*plane.point(value.across_m, value.depth_m), PIPE_RADIUS_PX)]
        u, _ = plane.point(value.across_m, 0.0)
        _, top, _, bottom = plane.box
        return [Mark.segment((u, top + TICK_LENGTH_PX, u, bottom))]

    def belief_marks(self, belief: Belief, picture: Picture) -> list[Mark]:
        """The particles' across-track positions as ticks from the top edge, weighted (:data:`TICK_LENGTH_PX`)."""
        plane = picture.plane
        if plane is None or belief.particles is None or belief.weights is None or belief.particles.shape[1] < 1:
            return []
        positions, weights = belief.particles[:, 0], belief.weights
        kept = np.isfinite(positions) & np.isfinite(weights)
        heaviest = float(weights[kept].max()) if kept.any() else 0.0
        if heaviest <= 0.0:
            return []
        points: list[float] = [plane.box[1], TICK_LENGTH_PX]
        for x, w in zip(positions[kept], weights[kept]):
            points += [round(plane.point(float(x), 0.0)[0], 1), round(float(w) / heaviest, 2)]
        return [Mark("ticks", tuple(points), "particle")]


def _pipe(truth: Any) -> tuple[float, float]:
    return (truth.across_m, truth.depth_m) if isinstance(truth, SonarTruth) else (math.nan, math.nan)


def _fill_seabed(image: np.ndarray, view: Viewport, across: np.ndarray, depth: np.ndarray) -> None:
    """Paint every pixel below the profile the returns trace, between the outermost returns, in :data:`SEABED_BGR`."""
    if across.size < 2:
        return
    order = np.argsort(across)
    xs, zs = across[order], depth[order]
    height, width = image.shape[:2]
    columns = view.left + np.arange(width) * (view.right - view.left) / (width - 1)
    inside = (columns >= xs[0]) & (columns <= xs[-1])
    floor = (np.interp(columns, xs, zs) - view.top) / (view.bottom - view.top) * (height - 1)
    below = np.arange(height)[:, None] >= np.where(inside, floor, np.inf)[None, :]
    image[below] = SEABED_BGR


def _label_axes(image: np.ndarray, view: Viewport) -> None:
    """The depths of the top and bottom rows at the left, the across-track ends at the bottom, m."""
    height, width = image.shape[:2]
    font, scale = cv2.FONT_HERSHEY_SIMPLEX, 0.35
    texts = (
        (f"depth {view.top:.1f} m", (3, 11)),
        (f"depth {view.bottom:.1f} m", (3, height - 4)),
        (f"across {view.left:.1f} to {view.right:+.1f} m", (width - 150, height - 4)),
    )
    for text, at in texts:
        cv2.putText(image, text, at, font, scale, LABEL_BGR, 1, cv2.LINE_AA)

    def region_marks(self, region: Any, picture: Picture) -> list[Mark]:
        """None: no first-party sonar tracker declares a search region yet."""
        return []
