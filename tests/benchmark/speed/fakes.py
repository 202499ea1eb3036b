"""Fake subjects of ``trackbench speed``: a fast and a slow tracker, the bound they share, and their plugin.

The slow tracker does the fast one's work :data:`SLOW_FACTOR` times a
frame, so against the same bound its ratio is larger whatever the
machine's speed: the tests compare ratios, never times.
"""

from __future__ import annotations

import types
from typing import Any

import numpy as np
import pluggy

from benchmark import hookimpl
from benchmark.model import Frame, SequenceInfo
from benchmark.plugins import PluginManager, fill_registry
from benchmark.speed.bounds import (
    SPEED_PLUGINS,
    BoundContext,
    BoundUnavailable,
    FpsAtLeast,
    RatioAtMost,
    SpeedBound,
    SpeedBounds,
)

from ..conftest import Perfect

SLOW_FACTOR = 40
DATASET = "fake/S1"


def work(frame: Frame, times: int) -> float:
    """Some arithmetic on the frame, ``times`` over."""
    image = np.asarray(frame.observation, dtype=float)
    total = 0.0
    for _ in range(times):
        total += float(np.sqrt(image * image + 1.0).sum())
    return total


class Fast(Perfect):
    """The bound's work, once a frame."""

    name = "fast"

    def step(self, frame: Frame) -> Any:
        work(frame, 1)
        return frame.truth.cable


class Slow(Fast):
    """The bound's work, :data:`SLOW_FACTOR` times a frame."""

    name = "slow"

    def step(self, frame: Frame) -> Any:
        work(frame, SLOW_FACTOR)
        return frame.truth.cable


class Learner(Fast):
    """Learns the mean grey level of its training frames; counts its fits (in this process)."""

    name = "learner"
    fits = 0

    def fit(self, training: Any, rng: np.random.Generator) -> float:
        type(self).fits += 1
        return float(np.mean([np.mean(frame.observation) for sequence in training for frame in sequence.frames()]))

    def use_model(self, model: float) -> None:
        self.model = model


class Bound:
    """The unavoidable work: once a frame."""

    def __init__(self, context: BoundContext) -> None:
        self.context = context

    def reset(self, info: SequenceInfo, rng: np.random.Generator, init: Any = None) -> None:
        self.init = init

    def step(self, frame: Frame) -> Any:
        return work(frame, 1)


def unavailable(context: BoundContext) -> Bound:
    raise BoundUnavailable("acme-peer is not installed")


def component(context: BoundContext) -> Bound:
    return Bound(context)


@hookimpl
def trackbench_register_speed_bounds(registry: SpeedBounds) -> None:
    registry.add_bound(SpeedBound("fast", "the same work", Bound, DATASET, RatioAtMost(1000)))
    registry.add_bound(SpeedBound("fast", "a peer not installed", unavailable, DATASET, RatioAtMost(1)))
    registry.add_bound(SpeedBound("slow", "the same work", Bound, DATASET, RatioAtMost(1.0)))
    registry.add_bound(SpeedBound("core step", "the same work", Bound, DATASET, FpsAtLeast(1e-3), ours=component))


PLUGIN = types.SimpleNamespace(trackbench_register_speed_bounds=trackbench_register_speed_bounds)
"""A plugin object implementing the hook, as an entry point's module would."""


@hookimpl
def register_learner(registry: SpeedBounds) -> None:
    registry.add_bound(SpeedBound("learner", "the same work", Bound, "learning/S1"))


LEARNING_PLUGIN = types.SimpleNamespace(trackbench_register_speed_bounds=register_learner)
"""A second plugin: the bound of the learning tracker, on a suite that has a training split."""


def bounds_of(*plugins: object) -> SpeedBounds:
    """The bounds the plugins declare, filled through the hook as :func:`benchmark.speed.bounds.load_bounds` does."""
    manager: pluggy.PluginManager = PluginManager(SPEED_PLUGINS.lost)
    for index, plugin in enumerate(plugins or (PLUGIN,)):
        manager.register(plugin, name=f"fake-speed-{index}")
    return fill_registry(manager, {}, SpeedBounds, SPEED_PLUGINS.hooks)
