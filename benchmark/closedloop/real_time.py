"""Real-time mode: frames arrive at the route's frame rate; a tracker busy with one misses those arriving meanwhile.

In the ordinary closed-loop run (:mod:`benchmark.closedloop.scene`) the
vehicle waits for the tracker: every frame is seen, however long a step
takes.  A vehicle does not wait.  The issue that asks for closed-loop runs
says it: "a slow one sees fewer frames".  In real-time mode a frame
arrives every ``frame_interval_s``; the tracker starts on a frame as it
arrives and is busy for its step time ``t``; the frames that arrive while
it is busy are skipped (never handed to it, never scored), and it takes
the first frame that arrives once it is free.  So after a seen frame the
next seen frame is :func:`intervals_until_next` intervals later,
``max(1, ceil(t / T))``: a step of 2.5 intervals sees one frame in three,
a step shorter than an interval sees every frame.

The vehicle keeps moving under the last command while the tracker is
busy; the command of a frame's estimate takes effect when the step ends,
at frame granularity: from the start of the interval in which the step
ends, which is the last interval before the next seen frame
(:meth:`benchmark.closedloop.loop.Loop.steer`).  A step shorter than an
interval so drives the vehicle exactly as the ordinary mode does (the
benchmark's ordinary loop counts a step as instant), and a run in real
time with a fast tracker equals its ordinary run.

The step time ``t`` is either declared (:attr:`RealTime.declared_ms`:
the same on every machine, so a seed gives the same frames and results)
or measured: the running (lower) median of the thread CPU times of the
cell's steps so far (:class:`StepClock`), which the runner measures for every
frame anyway (:mod:`benchmark.runner`).  A running median rather than one
measured on the first frames: it needs no extra pass over a route whose
frames depend on the run itself, it uses only steps already done (as a
vehicle would know), and it follows a tracker whose speed changes along
the route (one that searches harder once it has lost the cable).  The
first step is left out: it pays for compilation, allocation and cold
caches, which are this machine's start-up and not the tracker's pace; so
the frame after the first is always seen.  A measured figure depends on
the machine, and results say so (:attr:`RealTime.source`).
"""

from __future__ import annotations

import bisect
import math
from typing import Annotated

import pydantic
from annotated_types import Gt

MEASURED_SOURCE = "measured median, this machine"
"""What a run with a measured step time says of it."""


@pydantic.dataclasses.dataclass(frozen=True, config=pydantic.ConfigDict(extra="forbid"))
class RealTime:
    """A cell's real-time mode: where its tracker's step time comes from.

    Attributes
    ----------
    declared_ms : float or None
        The declared step time, ms; None takes the measured running median
        (:class:`StepClock`).
    """

    declared_ms: Annotated[pydantic.FiniteFloat, Gt(0)] | None = None

    @property
    def source(self) -> str:
        """The step time's source as results show it: ``"declared 17 ms"`` or :data:`MEASURED_SOURCE`."""
        return MEASURED_SOURCE if self.declared_ms is None else f"declared {self.declared_ms:g} ms"

    @property
    def key(self) -> str:
        """What the mode adds to a cell's key: ``real-time:declared=17ms`` or ``real-time:measured-median``."""
        return "real-time:measured-median" if self.declared_ms is None else f"real-time:declared={self.declared_ms!r}ms"

    def clock(self) -> StepClock:
        """A fresh clock for one cell."""
        return StepClock(self)


class StepClock:
    """The step time one cell's tracker is taken to need, frame after frame.

    Parameters
    ----------
    real_time : RealTime
        The mode: a declared figure, or the running median of measured steps.
    """

    def __init__(self, real_time: RealTime) -> None:
        self.real_time = real_time
        self._steps = 0
        self._sorted_s: list[float] = []

    def busy_s(self, step_s: float) -> float:
        """How long the tracker was busy with the frame just stepped, whose measured step took ``step_s``.

        Declared: the declared figure.  Measured: the lower median (the
        smaller middle value of an even count) of the steps so far, this one
        included, the cell's first left out (module docstring); 0 after the
        first step.  The lower median, so that one slow step among the
        first two (a branch compiled when first taken) is not taken for the
        tracker's pace.
        """
        self._steps += 1
        if self.real_time.declared_ms is not None:
            return self.real_time.declared_ms / 1000.0
        if self._steps == 1:
            return 0.0
        bisect.insort(self._sorted_s, float(step_s))
        return self._sorted_s[(len(self._sorted_s) - 1) // 2]


def intervals_until_next(busy_s: float, interval_s: float) -> int:
    """Frame intervals from a seen frame to the next one the tracker sees: ``max(1, ceil(busy_s / interval_s))``.

    The frames that arrive while the tracker is busy are skipped; one that
    arrives as the step ends (a step of exactly ``k`` intervals, to a
    billionth of an interval, so that rounding of the ratio does not skip
    one more) is taken.
    """
    if not (math.isfinite(busy_s) and busy_s >= 0.0):
        raise ValueError(f"a step time is a finite number of seconds >= 0, got {busy_s!r}")
    return max(1, math.ceil(busy_s / interval_s - 1e-9))
