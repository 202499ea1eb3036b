"""What a cell produced: per-frame scores, the cell's result, and the summary of both.

Every frame a tracker processes gets a :class:`FrameScore`: its detection
outcome (seeds/004, section VI-C, Table V), the estimate's errors (one per
error column of the modality's scorer) and the time the tracker's ``step``
took, as CPU time of the thread that ran it and as wall time
(:mod:`benchmark.runner`); a frame of a closed-loop sequence
(:mod:`benchmark.closedloop`) also gets the :class:`LoopValues` of the
vehicle that saw it, stored and read back beside the errors under names
that start with :data:`LOOP_PREFIX`.  A :class:`CellResult` holds a cell's identity, how it ended, its
frame scores and a :class:`Picture` of the first frame of each run of
failures (where its modality draws frames); it is what worker processes
hand back and what the store writes.  :func:`summarise` turns frame
scores, of one cell or pooled over many, into the metrics of a
leaderboard row (:mod:`benchmark.metrics`).

Column names carry their units (``conventions.md`` section 4): angles are
reported in degrees, distances in px (camera) or m (sonar, stereo).
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Literal, NamedTuple

import numpy as np
from pydantic import FiniteFloat, PositiveFloat
from pydantic.dataclasses import dataclass as pydantic_dataclass

from benchmark.metrics import CORE, Metric, Metrics, columns_with_values
from benchmark.model import Outcome

if TYPE_CHECKING:
    import pandas as pd

Status = Literal["ok", "error", "timeout"]

LOOP_PREFIX = "loop_"
"""Start of the name of every frame-table column that :class:`LoopValues` fills."""


@pydantic_dataclass(frozen=True)
class LoopValues:
    """The vehicle of a closed-loop run at one frame, where it stood when the camera took it.

    Frame tables (:func:`frame_table`) and the store hold each field as a
    column named :data:`LOOP_PREFIX` and the field (:meth:`column`):
    ``loop_offset_m``, ``loop_heading_error_deg``, ``loop_along_m``,
    ``loop_time_s`` and ``loop_in_view`` (1.0 or 0.0).  Frames of open-loop
    sequences have none of these columns.

    Attributes
    ----------
    offset_m : float
        Lateral offset from the cable, m, positive right of it
        (:class:`benchmark.closedloop.route.Place`).
    heading_error_deg : float
        The vehicle's heading minus the cable's, deg, positive turned to the right.
    along_m : float
        Distance along the route of the cable's point nearest the vehicle, m.
    time_s : float
        The frame's time from the start of the run, s.
    in_view : bool
        Whether the cable's centreline crosses the image (a cable buried
        under sand counts as in view: the camera looks at it).
    route_m : float or None
        The route's whole length, m (``loop_route_m``), so that the share
        of the route followed can be told from the frames alone; None
        where the sequence does not say it, and then no column.
    """

    offset_m: FiniteFloat
    heading_error_deg: FiniteFloat
    along_m: FiniteFloat
    time_s: FiniteFloat
    in_view: bool
    route_m: PositiveFloat | None = None

    @staticmethod
    def column(field_name: str) -> str:
        """The frame-table column of a field: ``offset_m`` -> ``loop_offset_m``."""
        return LOOP_PREFIX + field_name

    def columns(self) -> dict[str, float]:
        """The values by frame-table column, as floats (``in_view`` as 1.0 or 0.0); a value that is None has none."""
        values = {name: getattr(self, name) for name in self.__dataclass_fields__}
        return {self.column(name): float(value) for name, value in values.items() if value is not None}


@dataclass(frozen=True)
class FrameScore:
    """The score of one frame.

    Attributes
    ----------
    index : int
        Frame index in its sequence.
    outcome : Outcome or None
        None when the frame has no ground truth and is not scored.
    errors : Mapping[str, float]
        Estimate minus truth, one entry per error column of the modality;
        ``nan`` where there is no estimate or no truth.
    step_s : float
        CPU time of the thread that ran the tracker's ``step`` for this
        frame (:func:`time.thread_time`): the tracker's own work, since it
        runs its native libraries on that one thread.
    wall_s : float
        Wall time of the same ``step``, which also counts the waits for a
        core that other processes held.
    loop : LoopValues or None
        On a closed-loop sequence, the vehicle at this frame
        (:meth:`benchmark.model.Sequence.steer`); None on every other.
    """

    index: int
    outcome: Outcome | None
    errors: Mapping[str, float] = field(default_factory=dict)
    step_s: float = 0.0
    wall_s: float = 0.0
    loop: LoopValues | None = None


@dataclass(frozen=True)
class Picture:
    """A small picture of a failed frame with the truth and the tracker's estimate drawn on it.

    Made by the modality's drawer (:attr:`benchmark.modality.Modality.draw`)
    for the first frame of each run of failures of a cell
    (:func:`benchmark.runner.run_cell`).

    Attributes
    ----------
    frame : int
        Frame index in its sequence.
    outcome : str
        The frame's outcome, ``"false"`` or ``"missed"``.
    png : bytes
        The picture, a BGR image encoded as PNG.
    """

    frame: int
    outcome: str
    png: bytes


def frame_table(scores: Iterable[FrameScore]) -> pd.DataFrame:
    """Frame scores as a table: ``frame``, ``outcome``, error columns, ``step_ms`` (thread CPU) and ``wall_ms``.

    Frames of a closed-loop sequence add the ``loop_*`` columns of their
    :class:`LoopValues` after the error columns; a table without such a
    frame has none of them.
    """
    rows = [
        {
            "frame": s.index,
            "outcome": None if s.outcome is None else str(s.outcome),
            **s.errors,
            **({} if s.loop is None else s.loop.columns()),
            "step_ms": 1000.0 * s.step_s,
            "wall_ms": 1000.0 * s.wall_s,
        }
        for s in scores
    ]
    import pandas as pd  # here, so that listing the trackers does not import pandas

    return pd.DataFrame(rows)


def summarise(frames: pd.DataFrame, metrics: Iterable[Metric]) -> dict[str, float]:
    """``frames``, the number of scored frames, and the value of each metric over a frame table.

    Parameters
    ----------
    frames : pandas.DataFrame
        Frame scores as made by :func:`frame_table`, of one cell or of
        several pooled (with a ``cell_id`` column telling them apart).
    metrics : iterable of Metric
        The metrics of the board (:meth:`benchmark.metrics.Metrics.for_board`).

    Returns
    -------
    dict
        ``frames``, then each metric's name to its value
        (:meth:`benchmark.metrics.Metric.of`): for the core metrics
        ``correct_pct``, ``false_pct``, ``missed_pct`` (percentages of scored
        frames, summing to 100), ``rmse_*`` over frames with both an
        estimate and a truth, ``cpu_fps`` (frames processed per second of
        the CPU time of ``step``) and ``wall_fps`` (the same per second of
        its wall time).
    """
    scored = frames["outcome"].notna().sum() if "outcome" in frames else 0
    return {"frames": float(scored), **{metric.name: metric.of(frames) for metric in metrics}}


class CellKey(NamedTuple):
    """What makes two cells the same computation (``--resume`` matches on it).

    ``dataset_key`` is the dataset's :attr:`benchmark.identity.DatasetIdentity.key`,
    not its name: an edited file is another dataset, and two paths naming
    the same file are one.
    """

    tracker_key: str
    dataset_key: str
    seed: int
    init: str


@dataclass(frozen=True)
class CellResult:
    """What running a cell produced, ready to be stored.

    Attributes
    ----------
    tracker, tracker_version, tracker_key : str
        The tracker's name, version and cache key.
    params : dict
        The tracker's parameters by name.
    dataset, dataset_key, modality : str
        The sequence's name as shown, its identity's key
        (:class:`benchmark.identity.DatasetIdentity`) and its modality.
    seed : int
        The cell's seed.
    init : str
        ``"truth"`` or ``"none"``.
    status : {"ok", "error", "timeout"}
        How the cell ended.
    message : str
        Empty for ``"ok"``; otherwise ``"ExceptionType: message (frame k)"``
        or the time limit that was exceeded.
    scores : tuple of FrameScore
        Every frame scored, including those before a failure.
    elapsed_s : float
        Wall time of the whole cell, reading and scoring included.
    detail : str
        The traceback of an error, for the tracker's author.
    error_columns : tuple of str
        The modality's error columns, in its scorer's order.
    training : str
        The training set of a tracker that learns (:mod:`benchmark.training`), else empty.
    read_s : float
        Wall time spent getting the frames (rendering, or reading them from
        the frame cache or files); known for cells run now, not stored.
    pictures : tuple of Picture
        Pictures of the first frame of each run of failed frames, in frame
        order, at most :data:`benchmark.runner.MAX_PICTURES`; empty when the
        modality draws nothing.
    deterministic : bool
        The tracker declares that it draws no random numbers
        (:attr:`benchmark.tracker.Tracker.deterministic`), which the
        conformance kit verifies; only then may a board call it deterministic.
    real_time : str
        Empty for an ordinary cell; for a closed-loop cell run in real time
        (:mod:`benchmark.closedloop.real_time`), the source of its step
        time: ``"declared 17 ms"`` or ``"measured median, this machine"``.
    """

    tracker: str
    tracker_version: str
    tracker_key: str
    params: dict[str, Any]
    dataset: str
    dataset_key: str
    modality: str
    seed: int
    init: str
    status: Status
    message: str
    scores: tuple[FrameScore, ...]
    elapsed_s: float
    detail: str = ""
    error_columns: tuple[str, ...] = ()
    training: str = ""
    read_s: float = 0.0
    pictures: tuple[Picture, ...] = ()
    deterministic: bool = False
    real_time: str = ""

    @property
    def key(self) -> CellKey:
        """Identity of the computation (see :class:`CellKey`)."""
        return CellKey(self.tracker_key, self.dataset_key, self.seed, self.init)

    @property
    def frames(self) -> pd.DataFrame:
        """The frame scores as a table (:func:`frame_table`)."""
        return frame_table(self.scores)

    def summary(self, metrics: Metrics = CORE) -> dict[str, float]:
        """The metrics of this cell (:func:`summarise`), those of ``metrics`` for its modality that its frames feed."""
        frames = self.frames
        return summarise(frames, metrics.for_board(self.modality, self.error_columns, columns_with_values(frames)))
