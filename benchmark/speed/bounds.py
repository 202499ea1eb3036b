"""Speed bounds: what a tracker (or a core component) is timed against, and the goal it is held to.

A plugin of the entry-point group ``trackbench.speed`` implements
:func:`benchmark.hookspecs.trackbench_register_speed_bounds` and adds one
:class:`SpeedBound` per row of ``trackbench speed``::

    [project.entry-points."trackbench.speed"]
    mine = "mine.speed_bound"

    @hookimpl
    def trackbench_register_speed_bounds(registry):
        registry.add_bound(SpeedBound("mine", "its filter alone", make_filter_alone, "camera/S1", RatioAtMost(1.5)))

The group is its own, as the commands' are, so that loading the trackers
for a run imports no bound.  First-party trackers declare their bounds
exactly so (``plugins/trackbench_*/speed_bound.py``).

A bound is a :class:`Workload`: an object with a tracker's ``reset`` and
``step``, which does the unavoidable part of the tracker's work (its
likelihood kernel on as many particles, OpenCV's edge and line detection at
its thresholds) on the same frames.  Its factory gets a :class:`BoundContext`:
the tracker's parameters, the sequence's info and, for a tracker that
learns, its trained model.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable
from dataclasses import dataclass
from typing import Any, ClassVar, Generic, Protocol, TypeVar

from pydantic import PositiveFloat
from pydantic.dataclasses import dataclass as checked_dataclass

import numpy as np

from benchmark.model import Frame, SequenceInfo
from benchmark.plugins import PluginGroup, load_plugins
from benchmark.registry import Origin, PluginRecords

SPEED_PLUGINS = PluginGroup(
    "trackbench.speed", ("trackbench_register_speed_bounds",), "its speed bounds are unavailable"
)
"""The entry-point group of the plugins that declare speed bounds, and their one hook."""


class Workload(Protocol):
    """What a row times frame by frame: a tracker, or the work it is held against."""

    def reset(self, info: SequenceInfo, rng: np.random.Generator, init: Any = None) -> None: ...

    def step(self, frame: Frame) -> Any: ...


class BoundUnavailable(Exception):  # noqa: N818 - a state, not a failure of the command
    """A bound that cannot be built here (an optional package not installed); its row says why."""


@dataclass(frozen=True)
class BoundContext:
    """What a bound's factory may use to do the tracker's unavoidable work faithfully.

    Attributes
    ----------
    params : object or None
        The subject tracker's parameters (None for a component subject).
    info : SequenceInfo
        The info of the sequence whose frames are timed.
    model : object or None
        The trained model of a tracker that learns, else None.
    """

    params: Any
    info: SequenceInfo
    model: Any = None


WorkloadFactory = Callable[[BoundContext], Workload]

Value = TypeVar("Value")


class PerFrame(Generic[Value]):
    """Inputs a bound needs but must not time, worked out once per frame and kept by frame index.

    Every workload plays the frames once untimed before the timed rounds
    (:func:`benchmark.speed.measure.time_subject`), in order, so ``compute``
    runs there and may keep state from frame to frame (a shadow tracker
    whose window the bound searches, say); the timed rounds only look up.
    """

    def __init__(self, compute: Callable[[Frame], Value]) -> None:
        self.compute = compute
        self.values: dict[int, Value] = {}

    def __call__(self, frame: Frame) -> Value:
        if frame.index not in self.values:
            self.values[frame.index] = self.compute(frame)
        return self.values[frame.index]


@checked_dataclass(frozen=True)
class RatioAtMost:
    """Ours per frame at most ``limit`` times the bound's per frame."""

    uses_ratio: ClassVar[bool] = True

    limit: PositiveFloat

    def met(self, ratio: float, ours_s: float) -> bool:
        return ratio <= self.limit

    def __str__(self) -> str:
        return f"ratio <= {self.limit:g}x"


@checked_dataclass(frozen=True)
class TimesFaster:
    """Ours at least ``factor`` times faster than the peer: the ratio at most ``1 / factor``."""

    uses_ratio: ClassVar[bool] = True

    factor: PositiveFloat

    def met(self, ratio: float, ours_s: float) -> bool:
        return ratio * self.factor <= 1.0

    def __str__(self) -> str:
        return f">= {self.factor:g}x faster"


@checked_dataclass(frozen=True)
class FpsAtLeast:
    """Ours at least ``fps`` frames a second (thread CPU time), whatever the bound."""

    uses_ratio: ClassVar[bool] = False

    fps: PositiveFloat

    def met(self, ratio: float, ours_s: float) -> bool:
        return ours_s * self.fps <= 1.0

    def __str__(self) -> str:
        return f">= {self.fps:g} fps"


@checked_dataclass(frozen=True)
class MsAtMost:
    """Ours at most ``ms`` milliseconds a frame (thread CPU time), whatever the bound."""

    uses_ratio: ClassVar[bool] = False

    ms: PositiveFloat

    def met(self, ratio: float, ours_s: float) -> bool:
        return ours_s * 1e3 <= self.ms

    def __str__(self) -> str:
        return f"<= {self.ms:g} ms"


Goal = RatioAtMost | TimesFaster | FpsAtLeast | MsAtMost
"""A row's goal; :meth:`met` takes the median ratio and ours' median seconds a frame."""


@dataclass(frozen=True)
class SpeedBound:
    """One row of ``trackbench speed``: a subject against one bound or peer.

    Attributes
    ----------
    subject : str
        A registered tracker's name, or, with ``ours``, the name of a core
        component (``EKF predict+update``).
    bound : str
        What the bound is, as the table shows it.
    make_bound : callable
        ``make_bound(context) -> Workload``; raises :class:`BoundUnavailable`
        when it cannot be built here.
    dataset : str
        The registered sequence (``suite/name``) whose frames are timed.
    goal : Goal or None
        What the row is held to; None for a bound shown for information.
    ours : callable or None
        ``ours(context) -> Workload`` for a component subject; None: the
        tracker ``subject`` itself, created with its default parameters.
    """

    subject: str
    bound: str
    make_bound: WorkloadFactory
    dataset: str
    goal: Goal | None = None
    ours: WorkloadFactory | None = None


class SpeedBounds(PluginRecords):
    """The speed bounds plugins declare, in the order they were added."""

    def __init__(self) -> None:
        super().__init__()
        self.bounds: list[SpeedBound] = []
        self.origins: list[Origin] = []

    def add_bound(self, bound: SpeedBound) -> SpeedBound:
        """Add a row.

        Raises
        ------
        PluginError
            If ``bound`` is not a :class:`SpeedBound`, the same subject and
            bound are declared twice, or one subject is given two datasets
            or two ``ours``.
        """
        if not isinstance(bound, SpeedBound):
            raise self._fail(f"{bound!r} is not a benchmark.speed.bounds.SpeedBound")
        for known in self.of(bound.subject):
            if known.bound == bound.bound:
                raise self._fail(f"speed bound {bound.bound!r} of {bound.subject!r} is already declared")
            if (known.dataset, known.ours) != (bound.dataset, bound.ours):
                raise self._fail(f"speed bounds of {bound.subject!r} must share one dataset and one 'ours'")
        self.bounds.append(bound)
        self.origins.append(self.origin)
        return bound

    @property
    def subjects(self) -> list[str]:
        """The subjects with a bound, in the order first declared."""
        return list(dict.fromkeys(bound.subject for bound in self.bounds))

    def of(self, subject: str) -> list[SpeedBound]:
        """The bounds of ``subject``, in the order declared."""
        return [bound for bound in self.bounds if bound.subject == subject]


def load_bounds(disable: Iterable[str] = (), *, strict: bool = False) -> SpeedBounds:
    """The speed bounds of every plugin of :data:`SPEED_PLUGINS` not disabled.

    Raises
    ------
    PluginError
        With ``strict``, for any plugin left out (:func:`benchmark.plugins.load_plugins`).
    """
    return load_plugins(SpeedBounds, SPEED_PLUGINS, disable, strict=strict)
