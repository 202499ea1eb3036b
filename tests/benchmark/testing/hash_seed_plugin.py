"""``acme_hash_seed``: trackers for the tests of the hash-seed check (``test_hash_seed.py``).

The tests copy this file into a temporary site folder as the module
``acme_hash_seed``, which the check's fresh interpreter imports as it would
any plugin's module.  Every tracker here follows the cable from ``init``,
moved by the image's brightness, its parameters, its model and a generator
spawned from the one ``reset`` hands it; each subclass adds one way of
depending on its process.
"""

from __future__ import annotations

import dataclasses
import json
import os
import sys
import zlib
from typing import Any, ClassVar

import numpy as np

from benchmark import CableState, Frame, SequenceInfo, Tracker

SIDES = frozenset(
    {
        "left", "right", "centre", "port", "starboard", "bow", "stern", "keel", "deck", "mast",
        "boom", "rudder", "hull", "beam", "bridge", "anchor", "cable", "buoy", "tether", "winch",
    }
)  # fmt: skip
"""Twenty strings: in another hash seed's order with near certainty."""

FROM_FRAME = 3
"""The frame from which :class:`SetOrdered` lets the order of :data:`SIDES` move its estimate."""

CENSUS_VARIABLE = "ACME_HASH_SEED_CENSUS"
"""Where :class:`Census`, outside the process that set it up, writes the names of the modules loaded there."""


@dataclasses.dataclass(frozen=True)
class DriftingParams:
    offset_px: float = 0.0


class Drifting(Tracker):
    """Correct: its randomness comes only from the generator handed to reset, and no set decides anything."""

    name = "drifting"
    version = "1.0"
    modality = "camera"
    Params = DriftingParams
    bias_px = 0.0

    def use_model(self, model: Any) -> None:
        self.bias_px = model["bias_px"]

    def reset(self, info: SequenceInfo, rng: np.random.Generator, init: Any = None) -> None:
        (self.rng,) = rng.spawn(1)
        self.state = init.cable

    def step(self, frame: Frame) -> Any:
        shift = self.params.offset_px + self.bias_px + float(np.mean(frame.observation)) / 100.0
        self.state = dataclasses.replace(self.state, d=self.state.d + shift + self.rng.normal(0.0, 0.5))
        return self.state


class SetOrdered(Drifting):
    """From frame :data:`FROM_FRAME` on, the order in which a set of strings iterates moves the estimate."""

    name = "set-ordered"

    def step(self, frame: Frame) -> Any:
        estimate: CableState = super().step(frame)
        if frame.index < FROM_FRAME:
            return estimate
        order = ",".join(SIDES)
        return dataclasses.replace(estimate, d=estimate.d + zlib.crc32(order.encode()) % 1000 / 100.0)


class HomeOnly(Drifting):
    """Raises in any process but the one whose id a test put in ``home_pid``."""

    name = "home-only"
    home_pid: ClassVar[int] = 0

    def step(self, frame: Frame) -> Any:
        if os.getpid() != self.home_pid:
            raise RuntimeError(f"runs only in process {self.home_pid}")
        return super().step(frame)


class SpinsAway(HomeOnly):
    """Spins forever in any process but the one whose id a test put in ``home_pid``."""

    name = "spins-away"

    def step(self, frame: Frame) -> Any:
        while os.getpid() != self.home_pid:
            pass
        return super().step(frame)


class Census(HomeOnly):
    """Outside ``home_pid``, writes the modules of its process to the file named by :data:`CENSUS_VARIABLE`."""

    name = "census"

    def step(self, frame: Frame) -> Any:
        if os.getpid() != self.home_pid:
            with open(os.environ[CENSUS_VARIABLE], "w") as census:
                json.dump(sorted(sys.modules), census)
        return Drifting.step(self, frame)
