"""The camera modality's replay view: the image as a JPEG, the cable state ``(d, alpha, w, beta)``, its two borders.

The image is downscaled to at most :data:`MAX_WIDTH` px wide and encoded
at :data:`~benchmark.replay.jpeg.JPEG_QUALITY`; a state's overlay is the chord of each of its two
border lines through the image (:func:`~benchmark.modalities.camera.geometry.cable_borders`,
:func:`~benchmark.modalities.camera.draw.chord_ends`), the lines the
detection rule compares (seeds/004, section VI-C; ``conventions.md``
sections 1 and 3).
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import TYPE_CHECKING, Any

import cv2
import numpy as np

from benchmark.modalities.camera.draw import chord_ends
from benchmark.modalities.camera.geometry import Line, cable_borders, model_to_pixel
from benchmark.modalities.camera.model import CableState, CameraTruth
from benchmark.model import Frame
from benchmark.replay.jpeg import encode_jpeg, shrunk_to_width
from benchmark.replay.views import Mark, Picture, Segment

if TYPE_CHECKING:
    from benchmark.replay.record import Belief

MAX_WIDTH = 480
"""Widest picture of a frame, px; wider images are downscaled."""

PARTICLE_LINES = 24
"""Particles of a belief whose borders are drawn on the frame (seeds/000, section 4.7 draws them beside it)."""


class CameraView:
    """The replay view of camera frames (:class:`~benchmark.replay.views.ReplayView`)."""

    dimensions = ("d_px", "alpha_rad", "w_px", "beta_rad")
    """The cable state of seeds/000, section 4.2, Table 4.1, in :meth:`CableState.as_array` order."""

    def picture(self, frame: Frame) -> Picture:
        """The frame's image, at most :data:`MAX_WIDTH` px wide, as a JPEG."""
        image = np.asarray(frame.observation)
        if image.ndim == 3 and image.shape[2] == 4:
            image = cv2.cvtColor(image, cv2.COLOR_BGRA2BGR)
        source_size = (int(image.shape[1]), int(image.shape[0]))
        image = shrunk_to_width(image, MAX_WIDTH)
        jpeg = encode_jpeg(image, f"frame {frame.index}")
        return Picture(jpeg, int(image.shape[1]), int(image.shape[0]), source_size=source_size)

    def state(self, value: Any) -> tuple[float, ...] | None:
        """A :class:`CameraTruth`'s cable or a :class:`CableState` as ``(d, alpha, w, beta)``; None if unknown."""
        cable = value.cable if isinstance(value, CameraTruth) else value
        if not isinstance(cable, CableState) or not cable.is_known:
            return None
        return tuple(float(v) for v in cable.as_array())

    def overlay(self, value: Any, frame: Frame, picture: Picture) -> list[Mark]:
        """The chords of the cable's two borders, in the picture's canvas coordinates (pixel edges at integers)."""
        state = self.state(value)
        if state is None:
            return []
        return [Mark.segment(chord) for chord in _border_chords(state, picture)]

    def belief_marks(self, belief: Belief, picture: Picture) -> list[Mark]:
        """The borders of :data:`PARTICLE_LINES` particles of a particle belief, each as opaque as it is heavy.

        The particles are a systematic subsample of the belief
        (:func:`~benchmark.replay.record.systematic_subsample`), so each
        stands for an equal share of its weight: a belief split between the
        cable and an edge beside it shows as two bundles of lines, in
        proportion.
        """
        if belief.particles is None or belief.weights is None or belief.particles.shape[1] < 4:
            return []
        from benchmark.replay.record import systematic_subsample

        particles, weights = systematic_subsample(belief.particles[:, :4], belief.weights, PARTICLE_LINES)
        heaviest = float(weights.max())
        strokes: list[float] = []
        for state, weight in zip(particles, weights):
            if not np.all(np.isfinite(state)):
                continue
            for u1, v1, u2, v2 in _border_chords(tuple(float(v) for v in state), picture):
                strokes += [round(weight / heaviest, 2), round(u1, 1), round(v1, 1), round(u2, 1), round(v2, 1)]
        return [Mark("strokes", tuple(strokes), "particle")] if strokes else []

    def region_marks(self, region: Any, picture: Picture) -> list[Mark]:
        """The chords of the lines that bound the searched bands (model-coordinate :class:`Line` s), dashed."""
        if not isinstance(region, tuple | list) or not all(isinstance(line, Line) for line in region):
            return []
        size = picture.source_size or (picture.width, picture.height)
        return [Mark.segment(chord, "window") for chord in _chords(region, size, picture)]


def _border_chords(state: tuple[float, ...], picture: Picture) -> list[Segment]:
    """The chords of the two borders of ``state`` in the image ``picture`` shows, scaled to it; none that overflow."""
    size = picture.source_size or (picture.width, picture.height)
    try:
        borders = cable_borders(CableState(*state[:4]))
    except ValueError:  # a finite state whose border points overflow
        return []
    return _chords(borders, size, picture)


def _chords(lines: Iterable[Line], size: tuple[int, int], picture: Picture) -> list[Segment]:
    """The chords through a ``size`` image of model-coordinate ``lines``, scaled to ``picture``."""
    scale_u, scale_v = picture.width / size[0], picture.height / size[1]
    chords: list[Segment] = []
    for line in lines:
        chord = chord_ends(line, size)
        if chord is None:
            continue
        (u1, v1), (u2, v2) = (model_to_pixel(x, y, size) for x, y in chord)
        chords.append(((u1 + 0.5) * scale_u, (v1 + 0.5) * scale_v, (u2 + 0.5) * scale_u, (v2 + 0.5) * scale_v))
    return chords
