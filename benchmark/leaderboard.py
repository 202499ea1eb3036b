"""Leaderboards: cells pooled per tracker and dataset, ranked per modality.

A leaderboard row pools every scored frame of every seed a tracker ran on a
dataset, and has a column per metric of its board (:mod:`benchmark.metrics`),
computed from the pooled frames (:func:`benchmark.results.summarise`): rates
are percentages of all those frames (so seeds weigh by their frame counts),
each RMSE is the square root of the mean squared error over all frames with
an estimate and a truth, ``cpu_fps`` (``wall_fps``) is all frames over all
``step`` CPU (wall) time, and
the robustness metrics count failures over all frames.  A metric with a
spread (``correct_pct``) has the sample standard deviation of its per-seed
values (``correct_sd_pct``, empty for a single seed), so that a stochastic
tracker's mean is read with its variation.  A metric with an interval also
has its 95 % interval (``correct_lo_pct`` to ``correct_hi_pct``), a bootstrap
over seeds (:mod:`benchmark.intervals`), and ``deterministic`` says
whether all seeds gave the same frames *and* the tracker declares that it
draws no random numbers (empty for a single seed): seeds that agree are not
enough, since a tracker seeded from anything but its generator (the clock,
the process) agrees with itself within a run and not with the next one.  A row with dataset
``(all)`` pools each tracker over every dataset of the board and comes
first.  Where a board holds several suites (a thesis suite, a dev and a
test split), a row ``SUITE (all)`` pools each tracker over the datasets of
one suite (the part of a dataset's name before its ``/``) and comes next,
so a split is never read through another's numbers.  A tracker name that ran with several
parameter sets, or a dataset name that stood for several datasets (a file
edited between runs), gets a row per key, labelled ``name [key prefix]``.

Within each dataset trackers are ranked by the metrics that rank
(:attr:`benchmark.metrics.Metric.ranks`): ``correct_pct`` (higher first),
then the first RMSE column (``rmse_d_px`` for cameras, lower first), the
order of seeds/004, Table V followed by the accuracy of seeds/000,
section 5.2.3.  ``training`` names the training set of a tracker that
learns (:mod:`benchmark.training`), empty for the others.  Rows whose cells failed (status other than ``ok``) rank
after every row that ran cleanly, since their rates cover only the frames
before the failure.

There is one board per modality, as the modalities score different things,
and one per modality and suite of closed-loop cells (:mod:`benchmark.closedloop`),
named ``MODALITY: SUITE, closed loop``: a closed-loop cell's frames depend
on its tracker, so its rows are not read against open-loop ones.  A dataset
is closed-loop when any of its cells' frames holds the vehicle's values (the
``loop_*`` columns, :class:`benchmark.results.LoopValues`); a closed-loop
board's columns put the following metrics first
(:data:`benchmark.metrics.CLOSED_LOOP_KINDS`), then the open-loop metrics of
the frames the vehicle saw, and rank by the distance followed, then the mean
offset, before the correct rate.  Closed-loop cells run in real time
(:mod:`benchmark.closedloop.real_time`) have a board of their own, the name
ending in ``, real time``, so that a run that saw every frame is never
ranked or pooled with one that skipped frames.  Its ``real_time`` column says
where each row's step time came from (``declared 17 ms``, or ``measured
median, this machine``: a figure of the machine that ran it); a tracker run
under several sources gets a row per source, labelled ``name (source)``.
Numeric column names carry their units (``conventions.md`` section 4).
Boards keep full precision; :mod:`benchmark.report` writes them out.
"""

from __future__ import annotations

import math
import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

import pandas as pd

from benchmark.intervals import seed_intervals
from benchmark.metrics import CLOSED_LOOP_KINDS, CORE, KINDS, Kind, Metric, Metrics, columns_with_values
from benchmark.modality import Modality
from benchmark.results import LOOP_PREFIX, summarise

if TYPE_CHECKING:
    from benchmark.store import ResultStore

ALL_DATASETS = "(all)"
"""Dataset name of the row that pools a tracker over all datasets of a board."""

SUITE_POOL = " (all)"
"""Ending of the dataset name of a row that pools a tracker over one suite: ``camera-test (all)``."""


def suite_of(dataset: str) -> str:
    """The suite a dataset name belongs to: ``camera-test/t01`` -> ``camera-test``; a path is its own suite."""
    suite, slash, _ = dataset.partition("/")
    return suite if slash and suite else dataset


def is_pooled(dataset: str) -> bool:
    """Whether a board's dataset name is a pooled row: ``(all)`` or ``SUITE (all)``."""
    return dataset == ALL_DATASETS or dataset.endswith(SUITE_POOL)

LEADING_COLUMNS = ("rank", "tracker", "dataset", "init", "training", "seeds", "frames")

REAL_TIME_COLUMN = "real_time"
"""Column of a real-time board, after ``init``: the source of each row's step time."""

REAL_TIME_BOARD = ", real time"
"""Ending of the name of a board of cells run in real time: ``camera: routes, closed loop, real time``."""


def board_modality(board_name: str) -> str:
    """The modality a board of :func:`leaderboards` ranks: its name up to the first colon."""
    return board_name.partition(":")[0]


@dataclass(frozen=True)
class BoardLayout:
    """How a kind of board is named and in which order of metric kinds its columns stand.

    Attributes
    ----------
    title : str
        The board's name, formatted with its cells' ``modality`` and ``suite``.
    kinds : tuple of str
        The kinds of metric in board order (:meth:`benchmark.metrics.Metrics.for_board`).
    """

    title: str
    kinds: tuple[Kind, ...]

    def name(self, modality: str, suite: str) -> str:
        """The board's name for cells of ``modality`` and ``suite``."""
        return self.title.format(modality=modality, suite=suite)


LAYOUTS: dict[bool, BoardLayout] = {
    False: BoardLayout("{modality}", KINDS),
    True: BoardLayout("{modality}: {suite}, closed loop", CLOSED_LOOP_KINDS),
}
"""The layout of an open-loop board (one per modality) and of a closed-loop one (one per suite), by closed loop."""


def closed_loop_datasets(cells: pd.DataFrame, frames: pd.DataFrame) -> frozenset[str]:
    """The dataset keys of ``cells`` of which any cell's frames hold a ``loop_*`` value: the closed-loop datasets."""
    loop_columns = [column for column in frames.columns if str(column).startswith(LOOP_PREFIX)]
    if not loop_columns or "cell_id" not in frames.columns:
        return frozenset()
    with_values = frames.loc[frames[loop_columns].notna().any(axis=1), "cell_id"].unique()
    return frozenset(cells.loc[cells["id"].isin(with_values), "dataset_key"].astype(str))


def real_time_sources(cells: pd.DataFrame) -> pd.Series:
    """Each cell's source of step time (:data:`REAL_TIME_COLUMN`), ``""`` for a cell not run in real time."""
    if REAL_TIME_COLUMN not in cells:
        return pd.Series("", index=cells.index)
    return cells[REAL_TIME_COLUMN].fillna("").astype(str)


def board_layouts(cells: pd.DataFrame, frames: pd.DataFrame) -> pd.DataFrame:
    """Each cell's board: ``board`` (its name) and ``closed_loop``, in the order of ``cells``."""
    closed = cells["dataset_key"].astype(str).isin(closed_loop_datasets(cells, frames))
    real_time = real_time_sources(cells) != ""
    names = [
        LAYOUTS[bool(loop)].name(str(modality), suite_of(str(dataset))) + (REAL_TIME_BOARD if timed else "")
        for modality, dataset, loop, timed in zip(cells["modality"], cells["dataset"], closed, real_time, strict=True)
    ]
    return pd.DataFrame({"board": names, "closed_loop": closed.to_numpy()}, index=cells.index)


def error_columns(modality: Modality | None, frames: pd.DataFrame) -> tuple[str, ...]:
    """The error columns of a modality; those found in ``frames`` for a modality not registered here."""
    if modality is not None:
        return modality.error_columns
    return tuple(column for column in frames.columns if str(column).startswith("err_"))


def board_metrics(
    metrics: Metrics,
    modality_name: str,
    modality: Modality | None,
    frames: pd.DataFrame,
    kinds: Sequence[Kind] = KINDS,
) -> tuple[Metric, ...]:
    """The metrics of the board of a modality (registered or not: :func:`error_columns`), in board order.

    A metric that requires frame columns none of ``frames`` fills (the
    closed-loop metrics on open-loop frames) is not on the board
    (:attr:`benchmark.metrics.Metric.requires`).  ``kinds`` orders them
    (:attr:`BoardLayout.kinds`).
    """
    return metrics.for_board(modality_name, error_columns(modality, frames), columns_with_values(frames), kinds)


def board_columns(metrics: Sequence[Metric]) -> list[str]:
    """Columns of a board of ``metrics``: each kind's metrics then their spreads, ``deterministic``, intervals.

    Kinds stand in the order of ``metrics`` (board order).
    """
    kinds = list(dict.fromkeys(metric.kind for metric in metrics))
    values = [
        column
        for kind in kinds
        for column in [
            *(m.name for m in metrics if m.kind == kind),
            *(m.spread_column for m in metrics if m.kind == kind and m.spread),
        ]
    ]
    intervals = [column for metric in metrics if metric.interval for column in metric.interval_columns]
    return [*LEADING_COLUMNS, *values, "deterministic", *intervals, "status"]


def pooled_status(cells: pd.DataFrame) -> str:
    """``ok``, or how many cells failed and the first failure's message.

    Returns ``"error (k/n cells): message"``, or ``"timeout (k/n cells): ..."``
    when every failed cell timed out.
    """
    failed = cells[cells["status"] != "ok"].sort_values("id")
    if failed.empty:
        return "ok"
    kind = "timeout" if (failed["status"] == "timeout").all() else "error"
    first = failed[failed["status"] == kind].iloc[0]
    return f"{kind} ({len(failed)}/{len(cells)} cells): {first['message']}"


_FAILED_STATUS = re.compile(r"(?:error|timeout) \((\d+)/\d+ cells\)")


def failed_cells(status: str) -> int:
    """How many cells a board row's status (:func:`pooled_status`) counts as failed: 0 for ``ok``."""
    found = _FAILED_STATUS.match(str(status))
    return int(found.group(1)) if found else 0


def key_labels(cells: pd.DataFrame, name: str, key: str) -> pd.Series:
    """The ``name`` column, with the start of ``key`` added where one name has several keys.

    A tracker name run with several parameter sets, or a dataset name
    standing for several datasets (a file edited between runs), is shown
    once per key.
    """
    keys_per_name = cells.groupby(name)[key].transform("nunique")
    short_keys = cells[key].astype(str).str.slice(0, 8)
    return cells[name].where(keys_per_name <= 1, cells[name] + " [" + short_keys + "]")


def _rank(board: pd.DataFrame, metrics: Sequence[Metric]) -> pd.DataFrame:
    ranking = [metric for metric in metrics if metric.ranks]
    keys = {
        f"_by_{metric.name}": (board[metric.name] if metric.lower_is_better else -board[metric.name]).fillna(math.inf)
        for metric in ranking
    }
    ordered = board.assign(
        _failed=board["status"] != "ok",
        _all=[0 if name == ALL_DATASETS else 1 if is_pooled(name) else 2 for name in board["dataset"]],
        **keys,
    )
    ordered = ordered.sort_values(["_all", "dataset", "init", "_failed", *keys, "tracker"], kind="stable")
    ordered["rank"] = ordered.groupby(["dataset", "init"]).cumcount() + 1
    return ordered.drop(columns=["_failed", "_all", *keys]).reset_index(drop=True)


def modality_board(cells: pd.DataFrame, frames: pd.DataFrame, metrics: Sequence[Metric]) -> pd.DataFrame:
    """The ranked board of one modality.

    Parameters
    ----------
    cells : pandas.DataFrame
        Cells of one modality, with at least ``id``, ``tracker``,
        ``tracker_key``, ``dataset``, ``dataset_key``, ``seed``, ``init``,
        ``status`` and ``message`` (as :meth:`benchmark.store.ResultStore.cells`
        returns).
    frames : pandas.DataFrame
        Their frame scores: ``cell_id``, ``outcome``, the error columns and
        ``step_ms`` and ``wall_ms`` (as :meth:`benchmark.store.ResultStore.frame_tables`).
    metrics : sequence of Metric
        The board's metrics, in board order (:meth:`benchmark.metrics.Metrics.for_board`).

    Returns
    -------
    pandas.DataFrame
        Columns :func:`board_columns`; ``(all)`` rows first, then the
        ``SUITE (all)`` rows of a board of several suites (for suites of more
        than one dataset), then each dataset's rows in rank order.

    References
    ----------
    seeds/004, section VI-C and Table V (rates); seeds/000, sections 5.2.3
    and 5.2.5 (state errors and speed).
    """
    columns = board_columns(metrics)
    if cells.empty:
        return pd.DataFrame(columns=columns)
    if "cell_id" not in frames.columns:
        frames = pd.DataFrame(columns=["cell_id", "frame", "outcome", "step_ms", "wall_ms"])
    cells = cells.assign(
        label=key_labels(cells, "tracker", "tracker_key"), dataset=key_labels(cells, "dataset", "dataset_key")
    )
    # Frames are pooled in this order, not in the order cells finished: sums and the seeds' agreement are then
    # the same whatever the executor did.
    order = [column for column in ("label", "dataset", "init", "seed", "tracker_key", "dataset_key", "id") if column in cells]
    cells = cells.sort_values(order, kind="stable")
    by_cell = {int(cell_id): group for cell_id, group in frames.groupby("cell_id", sort=False)}
    empty = frames.iloc[0:0]

    def pool(group: pd.DataFrame) -> pd.DataFrame:
        parts = [by_cell[int(i)] for i in group["id"] if int(i) in by_cell]
        return pd.concat(parts, ignore_index=True) if parts else empty

    def row(group: pd.DataFrame, label: str, dataset: str, init: str) -> dict[str, object]:
        summary = summarise(pool(group), metrics)
        summary["frames"] = int(summary["frames"])
        seeds = [pool(cells_of_seed) for _, cells_of_seed in group.groupby("seed")]
        spreads = {
            metric.spread_column: pd.Series([metric.of(table) for table in seeds], dtype=float).std(ddof=1)
            for metric in metrics
            if metric.spread
        }
        intervals, seeds_agree = seed_intervals(seeds, metrics)
        declared = bool(group["deterministic"].all()) if "deterministic" in group else False
        deterministic = seeds_agree and declared if seeds_agree is not None else None
        return {
            "tracker": label,
            "dataset": dataset,
            "init": init,
            "training": ", ".join(sorted(set(group.get("training", pd.Series(dtype=str)).fillna("")) - {""})),
            "seeds": int(group["seed"].nunique()),
            **summary,
            **spreads,
            "deterministic": deterministic,
            **{column: end for metric in metrics if metric.interval
               for column, end in zip(metric.interval_columns, intervals[metric.name])},
            "status": pooled_status(group),
        }

    rows = [
        row(group, label, ALL_DATASETS, init)
        for (label, init), group in cells.groupby(["label", "init"], sort=True)
    ]
    suites = cells["dataset"].map(suite_of)
    if suites.nunique() > 1:
        rows += [
            row(group, label, f"{suite}{SUITE_POOL}", init)
            for (suite, label, init), group in cells.assign(suite=suites).groupby(["suite", "label", "init"], sort=True)
            if group["dataset"].nunique() > 1
        ]
    rows += [
        row(group, label, dataset, init)
        for (label, dataset, init), group in cells.groupby(["label", "dataset", "init"], sort=True)
    ]
    board = pd.DataFrame(rows).reindex(columns=columns)
    ranked = _rank(board, metrics)
    return ranked.astype({"rank": "int64", "seeds": "int64", "frames": "int64"})[columns]


def leaderboards(
    cells: pd.DataFrame, frames: pd.DataFrame, modalities: Mapping[str, Modality], metrics: Metrics = CORE
) -> dict[str, pd.DataFrame]:
    """One ranked board per modality present in ``cells``.

    Parameters
    ----------
    cells, frames : pandas.DataFrame
        As for :func:`modality_board`, any mix of modalities.
    modalities : Mapping
        The registered modalities by name, whose scorers give each board its
        error columns; a modality of ``cells`` not among them (its plugin
        since removed) takes the error columns its frames have.
    metrics : Metrics
        The catalogue of metrics (the registry's, with those plugins added).

    Returns
    -------
    dict
        Board name to board: the open-loop boards by modality name, then
        the closed-loop boards (``MODALITY: SUITE, closed loop``, :data:`LAYOUTS`),
        each in alphabetical order.
    """
    boards: dict[str, pd.DataFrame] = {}
    if cells.empty:
        return boards
    sources = real_time_sources(cells)
    grouped = cells.join(board_layouts(cells, frames)).groupby(["closed_loop", "board", "modality"], sort=True)
    for (closed_loop, name, modality), group in grouped:
        group = group.drop(columns=["board", "closed_loop"])
        timed = bool((sources[group.index] != "").any())
        if timed:
            group = group.assign(tracker=_source_labels(group["tracker"], sources[group.index]))
        part = frames[frames["cell_id"].isin(group["id"])] if "cell_id" in frames.columns else frames
        of_board = board_metrics(
            metrics, str(modality), modalities.get(str(modality)), part, LAYOUTS[bool(closed_loop)].kinds
        )
        board = modality_board(group, part, of_board)
        boards[str(name)] = _with_sources(board, group, sources[group.index]) if timed else board
    return boards


def _source_labels(trackers: pd.Series, sources: pd.Series) -> pd.Series:
    """The tracker names, each followed by ``(source)`` where one name ran under several step-time sources."""
    several = sources.groupby(trackers).transform("nunique") > 1
    return trackers.where(~several, trackers + " (" + sources + ")")


def _with_sources(board: pd.DataFrame, cells: pd.DataFrame, sources: pd.Series) -> pd.DataFrame:
    """``board`` of real-time cells with the :data:`REAL_TIME_COLUMN` after ``init``: each row's step-time sources."""
    labels = key_labels(cells, "tracker", "tracker_key")
    by_label = sources.groupby(labels).agg(lambda values: ", ".join(sorted(set(values))))
    at = board.columns.get_loc("init") + 1
    return board.assign(**{REAL_TIME_COLUMN: board["tracker"].map(by_label)})[
        [*board.columns[:at], REAL_TIME_COLUMN, *board.columns[at:]]
    ]


def load_leaderboards(
    store: ResultStore,
    modalities: Mapping[str, Modality],
    run_id: int | None = None,
    *,
    all_runs: bool = False,
    metrics: Metrics = CORE,
) -> dict[str, pd.DataFrame]:
    """The boards of a run stored in ``store`` (default: its latest run).

    With ``all_runs`` the boards take, for each tracker key, dataset key,
    seed and initialisation, the latest cell of any run.
    """
    cells = store.cells(run_id, all_runs=all_runs)
    return leaderboards(cells, store.frame_tables(cells["id"]), modalities, metrics)
