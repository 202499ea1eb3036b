"""Boards as text: values rounded for reading, columns aligned by type.

Boards keep full precision (and CSV exports them so); the Markdown, HTML and
terminal forms round each metric to its declared digits
(:attr:`benchmark.metrics.Metric.digits`: percentages to 0.1, RMSEs to
0.01, frames per second to 1), and other columns by their unit (the tables of
``trackbench pose-table``: metres to 0.01, degrees to 0.1, pixels to 1,
variances to three digits).
"""

from __future__ import annotations

import math

import pandas as pd

from benchmark.metrics import CORE, Metrics
from benchmark.text import one_line, printable  # noqa: F401 - re-exported: code written against this module




def format_value(column: str, value: object, metrics: Metrics = CORE) -> str:
    """A value as shown: a metric's (or its interval's or spread's) to its digits; other columns by unit.

    Percentages and degrees to 0.1, metres to 0.01, pixels to 1, variances
    as e-03.
    """
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return ""
    metric = metrics.of_column(column)
    if metric is not None:
        return metric.format(value)
    if column.endswith("_pct"):
        return f"{value:.1f}"
    if column.endswith("_m"):
        return f"{value:.2f}"
    if column.startswith("var_"):
        return f"{value:.2e}"
    if column.endswith("_deg"):
        return f"{value:.1f}"
    if column.endswith("_px"):
        return f"{value:.0f}"
    return str(value)


def _with_interval(column: str, value: object, low: object, high: object, metrics: Metrics) -> str:
    """``value [low, high]``, or the value alone when the interval is unknown or a point."""
    shown = format_value(column, value, metrics)
    ends = format_value(column, low, metrics), format_value(column, high, metrics)
    if not shown or not all(ends) or ends[0] == ends[1]:
        return shown
    return f"{shown} [{ends[0]}, {ends[1]}]"


def _intervals(board: pd.DataFrame, metrics: Metrics) -> dict[str, tuple[str, str]]:
    """The metric columns of ``board`` that have both ends of an interval, to those ends."""
    ends = {column: metric.interval_columns for column in board.columns if (metric := metrics.named(str(column)))}
    return {column: pair for column, pair in ends.items() if set(pair) <= set(board.columns)}


def _shown_columns(board: pd.DataFrame, metrics: Metrics) -> list[str]:
    """The columns of ``board`` but the interval ends, which are shown beside their values."""
    hidden = {end for pair in _intervals(board, metrics).values() for end in pair}
    return [column for column in board.columns if column not in hidden]


NO_TRUTH = "no truth"
"""What a board shows in place of the detection rates of a row whose frames had no ground truth to score against."""


def without_truth(board: pd.DataFrame) -> pd.Series:
    """The rows of a board that ran cleanly on frames of which none had a truth: ``frames`` (scored) 0, status ``ok``."""
    if not {"frames", "status"} <= set(board.columns):
        return pd.Series(False, index=board.index)
    return (board["frames"] == 0) & (board["status"] == "ok")


def display_table(board: pd.DataFrame, metrics: Metrics = CORE) -> pd.DataFrame:
    """The board as rounded text, for Markdown, HTML and the terminal.

    A metric with an interval over seeds (columns ``*_lo_*`` and ``*_hi_*``,
    :attr:`benchmark.metrics.Metric.interval_columns`) is shown as
    ``value [low, high]`` in its own column, and ``deterministic`` as yes or no.
    A row without truth (:func:`without_truth`: a video, an image folder, a
    sequence file of ``nan`` rows) shows :data:`NO_TRUTH` where its
    detection rates would be, since nothing was scored; the board itself
    keeps them NaN.
    """
    ends = _intervals(board, metrics)
    shown = _shown_columns(board, metrics)
    unscored = without_truth(board).tolist()
    table = {}
    for column in shown:
        if column in ends:
            low, high = ends[column]
            table[column] = [
                _with_interval(column, *values, metrics)
                for values in zip(board[column], board[low], board[high], strict=True)
            ]
        elif column == "deterministic":
            table[column] = ["" if pd.isna(value) else ("yes" if value else "no") for value in board[column]]
        else:
            table[column] = [format_value(column, value, metrics) for value in board[column].tolist()]
        metric = metrics.named(str(column))
        if metric is not None and metric.kind == "detection":
            table[column] = [NO_TRUTH if none else text for text, none in zip(table[column], unscored, strict=True)]
    return pd.DataFrame(table, columns=shown, dtype=object)


def alignment(board: pd.DataFrame, metrics: Metrics = CORE) -> list[str]:
    """Per column of :func:`display_table`: ``"right"`` for numeric columns, ``"left"`` for the others."""
    return [
        "right" if pd.api.types.is_numeric_dtype(board[column]) else "left"
        for column in _shown_columns(board, metrics)
    ]
