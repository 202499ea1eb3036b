"""The speed bounds of the condensation trackers: their own likelihood kernel on the same particles.

Every frame, the tracker weighs its ``N`` particles by eq. (4.11) (seeds/000,
section 4.5): that kernel is the work a condensation step cannot avoid.
The bound evaluates it, with the tracker's own :class:`BorderObservation`
(filter size, sample distance, interpolation, exponent), on ``N`` particles
drawn by the tracker's own prediction from the first frame's truth, frame
after frame over the same frames.  Goals: issue 34's frame rates.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from benchmark import hookimpl
from benchmark.model import Frame, SequenceInfo
from benchmark.speed.bounds import BoundContext, FpsAtLeast, SpeedBound, SpeedBounds
from trackbench_condensation.observation import as_grey_image
from trackbench_condensation.tracker import CondensationTracker

DATASET = "camera/S1"
"""The sequence timed: the thesis' first test sequence (seeds/000, Fig. 5.2)."""
GOALS = {"condensation": FpsAtLeast(3000), "condensation-thesis": FpsAtLeast(4000)}
"""Issue 34's goal of each tracker timed."""


class LikelihoodKernel:
    """Eq. (4.11) on ``N`` predicted particles of the tracker's own, each frame."""

    def __init__(self, context: BoundContext) -> None:
        self.tracker = CondensationTracker(context.params)
        self.states = np.empty((0, 4))

    def reset(self, info: SequenceInfo, rng: np.random.Generator, init: Any = None) -> None:
        self.tracker.reset(info, rng, init=init)
        predicted = self.tracker.filter.predict(self.tracker.particle_set, rng)
        self.states = np.ascontiguousarray(predicted.states)

    def step(self, frame: Frame) -> np.ndarray:
        return self.tracker.observation.likelihood(self.states, as_grey_image(frame.observation))


@hookimpl
def trackbench_register_speed_bounds(registry: SpeedBounds) -> None:
    """Each condensation tracker against its likelihood kernel on the same particles."""
    for name, goal in GOALS.items():
        registry.add_bound(SpeedBound(name, "its likelihood kernel, same particles", LikelihoodKernel, DATASET, goal))
