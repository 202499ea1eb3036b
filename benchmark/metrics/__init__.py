"""The metrics room: every number a board, the history and the regressions report about a tracker.

A :class:`Metric` declares all there is to know about one number: its name
(the board column, unit last: ``correct_pct``, ``rmse_d_px``, ``cpu_fps``), which
direction is better, how a cell's value comes from its frames, how it is
shown and the smallest change a regression counts.  Results
(:func:`benchmark.results.summarise`), intervals over seeds
(:mod:`benchmark.intervals`), boards (:mod:`benchmark.leaderboard`), the
text forms of a board (:mod:`benchmark.report.display`), regressions
(:mod:`benchmark.history.regressions`) and the nightly site iterate over
the metrics of a :class:`Metrics` catalogue; none of them names a metric.

How a value comes from frames
-----------------------------
A metric reduces a table of frame scores (:func:`benchmark.results.frame_table`,
of one cell or of several cells pooled) to a few **sums**, and its value is a
function of those sums.  Sums of several tables pool by adding them (or by
taking their largest, ``pool="max"``), so that a board row pools its seeds
and the bootstrap over seeds (:mod:`benchmark.intervals`) resamples seeds at
the cost of a sum.  A metric whose sums are squares of errors first divides
the errors by a **scale** common to all the tables pooled (the largest
error), which keeps the sums finite for any finite errors.

Where metrics come from
-----------------------
The detection rates (seeds/004, section VI-C, Table V) and the speed
(seeds/000, section 5.2.5) are core metrics, on every board.  Speed is
counted twice: ``cpu_fps`` per second of the CPU time of the thread that
ran ``step``, the tracker's own work, which is what is ranked, trended and
judged; and ``wall_fps`` per second of its wall time, which also counts
the waits for a core that other processes held, shown beside it and never
judged (:mod:`benchmark.runner`).  Each error
column ``err_X`` of a modality's scorer is an RMSE ``rmse_X``
(seeds/000, section 5.2.3); the first of them ranks the board after the
correct rate.  Plugins add others through the ``trackbench_register_metrics``
hook (:meth:`benchmark.registry.Registry.add_metric`), for every modality or
for one; trackbench's own robustness metrics are added that way
(:mod:`benchmark.metrics.robustness`), and so are the following metrics of
closed-loop runs (:mod:`benchmark.metrics.closed_loop`), which declare the
frame columns they need (:attr:`Metric.requires`) so that a board whose
frames lack them does not show them.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable, Collection, Iterable, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Annotated, Literal

import numpy as np
from pydantic import ConfigDict, Field, NonNegativeFloat, NonNegativeInt
from pydantic.dataclasses import dataclass as pydantic_dataclass

from benchmark.model import Outcome

if TYPE_CHECKING:
    import pandas as pd

Kind = Literal["detection", "accuracy", "speed", "robustness", "following"]
KINDS: tuple[Kind, ...] = ("detection", "accuracy", "speed", "robustness", "following")
"""The kinds of metric, in the order their columns stand on a board."""

CLOSED_LOOP_KINDS: tuple[Kind, ...] = ("following", "detection", "accuracy", "speed", "robustness")
"""The order of a closed-loop board (:mod:`benchmark.leaderboard`): how the vehicle followed the cable first,
then the open-loop metrics of the frames it saw."""

NAME_PATTERN = r"^[a-z][a-z0-9]*(_[a-z0-9]+)*$"
"""A metric's name: lower-case words joined by ``_``, the unit last (``rmse_d_px``)."""

Sums = Callable[..., Sequence[float]]
"""``sums(frames, scale)``: a metric's sums of a frame table, given the scale of the tables pooled with it."""
Value = Callable[[np.ndarray, float], np.ndarray]
"""A metric's value from its pooled sums (the last axis; any leading axes are kept) and the scale."""
Scale = Callable[..., float]
"""``scale(tables)``: the scale of a metric's sums over all the tables that are pooled together."""


def unit_scale(tables: Sequence[pd.DataFrame]) -> float:
    """The scale of a metric whose sums need none: 1."""
    return 1.0


@pydantic_dataclass(frozen=True)
class Effect:
    """The smallest change of a metric that counts as a change (:mod:`benchmark.history.regressions`).

    Attributes
    ----------
    amount : float
        In the metric's own units, or as a share of the earlier value when
        ``relative``.
    relative : bool
        Whether ``amount`` is a share of the earlier value.
    """

    amount: NonNegativeFloat
    relative: bool = False

    def of(self, before: float, amount: float | None = None) -> float:
        """The smallest change from ``before`` that counts, in the metric's units (``amount`` overrides the own)."""
        share = self.amount if amount is None else amount
        return share * abs(before) if self.relative else share


@pydantic_dataclass(frozen=True, config=ConfigDict(arbitrary_types_allowed=True))
class Metric:
    """One number reported about a tracker on a sequence.

    Attributes
    ----------
    name : str
        Its column on boards and in the history, the unit last
        (``correct_pct``, ``rmse_d_px``, ``failures_per100``).
    better : {"higher", "lower"}
        Which direction is an improvement.
    kind : {"detection", "accuracy", "speed", "robustness", "following"}
        What it measures; boards group their columns by kind
        (:data:`KINDS`), and regressions judge speed on the same machine
        only.  ``following`` is how a vehicle steered by the tracker
        followed the cable (:mod:`benchmark.metrics.closed_loop`).
    columns : tuple of str
        The frame-table columns it reads; seeds that agree on these (and on
        ``frame``) for every interval metric are seeds that agree.
    sums : callable
        ``sums(frames, scale)``: the additive sums of a frame table.
    value : callable
        ``value(sums, scale)``: the value from pooled sums (last axis),
        vectorised over any leading axes; NaN where it is undefined.
    digits : int
        Decimals shown in reports.
    minimum_effect : Effect
        The smallest change a regression counts.
    description : str
        One line for a reader of the board.
    scale : callable
        ``scale(tables)``: the scale shared by the tables pooled together;
        1 unless the sums need one.
    pool : {"sum", "max"}
        How the sums of several tables pool: added, or their largest (NaN
        sums, of a table with nothing to say, are skipped).
    interval : bool
        Whether boards show its 95 % interval over seeds.
    spread : bool
        Whether boards show its standard deviation over seeds.
    ranks : bool
        Whether boards rank trackers by it (in board order, after the
        metrics before it).
    headline : bool
        Whether trend plots show it.
    judged : bool
        Whether regressions judge it (:mod:`benchmark.history.regressions`);
        a number that measures the machine's other work more than the
        tracker's, such as the wall-clock speed, is shown but not judged.
    requires : tuple of str
        Frame-table columns only some sequences give (the ``loop_*``
        columns of closed-loop runs): a board whose frames hold no value in
        one of them leaves the metric out (:meth:`Metrics.for_board`).
        Empty for a metric every frame table can feed.
    """

    name: Annotated[str, Field(pattern=NAME_PATTERN)]
    better: Literal["higher", "lower"]
    kind: Kind
    columns: tuple[str, ...]
    sums: Sums
    value: Value
    digits: NonNegativeInt
    minimum_effect: Effect
    description: str = ""
    scale: Scale = unit_scale
    pool: Literal["sum", "max"] = "sum"
    interval: bool = True
    spread: bool = False
    ranks: bool = False
    headline: bool = False
    judged: bool = True
    requires: tuple[str, ...] = ()

    def feeds_on(self, present: Collection[str]) -> bool:
        """Whether frames with values in the columns ``present`` give it one: it requires none missing."""
        return all(column in present for column in self.requires)

    @property
    def unit(self) -> str:
        """The unit, the last word of the name: ``pct``, ``px``, ``fps`` (of ``cpu_fps``)."""
        return self.name.rsplit("_", 1)[-1]

    @property
    def lower_is_better(self) -> bool:
        return self.better == "lower"

    @property
    def interval_columns(self) -> tuple[str, str]:
        """The board columns of the low and high end of its interval, unit last: ``correct_lo_pct``."""
        return derived_column(self.name, "lo"), derived_column(self.name, "hi")

    @property
    def spread_column(self) -> str:
        """The board column of its standard deviation over seeds: ``correct_sd_pct``."""
        return derived_column(self.name, "sd")

    def pooled(self, sums: np.ndarray, axis: int) -> np.ndarray:
        """Sums of several tables (along ``axis``) pooled as this metric pools them."""
        return np.fmax.reduce(sums, axis=axis) if self.pool == "max" else sums.sum(axis=axis)

    def of(self, frames: pd.DataFrame) -> float:
        """The value of one frame table (one cell, or several pooled into one table)."""
        scale = self.scale([frames])
        return float(self.value(np.asarray(self.sums(frames, scale), dtype=float), scale))

    def format(self, value: object) -> str:
        """The value as reports show it: ``digits`` decimals; empty for a missing value."""
        if value is None or (isinstance(value, float) and math.isnan(value)):
            return ""
        return f"{value:.{self.digits}f}"


def derived_column(name: str, part: str) -> str:
    """A column derived from a metric's, ``part`` before the unit: ``correct_pct`` and ``lo`` give ``correct_lo_pct``."""
    stem, _, unit = name.rpartition("_")
    return f"{stem}_{part}_{unit}" if stem else f"{name}_{part}"


# --- the core metrics ---------------------------------------------------------------------------------------------


def columns_with_values(frames: pd.DataFrame) -> frozenset[str]:
    """The columns of a frame table with at least one value (not NaN, not None)."""
    return frozenset(str(column) for column in frames.columns[frames.notna().any(axis=0).to_numpy()])


def sequence_starts(frames: pd.DataFrame, rows: np.ndarray) -> np.ndarray:
    """Of the selected ``rows`` (a boolean mask) of a frame table, those that start a cell's sequence.

    The first row starts one, and so does every row whose ``cell_id``
    differs from the row before or whose ``frame`` does not increase:
    pooled tables hold several cells one after another.
    """
    count = int(np.count_nonzero(rows))
    starts = np.zeros(count, dtype=bool)
    if count:
        starts[0] = True
        if "cell_id" in frames:
            cells = frames["cell_id"].to_numpy()[rows]
            starts[1:] |= cells[1:] != cells[:-1]
        if "frame" in frames:
            indices = frames["frame"].to_numpy(dtype=float)[rows]
            starts[1:] |= ~(indices[1:] > indices[:-1])
    return starts


def outcomes(frames: pd.DataFrame) -> np.ndarray:
    """The ``outcome`` column as an object array (``None`` or NaN for a frame without truth); empty without one."""
    return frames["outcome"].to_numpy(dtype=object) if "outcome" in frames else np.array([], dtype=object)


def scored(values: np.ndarray) -> np.ndarray:
    """Which of an ``outcome`` array's frames have an outcome (a truth to be scored against)."""
    return np.logical_or.reduce([values == str(outcome) for outcome in Outcome], initial=False)


def _outcome_sums(outcome: Outcome, frames: pd.DataFrame, scale: float) -> tuple[float, float]:
    """Scored frames, and those with ``outcome``."""
    values = outcomes(frames)
    return float(np.count_nonzero(scored(values))), float(np.count_nonzero(values == str(outcome)))


def percentage(sums: np.ndarray, scale: float) -> np.ndarray:
    """``100 * part / whole`` of sums ``(whole, part)``; NaN for an empty whole."""
    with np.errstate(invalid="ignore", divide="ignore"):
        return 100.0 * sums[..., 1] / sums[..., 0]


def ratio(sums: np.ndarray, scale: float) -> np.ndarray:
    """``total / count`` of sums ``(count, total)``: a mean; NaN for no count."""
    with np.errstate(invalid="ignore", divide="ignore"):
        return sums[..., 1] / sums[..., 0]


def single(sums: np.ndarray, scale: float) -> np.ndarray:
    """The one sum of a metric that keeps one (a largest value, a longest run), as its value."""
    return sums[..., 0]


def _finite(frames: pd.DataFrame, column: str) -> np.ndarray:
    values = frames[column].to_numpy(dtype=float) if column in frames else np.array([])
    return values[np.isfinite(values)]


def _largest_error(column: str, tables: Sequence[pd.DataFrame]) -> float:
    """The largest finite ``|error|`` of a column over all tables, the unit errors are squared in."""
    values = [np.abs(_finite(table, column)) for table in tables]
    return float(np.max(np.concatenate(values), initial=0.0)) if values else 0.0


def _square_sums(column: str, frames: pd.DataFrame, scale: float) -> tuple[float, float]:
    """Finite errors, and the sum of their squares in units of ``scale``."""
    values = _finite(frames, column)
    return float(values.size), float(np.sum((values / scale) ** 2)) if scale > 0 else 0.0


def _root_mean_square(sums: np.ndarray, scale: float) -> np.ndarray:
    """``scale * sqrt(sum / count)``: the RMSE, never above the largest error; NaN for no error."""
    with np.errstate(invalid="ignore", divide="ignore"):
        return scale * np.sqrt(sums[..., 1] / sums[..., 0])


def _time_sums(column: str, frames: pd.DataFrame, scale: float) -> tuple[float, float]:
    """Frames processed whose ``step`` was timed in ``column``, and its milliseconds over them.

    A frame without a time (``step_ms`` of a results file older than the
    CPU timing, :mod:`benchmark.store`) counts in neither sum.
    """
    times = _finite(frames, column)
    return float(times.size), float(times.sum())


def _frames_per_second(sums: np.ndarray, scale: float) -> np.ndarray:
    seconds = sums[..., 1] / 1000.0
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(seconds > 0, sums[..., 0] / seconds, math.nan)


RATES: tuple[Metric, ...] = tuple(
    Metric(
        name=f"{outcome}_pct",
        better="higher" if outcome is Outcome.CORRECT else "lower",
        kind="detection",
        columns=("outcome",),
        sums=functools.partial(_outcome_sums, outcome),
        value=percentage,
        digits=1,
        minimum_effect=Effect(2.0),
        description=f"share of scored frames that are {outcome} (seeds/004, Table V)",
        spread=outcome is Outcome.CORRECT,
        ranks=outcome is Outcome.CORRECT,
        headline=outcome is Outcome.CORRECT,
    )
    for outcome in Outcome
)
"""The detection rates, percentages of scored frames summing to 100 (seeds/004, section VI-C, Table V)."""


def _speed(name: str, column: str, description: str, **flags: bool) -> Metric:
    """Frames processed per second of the step times in a frame table's ``column``; no interval over seeds."""
    return Metric(
        name=name,
        better="higher",
        kind="speed",
        columns=(column,),
        sums=functools.partial(_time_sums, column),
        value=_frames_per_second,
        digits=0,
        minimum_effect=Effect(0.10, relative=True),
        description=description,
        interval=False,
        **flags,
    )


SPEED = _speed(
    "cpu_fps",
    "step_ms",
    "frames processed per second of CPU time of the thread running the tracker's step (seeds/000, section 5.2.5)",
    headline=True,
)
"""Frames processed per second of the CPU time of ``step``'s thread: the tracker's own work.

It measures the machine's CPU too, so it has no interval over seeds and is
compared on the same machine only.
"""

WALL_SPEED = _speed(
    "wall_fps",
    "wall_ms",
    "frames processed per second of wall-clock time of the tracker's step, waits for a core held by other "
    "processes included; shown, not judged",
    judged=False,
)
"""Frames processed per second of the wall time of ``step``; not judged for regressions.

The wall time adds to the tracker's work every wait for a core that
another process held: on a shared two-core machine it told how busy the
neighbours were, and judged at 10 % it turned nightlies with nothing
changed red.  :data:`SPEED` judges the tracker's speed; this one is shown
beside it, so that a reader sees how far the machine's load stretched the
run.
"""


def error_metric(column: str, *, ranks: bool = False) -> Metric:
    """The RMSE of a modality's error column ``err_X``, named ``rmse_X`` (seeds/000, section 5.2.3).

    Over frames with both an estimate and a truth (finite errors).  The
    RMSE ``sqrt(mean(e**2))`` is computed as ``m * sqrt(mean((e/m)**2))``
    with ``m`` the largest ``|e|`` of the tables pooled: equal to the plain
    formula up to rounding wherever that does not overflow, and finite for
    any finite errors (scorers report an error too large for a float as
    ``+-sys.float_info.max``, :meth:`benchmark.modality.Scorer.score`).
    """
    return Metric(
        name="rmse_" + column.removeprefix("err_"),
        better="lower",
        kind="accuracy",
        columns=(column,),
        sums=functools.partial(_square_sums, column),
        value=_root_mean_square,
        scale=functools.partial(_largest_error, column),
        digits=2,
        minimum_effect=Effect(0.10, relative=True),
        description=f"root mean square of {column} over frames with an estimate and a truth",
        ranks=ranks,
        headline=ranks,
    )


ERROR_PREFIX = "rmse_"


def error_columns_of(columns: Iterable[str]) -> tuple[str, ...]:
    """The error columns whose RMSEs are among ``columns`` (a table of summaries): ``rmse_d_px`` -> ``err_d_px``."""
    return tuple("err_" + str(c).removeprefix(ERROR_PREFIX) for c in columns if str(c).startswith(ERROR_PREFIX))


@dataclass(frozen=True)
class Metrics:
    """A catalogue of metrics: the core ones, each modality's errors, and those plugins added.

    Immutable: :meth:`adding` returns a new catalogue, so the core catalogue
    :data:`CORE` is a safe default everywhere.

    Attributes
    ----------
    added : tuple of (Metric, str or None)
        Metrics added by plugins, each with the modality it is for (None:
        every modality), in the order they were added.
    """

    added: tuple[tuple[Metric, str | None], ...] = ()

    def adding(self, metric: Metric, modality: str | None = None) -> Metrics:
        """This catalogue with ``metric`` added, for one modality or (None) for all.

        Raises
        ------
        ValueError
            If ``metric`` is not a :class:`Metric`, or its name or a column
            derived from it is already a metric's or a board's column.
        """
        if not isinstance(metric, Metric):
            raise ValueError(f"{metric!r} is not a benchmark.metrics.Metric")
        taken = {
            column
            for known, scope in self._all()
            if scope is None or modality is None or scope == modality
            for column in (known.name, *known.interval_columns, known.spread_column)
        }
        mine = {metric.name, *metric.interval_columns, metric.spread_column}
        clash = sorted(mine & (taken | RESERVED_COLUMNS)) or (
            [metric.name] if metric.name.startswith(ERROR_PREFIX) else []
        )
        if clash:
            raise ValueError(f"metric {metric.name!r}: {', '.join(clash)} is taken (rmse_* names are the modalities')")
        return Metrics((*self.added, (metric, modality)))

    def _all(self) -> Iterable[tuple[Metric, str | None]]:
        yield from ((metric, None) for metric in (*RATES, SPEED, WALL_SPEED))
        yield from self.added

    def for_board(
        self,
        modality: str | None,
        error_columns: Sequence[str],
        present: Collection[str] | None = None,
        kinds: Sequence[Kind] = KINDS,
    ) -> tuple[Metric, ...]:
        """The metrics of a board of ``modality`` whose scorer has ``error_columns``, in board order.

        Board order is by kind (``kinds``, :data:`KINDS` by default; a
        closed-loop board puts the following metrics first,
        :data:`CLOSED_LOOP_KINDS`), then the rates, the RMSEs
        in the scorer's order, the speeds (CPU, then wall) and the added
        metrics in the order they were added.  Given the frame-table
        columns ``present`` with a value (:func:`columns_with_values`), an
        added metric that :attr:`~Metric.requires` another is left out.
        """
        errors = [error_metric(column, ranks=i == 0) for i, column in enumerate(error_columns)]
        added = [
            metric
            for metric, scope in self.added
            if (scope is None or scope == modality) and (present is None or metric.feeds_on(present))
        ]
        ordered = [*RATES, *errors, SPEED, WALL_SPEED, *added]
        return tuple(sorted(ordered, key=lambda metric: kinds.index(metric.kind)))

    def named(self, name: str) -> Metric | None:
        """The metric whose column is ``name``, of any modality (``rmse_X`` for any error ``err_X``); else None."""
        for metric, _ in self._all():
            if metric.name == name:
                return metric
        return error_metric("err_" + name.removeprefix(ERROR_PREFIX)) if name.startswith(ERROR_PREFIX) else None

    def of_column(self, column: str) -> Metric | None:
        """The metric a board column shows: its own, or its interval's ends or spread (``correct_lo_pct``)."""
        stem, _, unit = column.rpartition("_")
        base, _, part = stem.rpartition("_")
        derived_from = self.named(f"{base}_{unit}" if base else unit) if part in ("lo", "hi", "sd") else None
        return derived_from or self.named(column)


RESERVED_COLUMNS = frozenset(
    {
        "rank", "tracker", "dataset", "init", "real_time", "training", "seeds", "frames", "deterministic", "status",
        "message",
    }
)
"""Board and history columns that are not metrics."""

CORE = Metrics()
"""The catalogue of the core metrics alone: the rates, the speed and each modality's RMSEs."""


__all__ = [
    "CLOSED_LOOP_KINDS",
    "CORE",
    "KINDS",
    "RATES",
    "SPEED",
    "WALL_SPEED",
    "Effect",
    "Metric",
    "Metrics",
    "columns_with_values",
    "derived_column",
    "error_columns_of",
    "error_metric",
    "outcomes",
    "scored",
    "sequence_starts",
    "percentage",
    "ratio",
    "single",
    "unit_scale",
]
