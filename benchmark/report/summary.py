"""A run's boards summed up for a terminal: one row per tracker and board, as wide as the terminal.

A full board has a row for every tracker and dataset and a column for every
metric, interval and spread: hundreds of lines by hundreds of columns for
the default suite.  ``trackbench run`` and ``nightly`` print this summary
instead and name the files that hold the full boards (``trackbench
leaderboard`` and ``tables`` still print those).

Each board (modality) shows the rows that pool a tracker over every dataset
(:data:`benchmark.leaderboard.ALL_DATASETS`), in rank order, with the
columns the metrics catalogue marks as headlines (the correct rate, the
ranking RMSE, the speeds, ...), every speed metric among them, and the
number of cells that did not end ``ok``.  Columns are read from the
catalogue, never named here, so a metric a plugin adds, or a renamed one,
shows up by itself.  Columns that do not fit the width are left out from
the right, the less important first; a long tracker name is shortened.
"""

from __future__ import annotations

import shutil
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import TYPE_CHECKING

from benchmark.leaderboard import ALL_DATASETS, REAL_TIME_COLUMN, board_modality, failed_cells, is_pooled
from benchmark.metrics import CORE, Metric, Metrics, error_columns_of
from benchmark.report.display import format_value
from benchmark.text import counted, one_line, printable, shortened

if TYPE_CHECKING:
    import pandas as pd

FALLBACK_WIDTH = 80
"""Columns assumed when the output is not a terminal."""
FAILED_COLUMN = "failed_cells"
"""The column counting the cells that did not end ``ok``, as ``failed/all``."""
GAP = "  "
MIN_NAME_WIDTH = 12
"""Tracker names are shortened to no less than this many characters to make room for metrics."""


def terminal_width() -> int:
    """The terminal's width in columns (``$COLUMNS`` first), or :data:`FALLBACK_WIDTH` when there is none."""
    return shutil.get_terminal_size((FALLBACK_WIDTH, 24)).columns


def summary_metrics(board: pd.DataFrame, modality: str, metrics: Metrics = CORE) -> list[Metric]:
    """The metrics a summary row of ``board`` shows: the catalogue's headline metrics and every speed metric.

    In the board's order of columns (a closed-loop board's following
    metrics first), except that the ranking metrics come first, then the
    speeds, then the rest (left out first when the terminal is narrow).
    """
    shown = [
        metric
        for metric in metrics.for_board(modality, error_columns_of(board.columns))
        if (metric.headline or metric.kind == "speed") and metric.name in board.columns
    ]
    columns = list(board.columns)
    return sorted(
        shown, key=lambda metric: (0 if metric.ranks else 1 if metric.kind == "speed" else 2, columns.index(metric.name))
    )


def _fitting(widths: Sequence[int], first: int, width: int) -> int:
    """How many of the columns of ``widths``, taken in order, fit beside a first column ``first`` wide."""
    used = first
    for kept, column_width in enumerate(widths):
        used += len(GAP) + column_width
        if used > width:
            return kept
    return len(widths)


def board_summary(board: pd.DataFrame, modality: str, width: int, metrics: Metrics = CORE) -> list[str]:
    """The lines of one board's summary: a title, a header and one row per tracker, at most ``width`` wide."""
    pooled = board[board["dataset"] == ALL_DATASETS]
    single = board[~board["dataset"].map(is_pooled)]
    datasets = single["dataset"].nunique()
    cells_of = single.groupby(["tracker", "init"])["seeds"].sum()
    names = [printable(name) for name in pooled["tracker"]]
    if pooled["init"].nunique() > 1:
        names = [f"{name} (init {init})" for name, init in zip(names, pooled["init"])]

    def shown(metric: Metric) -> tuple[str, list[str]]:
        return metric.name, [format_value(metric.name, value, metrics) for value in pooled[metric.name]]

    chosen = summary_metrics(board, board_modality(modality), metrics)
    first = [metric for metric in chosen if metric.ranks or metric.kind == "speed"]
    failed = [
        f"{failed_cells(status)}/{cells_of.get((tracker, init), 0)}"
        for tracker, init, status in zip(pooled["tracker"], pooled["init"], pooled["status"])
    ]
    columns = [
        *map(shown, first),
        (FAILED_COLUMN, failed),
        *(shown(metric) for metric in chosen if metric not in first),
    ]
    widths = [max(len(title), *(len(value) for value in values)) for title, values in columns]
    longest = max(len("tracker"), *(len(name) for name in names))
    kept = _fitting(widths, longest, width)
    if kept <= len(first):  # shorten the names rather than leave out a ranking metric, a speed or the failures
        kept = _fitting(widths, min(longest, MIN_NAME_WIDTH), width)
    name_width = max(1, min(longest, width - sum(len(GAP) + w for w in widths[:kept])))
    title = f"{modality}: {counted(len(names), 'tracker')} over {counted(datasets, 'dataset')}"
    if REAL_TIME_COLUMN in board:  # a real-time board says where its step times came from
        title += "; step time " + "; ".join(sorted(set(pooled[REAL_TIME_COLUMN].dropna())))
    lines = [
        shortened(title, width),
        "tracker".ljust(name_width)
        + "".join(GAP + title.rjust(w) for (title, _), w in zip(columns[:kept], widths[:kept])),
    ]
    for i, name in enumerate(names):
        row = "".join(GAP + values[i].rjust(w) for (_, values), w in zip(columns[:kept], widths[:kept]))
        lines.append((shortened(name, name_width).ljust(name_width) + row).rstrip())
    if kept < len(columns):
        lines.append(shortened(f"(too narrow for {', '.join(title for title, _ in columns[kept:])})", width))
    return lines


def summary_text(
    boards: Mapping[str, pd.DataFrame],
    files: Sequence[Path] = (),
    problems: Sequence[str] = (),
    metrics: Metrics = CORE,
    width: int | None = None,
) -> str:
    """Every board's summary (:func:`board_summary`), the problems one line each, and where the full boards are.

    Parameters
    ----------
    boards : Mapping
        Modality to ranked board (:func:`benchmark.leaderboard.leaderboards`).
    files : sequence of pathlib.Path
        The files the full boards were written to, named one a line.
    problems : sequence of str
        What went wrong outside any cell, each shortened to the width.
    metrics : Metrics
        The catalogue naming the headline and speed metrics.
    width : int, optional
        Columns to fit; by default the terminal's (:func:`terminal_width`).
    """
    width = max(width or terminal_width(), 20)
    blocks = ["\n".join(board_summary(board, modality, width, metrics)) for modality, board in boards.items()]
    if not boards:
        blocks.append("No results.")
    if problems:
        blocks.append("\n".join(["Problems", *(shortened(f"- {one_line(problem)}", width) for problem in problems)]))
    if files:
        named = [f"  {printable(path)}" for path in files]
        blocks.append("\n".join(["Full boards (trackbench leaderboard prints them):", *named]))
    return "\n\n".join(blocks)
