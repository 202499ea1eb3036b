"""Drawn cable images and in-memory labelled sequences for the tests of the texture tracker.

``drawn.cable_image(state, ground)`` is a ``uint8`` image of a cable of known
:class:`benchmark.modalities.camera.model.CableState`: the region between its
two border lines, ``contrast`` grey levels off a ``"blank"`` ground (one
grey level) or a ``"sand"`` ground (blurred random relief plus pixel
noise).  ``drawn.sequence(name, states, ground)`` wraps such images, with
their truths, as a :class:`benchmark.model.Sequence`; ``drawn.random_states``
draws plausible cable states.  ``trained`` is a texture tracker fitted once
per test session on a few drawn sequences.
"""

from __future__ import annotations

import math
import types
from collections.abc import Iterator

import cv2
import numpy as np
import pytest
from trackbench_texture.tracker import TextureTracker

from benchmark.modalities.camera.geometry import Line, cable_borders, model_to_pixel
from benchmark.modalities.camera.model import CableState, CameraTruth
from benchmark.model import Frame, Sequence, SequenceInfo

SIZE = (160, 120)

FAST = {"frames_per_sequence": 4, "pixels_per_frame": 1000, "boosting_rounds": 25, "working_height_px": 120}
"""Small training settings, so that fitting in a test takes a fraction of a second; the working height is
the drawn frames' own, so that they are measured as drawn."""


def ground(kind: str, size: tuple[int, int] = SIZE, seed: int = 0) -> np.ndarray:
    """A ``float32`` ``(H, W)`` ground: ``"blank"`` (grey 140) or ``"sand"`` (blurred relief plus grain)."""
    width, height = size
    if kind == "blank":
        return np.full((height, width), 140.0, np.float32)
    rng = np.random.default_rng(seed)
    relief = cv2.GaussianBlur(rng.standard_normal((height, width)).astype(np.float32), (0, 0), 2.0)
    relief *= 10.0 / float(relief.std())
    return 140.0 + relief + rng.normal(0.0, 3.0, (height, width)).astype(np.float32)


def _crossing(line: Line, y: float, size: tuple[int, int]) -> tuple[float, float]:
    """The pixel point where a non-horizontal model line crosses model height ``y``."""
    s = (y - line.y0) / line.dy
    return model_to_pixel(line.x0 + s * line.dx, y, size)


def cable_image(
    state: CableState, kind: str = "sand", contrast: float = -60.0, seed: int = 0, size: tuple[int, int] = SIZE
) -> np.ndarray:
    """A ``uint8`` image of a cable (darker than the ground for negative ``contrast``)."""
    width, height = size
    left, right = cable_borders(state)
    reach = 2.0 * height
    corners = [_crossing(left, reach, size), _crossing(right, reach, size)]
    corners += [_crossing(right, -reach, size), _crossing(left, -reach, size)]
    cover = np.zeros((height, width), np.uint8)
    scale = 1 << 4
    cv2.fillPoly(cover, [np.round(np.array(corners) * scale).astype(np.int32)], 255, cv2.LINE_AA, 4)
    image = ground(kind, size, seed) + np.float32(contrast / 255.0) * cover.astype(np.float32)
    return np.clip(np.rint(image), 0, 255).astype(np.uint8)


def random_states(rng: np.random.Generator, count: int) -> list[CableState]:
    """Nearly vertical cables 18-26 px wide, crossing the image near its centre."""
    return [
        CableState(
            rng.uniform(-30.0, 30.0), math.radians(rng.uniform(-15.0, 15.0)), rng.uniform(18.0, 26.0),
            math.radians(rng.uniform(0.0, 1.0)),
        )
        for _ in range(count)
    ]


class DrawnSequence(Sequence):
    """Labelled frames held in memory."""

    def __init__(self, name: str, frames: list[Frame]) -> None:
        self._info = SequenceInfo(name, "camera", n_frames=len(frames), frame_size=SIZE)
        self._frames = frames

    @property
    def info(self) -> SequenceInfo:
        return self._info

    def frames(self) -> Iterator[Frame]:
        return iter(self._frames)


def sequence(name: str, states: list[CableState], kind: str = "sand", seed: int = 0) -> DrawnSequence:
    """A sequence of drawn cables, one frame per state, each labelled with its state."""
    frames = [
        Frame(k, cable_image(state, kind, seed=seed + k), CameraTruth(state)) for k, state in enumerate(states)
    ]
    return DrawnSequence(name, frames)


def training_set(seed: int = 1) -> list[DrawnSequence]:
    """Three drawn sequences, sand and blank ground, of six frames each."""
    rng = np.random.default_rng(seed)
    return [
        sequence(f"drawn/{kind}-{k}", random_states(rng, 6), kind, seed=100 * k)
        for k, kind in enumerate(["sand", "blank", "sand"])
    ]


@pytest.fixture(scope="session")
def drawn() -> types.SimpleNamespace:
    """Helpers: ``SIZE``, ``FAST``, ``ground``, ``cable_image``, ``random_states``, ``sequence``, ``training_set``."""
    return types.SimpleNamespace(
        SIZE=SIZE, FAST=FAST, ground=ground, cable_image=cable_image, random_states=random_states,
        sequence=sequence, training_set=training_set, DrawnSequence=DrawnSequence,
    )


@pytest.fixture(scope="session")
def trained() -> TextureTracker:
    """A texture tracker fitted on :func:`training_set` with seed 7 (do not reset it with another model)."""
    tracker = TextureTracker(TextureTracker.make_params(FAST))
    tracker.fit(training_set(), np.random.default_rng(7))
    return tracker
