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
* **Speed** (the judged metrics of kind ``speed``: ``cpu_fps``; ``wall_fps``
  is shown, never judged, :data:`benchmark.metrics.WALL_SPEED`) compares
  the run's median over seeds with the median of the per-run medians of the
  last ``window`` earlier runs *on the same machine*.  A change counts when
  it exceeds both the minimum effect (10 % of the earlier median) and the
  series' own noise, ``k`` times the scaled median absolute deviation of
  those per-run medians (:func:`speed_noise`); the larger of the two is the
  row's ``noise``.  With fewer than :data:`NOISE_RUNS` earlier runs on the
  machine there is no noise estimate: a change beyond the minimum effect is
  then listed with the verdict ``unjudged`` and a ``note`` saying why.  Cells
  that spent less than ``min_step_s`` in their trackers' steps are too
  short to time.  A speed change is a candidate until a repeat of its cells
  holds it (:func:`confirm_speed`, run by :mod:`benchmark.history.nightly`):
  ``confirmed`` is then true, or the verdict becomes ``unconfirmed``.

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
    "noise",
    "confirmed",
    "effects",
    "note",
]
"""Columns of :func:`find_changes`'s table."""

ESTIMATED_SHARE = 0.02
"""How much the mean number of frames with an estimate may move (a share of the earlier count) before an RMSE
change beside it is noted: a few frames more or less do not change what an RMSE averages over.

Set by reasoning, not fitted to any split: 2 % of a 250-frame sequence is five frames, below one
failure run of the trackers here (their longest failures run 0-136 frames on the default board).
"""

JUDGED = ("regression", "improvement")
"""The verdicts of a change judged beyond its noise."""

VERDICTS = (*JUDGED, "unconfirmed", "unjudged")
"""Every verdict a change can have: the two judged ones, a speed change a repeat did not hold, and a speed change
on a machine with too few earlier runs to estimate its noise."""

GROUP_COLUMNS = ["verdict", "kind", "tracker", "cause", "datasets", "metrics", "count", "largest", "headline", "rows"]
"""Columns of :func:`group_changes`'s table."""

NOISE_RUNS = 3
"""Earlier runs on the same machine without which a speed series has no noise estimate, and no speed verdict.

Three is the fewest whose median absolute deviation is not set by one
value alone (of two values it is half their distance).
"""

MAD_TO_SD = 1.4826
"""The median absolute deviation of normal values times this is their standard deviation."""

NOISE_MULTIPLE = 3.0
"""``k``: a speed change counts beyond ``k`` scaled MADs of the earlier runs' medians (see :func:`speed_noise`)."""


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

    noise_multiple : float
        ``k`` of the speed noise (:func:`speed_noise`).
    noise_runs : int
        Earlier runs on the same machine without which a speed series has
        no noise estimate and no speed verdict.
    """

    window: int = 5
    min_step_s: float = 2.0
    overrides: Mapping[str, float] = field(default_factory=dict)
    noise_multiple: float = NOISE_MULTIPLE
    noise_runs: int = NOISE_RUNS

    def minimum_effect(self, metric: Metric, before: float) -> float:
        """The smallest change of ``metric`` from ``before`` that counts, in the metric's units."""
        return metric.minimum_effect.of(before, self.overrides.get(metric.name))


def judged_metrics(cells: pd.DataFrame, metrics: Metrics) -> list[Metric]:
    """The metrics of ``metrics`` that are columns of a table of cells and are judged, in column order.

    A metric that is shown but not judged (:attr:`benchmark.metrics.Metric.judged`, such as ``wall_fps``) is left out.
    """
    return [metric for column in cells.columns if (metric := metrics.named(str(column))) is not None and metric.judged]


def speed_noise(medians: Sequence[float] | np.ndarray, multiple: float = NOISE_MULTIPLE) -> float:
    """The noise of a speed series: ``multiple`` times the scaled median absolute deviation of its per-run medians.

    Parameters
    ----------
    medians : sequence of float
        One value per earlier run on the machine: the median over its seeds.
    multiple : float
        ``k``.

    Returns
    -------
    float
        ``k * 1.4826 * median(|m - median(m)|)``, in the metric's units.

    Notes
    -----
    The scaled MAD estimates the standard deviation of normal values and,
    unlike the standard deviation, is not inflated by one run that a busy
    neighbour slowed.  ``k = 3`` is the usual three-sigma rule: a normal
    night leaves it with probability 0.27 %, and a change must also hold on
    a repeat to count, which a chance excursion does with about that
    probability again.  The estimate is loose from the three to five runs of
    a window (the MAD of three values is the middle one's distance to the
    nearer other), so it may come out small; the metric's minimum effect
    (10 %) is then the floor, as :func:`find_changes` takes the larger of
    the two.

    Measured on this project's shared two-core machine (load average 9 to
    16 from other work throughout): ten tiny nightlies with nothing changed
    (hough, foresti_lines and condensation-fast on camera/S5 and S6, one
    seed), five of them while another process spun on both cores.  The
    scaled MAD of ``cpu_fps`` over five runs was 1.1 % to 7.2 % of the
    median for eleven of the twelve series, and 19.7 % for
    condensation-fast on S6 under the extra load (its runs 1103 to 1590
    fps); that of ``wall_fps`` was 1.3 % to 46 %, its range up to 198 %.
    With ``k = 3`` the typical CPU series' noise (3 x 2-6 %) lies around
    the 10 % floor, so the floor decides for a steady series and the noise
    for one the machine disturbs.  Of the 24 series and nights with a noise
    estimate (nights 4 and 5 of both sets) none gave a verdict, while the
    fixed 10 % rule on the same runs flagged up to 2 of 4 nights per series
    on ``cpu_fps`` and 1 to 4 on ``wall_fps``
    (``tests/benchmark/history/test_regressions.py`` keeps one such series).
    """
    values = np.asarray(medians, dtype=float)
    values = values[np.isfinite(values)]
    if not values.size:
        return math.nan
    return float(multiple * MAD_TO_SD * np.median(np.abs(values - np.median(values))))


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


def _estimate_note(metric: Metric, now: pd.DataFrame, earlier: pd.DataFrame) -> str:
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
    """The CPU time the cells spent in their trackers' steps, from their frames and CPU speed."""
    return float((cells["frames"] / cells[SPEED.name]).sum()) if SPEED.name in cells else 0.0


def _speed_change(
    metric: Metric, current: pd.DataFrame, same_machine: pd.DataFrame, thresholds: Thresholds
) -> dict[str, object] | None:
    """The speed change of one series (see the module's notes), or None when there is none to list."""
    if metric.name not in same_machine or not math.isfinite(now_median := float(current[metric.name].median())):
        return None
    timed = same_machine.dropna(subset=[metric.name])
    runs = sorted(timed["run_id"].unique())[-thresholds.window :]
    medians = timed[timed["run_id"].isin(runs)].groupby("run_id")[metric.name].median()
    if medians.empty or _step_seconds(current) < thresholds.min_step_s:
        return None
    before = float(medians.median())
    change = now_median - before
    minimum = thresholds.minimum_effect(metric, before)
    if not _verdict(metric, change, True, minimum):
        return None
    row: dict[str, object] = dict(
        metric=metric.name, kind="speed", before=before, after=now_median, change=change, low=math.nan,
        high=math.nan, confirmed=False, effects=_effects(change, minimum),
    )
    if len(medians) < thresholds.noise_runs:
        note = (
            f"not judged: {len(medians)} earlier run{'s' if len(medians) != 1 else ''} on this machine, "
            f"{thresholds.noise_runs} needed to estimate the noise"
        )
        return dict(row, verdict="unjudged", noise=math.nan, note=note)
    spread = speed_noise(medians.to_numpy(), thresholds.noise_multiple)
    noise = max(minimum, spread)
    verdict = _verdict(metric, change, True, noise)
    if not verdict:
        return None
    source = "the minimum effect" if noise == minimum else f"{thresholds.noise_multiple:g} x MAD"
    note = f"beyond {source} of {len(medians)} earlier runs on this machine; not yet repeated"
    return dict(row, verdict=verdict, noise=noise, effects=_effects(change, noise), note=note)


def judged_speed(changes: pd.DataFrame) -> pd.Series:
    """Which rows of :func:`find_changes`'s table are speed changes judged a regression or an improvement."""
    return changes["kind"].eq("speed") & changes["verdict"].isin(JUDGED)


def confirm_speed(changes: pd.DataFrame, repeat: pd.DataFrame) -> pd.DataFrame:
    """The changes with each speed change held against a repeat of its cells.

    Parameters
    ----------
    changes : pandas.DataFrame
        As :func:`find_changes` gives them.
    repeat : pandas.DataFrame
        The repeated cells' values: ``tracker``, ``dataset`` and a column
        per speed metric, a row per seed (cells that did not end ok left
        out).

    Returns
    -------
    pandas.DataFrame
        ``changes`` where each speed regression or improvement is
        ``confirmed`` when the repeat's median over seeds also differs from
        the earlier median (``before``) by at least the row's ``noise``, in
        the same direction; otherwise its verdict becomes ``unconfirmed``:
        reported, and neither a regression nor an improvement.  Its ``note``
        gives the repeat's median.  Regressions stay first.
    """
    changes = changes.copy()
    judged = judged_speed(changes)
    for index in changes.index[judged]:
        row = changes.loc[index]
        cells = repeat[(repeat["tracker"] == row["tracker"]) & (repeat["dataset"] == row["dataset"])]
        again = float(cells[row["metric"]].median()) if row["metric"] in cells and len(cells) else math.nan
        moved = again - float(row["before"])
        held = math.isfinite(again) and abs(moved) >= float(row["noise"]) and moved * float(row["change"]) > 0
        repeated = f"repeat {again:.6g}" if math.isfinite(again) else "the repeat gave no value"
        changes.loc[index, "confirmed"] = held
        changes.loc[index, "note"] = f"{repeated}: {'held' if held else 'within the noise, not held'}"
        if not held:
            changes.loc[index, "verdict"] = "unconfirmed"
    return _ordered(changes)


def _ordered(table: pd.DataFrame) -> pd.DataFrame:
    """Regressions first, then by tracker, dataset and metric."""
    order = table.assign(_regression=table["verdict"] != "regression")
    return order.sort_values(["_regression", "tracker", "dataset", "metric"]).drop(columns="_regression").reset_index(
        drop=True
    )


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
        (``speed`` for a metric of that kind, else ``accuracy``), ``verdict``
        (``regression`` or ``improvement``; for speed also ``unjudged``,
        a change beyond the minimum effect of a series without a noise
        estimate), ``cause`` (the tracker's version or parameters that
        changed, if any), ``noise`` (speed: the threshold the change passed,
        in the metric's units), ``confirmed`` (accuracy: true; speed: false
        until :func:`confirm_speed` holds it on a repeat), ``effects``
        (``|change|`` in minimum effects, or in ``noise`` for speed) and
        ``note`` (what a reader must know: for an RMSE, that the number of
        frames with an estimate changed with it, see :func:`_estimate_note`;
        for speed, how it was judged).  Only cells with status ``ok`` count.
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
                         noise=math.nan, confirmed=True, effects=_effects(change, minimum),
                         note=_estimate_note(metric, current, baseline))
                )
        same_machine = earlier[earlier["machine_key"] == machine]
        for metric in (m for m in judged if m.kind == "speed"):
            speed = _speed_change(metric, current, same_machine, thresholds)
            if speed is not None:
                rows.append(dict(shared, **speed))
    table = pd.DataFrame(rows, columns=CHANGE_COLUMNS).astype({"confirmed": bool})
    return _ordered(table)


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
