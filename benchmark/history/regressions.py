"""Regressions: what changed in a nightly run against the runs before it, and where each metric stepped.

For each tracker, dataset and metric (:mod:`benchmark.metrics`) a run is
compared with the earlier runs of the same series
(:data:`benchmark.history.database.SERIES`):

* **Accuracy** (every metric but speed: rates, RMSEs, robustness) compares
  the run's per-seed values with those of the last ``window`` earlier runs.
  It is a change when the 95 % percentile-bootstrap interval of the
  difference of the means (seeds resampled within each side,
  :func:`scipy.stats.bootstrap`) excludes zero *and* the difference reaches
  the metric's minimum effect (:attr:`benchmark.metrics.Metric.minimum_effect`:
  2 points for a rate, 10 % of the earlier value for an RMSE).  A
  deterministic tracker, or a single seed on both sides, has a point
  interval, so the minimum effect alone decides.
* **Speed** (metrics of kind ``speed``: fps) compares the run's median over
  seeds with the median of the last ``window`` earlier runs *on the same
  machine*; a change reaches the minimum effect (10 % of the earlier
  median).  Cells that spent less than ``min_step_s`` in their trackers'
  steps are too short to time.

A change for the worse is a regression, for the better an improvement.
:func:`steps` finds where a metric's level changed over the whole history
(penalised change-point detection, ``ruptures``), as a trend plot shows
it.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field

import numpy as np
import pandas as pd
import ruptures
from scipy.stats import DegenerateDataWarning, bootstrap

from benchmark.history.database import ESTIMATED, SERIES
from benchmark.metrics import CORE, SPEED, Metric, Metrics
from benchmark.report.display import format_value

CHANGE_COLUMNS = [
    "tracker",
    "dataset",
    "metric",
    "kind",
    "before",
    "after",
    "change",
    "low",
    "high",
    "verdict",
    "cause",
    "effects",
    "flag",
]
"""Columns of :func:`find_changes`'s table."""

ESTIMATED_SHARE = 0.02
"""How much the mean number of frames with an estimate may move (a share of the earlier count) before an RMSE
change beside it is flagged: a few frames more or less do not change what an RMSE averages over."""

GROUP_COLUMNS = ["verdict", "kind", "tracker", "cause", "datasets", "metrics", "count", "largest", "headline", "rows"]
"""Columns of :func:`group_changes`'s table."""


@dataclass(frozen=True)
class Thresholds:
    """The minimum effects, and how many earlier runs make the baseline.

    Attributes
    ----------
    window : int
        The earlier runs a run is compared with.
    min_step_s : float
        Speed is judged only where tonight's cells spent at least this
        long in ``step`` together: the fps of a few milliseconds is noise.
    overrides : Mapping
        Metric name to a minimum effect other than the metric's own, in
        the same terms (points for a rate, a share for an RMSE or fps),
        e.g. ``{"rmse_d_px": 0.2}``.
    """

    window: int = 5
    min_step_s: float = 2.0
    overrides: Mapping[str, float] = field(default_factory=dict)

    def minimum_effect(self, metric: Metric, before: float) -> float:
        """The smallest change of ``metric`` from ``before`` that counts, in the metric's units."""
        return metric.minimum_effect.of(before, self.overrides.get(metric.name))


def judged_metrics(cells: pd.DataFrame, metrics: Metrics) -> list[Metric]:
    """The metrics of ``metrics`` that are columns of a table of cells, in column order."""
    return [metric for column in cells.columns if (metric := metrics.named(str(column))) is not None]


def _varies(sample: np.ndarray) -> bool:
    return sample.size > 1 and bool(np.ptp(sample) > 0)


def _difference_interval(after: np.ndarray, before: np.ndarray) -> tuple[float, float]:
    """95 % percentile-bootstrap interval of ``mean(after) - mean(before)``, seeds resampled within each side.

    A side of one value, or of equal values, is taken as exact.
    """
    def difference(a: np.ndarray, b: np.ndarray, axis: int = -1) -> np.ndarray:
        return np.mean(a, axis=axis) - np.mean(b, axis=axis)

    varying = [sample for sample in (after, before) if _varies(sample)]
    if not varying:
        point = float(after.mean() - before.mean())
        return point, point
    if len(varying) == 1:
        sample = varying[0]
        sign = 1.0 if sample is after else -1.0
        fixed = before.mean() if sample is after else after.mean()
        data: tuple[np.ndarray, ...] = (sample,)

        def statistic(a: np.ndarray, axis: int = -1) -> np.ndarray:
            return sign * (np.mean(a, axis=axis) - fixed)
    else:
        data, statistic = (after, before), difference
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DegenerateDataWarning)
        result = bootstrap(
            data, statistic, vectorized=True, n_resamples=2000, method="percentile", rng=np.random.default_rng(0)
        )
    return float(result.confidence_interval.low), float(result.confidence_interval.high)


def _verdict(metric: Metric, change: float, significant: bool, minimum: float) -> str:
    if not significant or abs(change) < minimum or change == 0:
        return ""
    worse = change > 0 if metric.lower_is_better else change < 0
    return "regression" if worse else "improvement"


def _values(cells: pd.DataFrame, column: str) -> str:
    return ", ".join(sorted({str(value) for value in cells[column]}))


def _cause(now: pd.DataFrame, earlier: pd.DataFrame) -> str:
    """What differs between the cells of two runs besides their results: the tracker's version and parameters."""
    causes = []
    if _values(now, "tracker_version") != _values(earlier, "tracker_version"):
        causes.append(f"version {_values(earlier, 'tracker_version')} -> {_values(now, 'tracker_version')}")
    params_now, params_earlier = pd.DataFrame(list(now["params"])), pd.DataFrame(list(earlier["params"]))
    for name in sorted(set(params_now.columns) | set(params_earlier.columns)):
        old = _values(params_earlier, name) if name in params_earlier else "(none)"
        new = _values(params_now, name) if name in params_now else "(none)"
        if old != new:
            causes.append(f"{name} {old} -> {new}")
    if not causes and _values(now, "tracker_key") != _values(earlier, "tracker_key"):
        causes.append("the tracker's code or training changed")
    return "; ".join(causes)


def _effects(change: float, minimum: float) -> float:
    """The size of a change in minimum effects: what makes changes of different metrics comparable."""
    return abs(change) / minimum if minimum > 0 else math.inf


def _estimate_flag(metric: Metric, now: pd.DataFrame, earlier: pd.DataFrame) -> str:
    """Why an RMSE change may not mean what it says: the frames it averages over changed in number with it.

    An RMSE is taken over the frames with an estimate and a truth; a tracker
    that stops reporting on its hardest frames "improves" its RMSE.  Empty
    for other metrics, for cells recorded before the count was kept, and for
    counts within :data:`ESTIMATED_SHARE` of each other.
    """
    if not any(column.startswith("err_") for column in metric.columns) or ESTIMATED not in now or ESTIMATED not in earlier:
        return ""
    after, before = now[ESTIMATED].dropna(), earlier[ESTIMATED].dropna()
    if after.empty or before.empty:
        return ""
    after_mean, before_mean = float(after.mean()), float(before.mean())
    if abs(after_mean - before_mean) <= max(ESTIMATED_SHARE * before_mean, 0.5):
        return ""
    return f"frames with an estimate {before_mean:.0f} -> {after_mean:.0f}"


def _step_seconds(cells: pd.DataFrame) -> float:
    """The time the cells spent in their trackers' steps, from their frames and fps."""
    return float((cells["frames"] / cells[SPEED.name]).sum()) if SPEED.name in cells else 0.0


def find_changes(
    history_cells: pd.DataFrame,
    run_id: int,
    thresholds: Thresholds | None = None,
    against: Sequence[int] | None = None,
    metrics: Metrics = CORE,
) -> pd.DataFrame:
    """The changes of a run against the runs before it (or other given runs), regressions first.

    Parameters
    ----------
    history_cells : pandas.DataFrame
        Cells of the history (:meth:`benchmark.history.database.History.cells`),
        at least those of ``run_id`` and the runs before it.
    run_id : int
        The run to judge.
    thresholds : Thresholds, optional
        Minimum effects and baseline window; the defaults above.
    against : sequence of int, optional
        The runs to compare with (``trackbench compare``); by default the
        last ``thresholds.window`` runs before ``run_id`` that share a series
        with it (for speed: on the same machine).
    metrics : Metrics
        The catalogue of metrics to judge (those that are columns of the
        history's cells).

    Returns
    -------
    pandas.DataFrame
        Columns :data:`CHANGE_COLUMNS`: per tracker, dataset and metric with
        a verdict, the earlier and current values (mean over seeds, or
        median for speed), their difference with its interval, ``kind``
        (``speed`` for a metric of that kind, else ``accuracy``), ``verdict`` (``regression`` or
        ``improvement``), ``cause`` (the tracker's version or parameters
        that changed, if any), ``effects`` (``|change|`` in minimum effects)
        and ``flag`` (for an RMSE: the number of frames with an estimate
        changed with it, see :func:`_estimate_flag`).  Only cells with status
        ``ok`` count.
    """
    thresholds = thresholds or Thresholds()
    cells = history_cells[history_cells["status"] == "ok"]
    now = cells[cells["run_id"] == run_id]
    rows: list[dict[str, object]] = []
    if now.empty:
        return pd.DataFrame(columns=CHANGE_COLUMNS)
    machine = now["machine_key"].iloc[0]
    candidates = cells["run_id"].isin(against) if against is not None else cells["run_id"] < run_id
    earlier_all = cells[candidates & cells.set_index(SERIES).index.isin(now.set_index(SERIES).index)]
    for (tracker, dataset_key), current in now.groupby(["tracker", "dataset_key"], sort=True):
        earlier = earlier_all[(earlier_all["tracker"] == tracker) & (earlier_all["dataset_key"] == dataset_key)]
        if earlier.empty:
            continue
        accuracy_runs = sorted(earlier["run_id"].unique())[-thresholds.window :]
        baseline = earlier[earlier["run_id"].isin(accuracy_runs)]
        shared = dict(tracker=tracker, dataset=current["dataset"].iloc[-1], cause=_cause(current, baseline))
        judged = judged_metrics(current, metrics)
        for metric in (m for m in judged if m.kind != "speed"):
            after = current[metric.name].dropna().to_numpy(dtype=float)
            before = baseline[metric.name].dropna().to_numpy(dtype=float) if metric.name in baseline else np.array([])
            if not after.size or not before.size:
                continue
            low, high = _difference_interval(after, before)
            change = float(after.mean() - before.mean())
            minimum = thresholds.minimum_effect(metric, float(before.mean()))
            verdict = _verdict(metric, change, low > 0 or high < 0, minimum)
            if verdict:
                rows.append(
                    dict(shared, metric=metric.name, kind="accuracy", before=float(before.mean()),
                         after=float(after.mean()), change=change, low=low, high=high, verdict=verdict,
                         effects=_effects(change, minimum), flag=_estimate_flag(metric, current, baseline))
                )
        same_machine = earlier[earlier["machine_key"] == machine]
        speed_runs = sorted(same_machine["run_id"].unique())[-thresholds.window :]
        step_s = _step_seconds(current)
        for metric in (m for m in judged if m.kind == "speed"):
            speeds = same_machine[same_machine["run_id"].isin(speed_runs)].groupby("run_id")[metric.name].median()
            speeds = speeds.dropna()
            now_median = float(current[metric.name].median())
            if len(speeds) and math.isfinite(now_median) and step_s >= thresholds.min_step_s:
                before_median = float(speeds.median())
                change = now_median - before_median
                minimum = thresholds.minimum_effect(metric, before_median)
                verdict = _verdict(metric, change, True, minimum)
                if verdict:
                    rows.append(
                        dict(shared, metric=metric.name, kind="speed", before=before_median, after=now_median,
                             change=change, low=math.nan, high=math.nan, verdict=verdict,
                             effects=_effects(change, minimum), flag="")
                    )
    table = pd.DataFrame(rows, columns=CHANGE_COLUMNS)
    order = table.assign(_regression=table["verdict"] != "regression")
    return order.sort_values(["_regression", "tracker", "dataset", "metric"]).drop(columns="_regression").reset_index(
        drop=True
    )


def group_changes(changes: pd.DataFrame, metrics: Metrics = CORE) -> pd.DataFrame:
    """The changes of :func:`find_changes` folded into one row per verdict, kind, tracker and cause.

    One parameter change moves many metrics on many datasets; a reader wants
    to see it once, with its cause, its largest effect, and what it touched.

    Parameters
    ----------
    changes : pandas.DataFrame
        A table of :data:`CHANGE_COLUMNS`.
    metrics : Metrics
        The catalogue that rounds the headline's value.

    Returns
    -------
    pandas.DataFrame
        Columns :data:`GROUP_COLUMNS`: ``datasets`` and ``metrics`` (lists,
        in order of first appearance), ``count`` (changes folded in),
        ``largest`` (the largest change in minimum effects), ``headline``
        (that change as text: ``correct_pct -12.3 on camera/S1``) and
        ``rows`` (the group's changes, largest first).  Regressions come
        first, accuracy before speed, then the largest group first.
    """
    groups = []
    for (verdict, kind, tracker, cause), rows in changes.groupby(["verdict", "kind", "tracker", "cause"], sort=False):
        rows = rows.sort_values("effects", ascending=False, kind="stable").reset_index(drop=True)
        top = rows.iloc[0]
        change = format_value(str(top["metric"]), float(top["change"]), metrics)
        groups.append(
            dict(
                verdict=verdict, kind=kind, tracker=tracker, cause=cause,
                datasets=list(dict.fromkeys(rows["dataset"])), metrics=list(dict.fromkeys(rows["metric"])),
                count=len(rows), largest=float(top["effects"]),
                headline=f"{top['metric']} {'+' if top['change'] > 0 else ''}{change} on {top['dataset']}", rows=rows,
            )
        )
    table = pd.DataFrame(groups, columns=GROUP_COLUMNS)
    order = table.assign(_speed=table["kind"] == "speed", _regression=table["verdict"] != "regression")
    return (
        order.sort_values(["_regression", "_speed", "largest"], ascending=[True, True, False], kind="stable")
        .drop(columns=["_speed", "_regression"])
        .reset_index(drop=True)
    )


@dataclass(frozen=True)
class Step:
    """A change of level in a metric's history.

    Attributes
    ----------
    run_id : int
        The first run at the new level.
    before, after : float
        The median level before and from that run.
    """

    run_id: int
    before: float
    after: float


def steps(levels: pd.Series, minimum_effect: float) -> list[Step]:
    """Where a metric's level stepped over its history.

    Parameters
    ----------
    levels : pandas.Series
        One value per run (e.g. the mean over seeds), indexed by run id in
        run order; NaN values are skipped.
    minimum_effect : float
        The smallest step that counts, in the metric's units: the penalty
        of the change-point search (an L1 cost, robust to single outliers)
        is set so that only steps of about this size over a few runs pay
        for themselves, and smaller steps found are dropped.  The latest
        run is a step of its own when it leaves the level of the runs
        before it by this much (a new level needs two runs to be found
        otherwise), so tonight's change shows at once.

    Returns
    -------
    list of Step
        In run order.
    """
    values = levels.dropna()
    if len(values) < 2 or minimum_effect <= 0:
        return []
    signal = values.to_numpy(dtype=float).reshape(-1, 1)
    ends = ruptures.Pelt(model="l1", min_size=2, jump=1).fit(signal).predict(pen=1.5 * minimum_effect)
    found = []
    for start, end, stop in zip([0, *ends[:-2]], ends[:-1], ends[1:]):
        before, after = float(np.median(signal[start:end])), float(np.median(signal[end:stop]))
        if abs(after - before) >= minimum_effect:
            found.append(Step(int(values.index[end]), before, after))
    # A segment needs two runs, so the latest run alone cannot start one: it is a step when it leaves its level.
    start = ends[-2] if len(ends) > 1 else 0
    level, latest = float(np.median(signal[start:-1])), float(signal[-1, 0])
    if abs(latest - level) >= minimum_effect:
        found.append(Step(int(values.index[-1]), level, latest))
    return found
