"""Fakes shared by the tests of the conformance kit."""

from __future__ import annotations

from typing import Any

import numpy as np

from benchmark.modalities.camera.model import CableState
from benchmark.model import Frame, SequenceInfo
from benchmark.tracker import Tracker


class Steady(Tracker):
    """Starts from ``init`` (or a fixed state), follows the image brightness; uses only its rng; no belief."""

    name = "steady"
    version = "1.0"
    modality = "camera"

    def reset(self, info: SequenceInfo, rng: np.random.Generator, init: Any = None) -> None:
        self.rng = rng
        self.state = init.cable if init is not None else CableState(0.0, 0.0, 12.0, 0.0)

    def step(self, frame: Frame) -> Any:
        shift = float(np.mean(frame.observation)) / 100.0 + self.rng.normal(0.0, 0.1)
        self.state = CableState(self.state.d + shift, self.state.alpha, self.state.w, self.state.beta)
        return self.state
