"""Figures of the site: a tracker's metrics over the history, and a cell's frames.

Figures are drawn on :class:`matplotlib.figure.Figure` objects rendered by
the Agg canvas, never through ``pyplot``, so that building the site leaves
no global state behind and needs no display.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from pathlib import Path

import numpy as np
import pandas as pd
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure
from matplotlib.patches import Patch
from matplotlib.ticker import FuncFormatter, MaxNLocator

from benchmark.history.regressions import Step
from benchmark.metrics import CORE, Metrics
from benchmark.report.display import format_value

OUTCOME_COLOURS = {
    "correct": "#2e7d32",
    "false": "#ef6c00",
    "missed": "#c62828",
    "unscored": "#cfd8dc",
}
"""Colour of each frame outcome in the outcome strip; ``unscored`` is a frame without truth."""

DPI = 96


def _save(figure: Figure, path: Path) -> Path:
    FigureCanvasAgg(figure)
    figure.savefig(path, dpi=DPI, facecolor="white")
    return path


def trend_figure(
    levels: Mapping[str, pd.DataFrame],
    runs: Sequence[str],
    found: Mapping[tuple[str, str], list[Step]],
    path: Path,
    metrics: Metrics = CORE,
) -> Path:
    """Draw one panel per metric of a tracker's levels over the runs, steps marked, and save it as PNG.

    Parameters
    ----------
    levels : Mapping
        Metric name to a table with one row per run position (``0`` is the
        oldest run of ``runs``) and one column per dataset: the metric's mean
        over seeds, NaN where the dataset did not run.
    runs : sequence of str
        The label of each run position on the x axis (its date).
    found : Mapping
        ``(metric, dataset)`` to the steps found in that series, whose
        ``run_id`` is a run position.
    path : pathlib.Path
        The PNG file to write.
    metrics : Metrics
        The catalogue that rounds each metric's values for the labels.

    Returns
    -------
    pathlib.Path
        ``path``.
    """
    shown = list(levels)
    datasets = sorted({str(column) for table in levels.values() for column in table.columns})
    colours = {name: f"C{i % 10}" for i, name in enumerate(datasets)}
    figure = Figure(figsize=(10, 2.4 * len(shown) + 0.6), layout="constrained")
    axes = figure.subplots(len(shown), 1, sharex=True, squeeze=False)[:, 0]
    for ax, metric in zip(axes, shown):
        table = levels[metric]
        marked: dict[int, int] = {}
        for dataset in table.columns:
            series = table[dataset]
            ax.plot(series.index, series.to_numpy(dtype=float), marker="o", markersize=3, linewidth=1.4,
                    color=colours[str(dataset)], label=str(dataset))
            for step in found.get((metric, str(dataset)), []):
                ax.axvline(step.run_id - 0.5, color=colours[str(dataset)], linestyle="--", linewidth=1)
                above = marked[step.run_id] = marked.get(step.run_id, 0) + 1
                ax.annotate(
                    f"{format_value(metric, step.before, metrics)} \u2192 {format_value(metric, step.after, metrics)}",
                    (step.run_id - 0.5, 1.0), xycoords=("data", "axes fraction"), xytext=(4, -11 * above),
                    textcoords="offset points", fontsize=8, color=colours[str(dataset)],
                    bbox={"boxstyle": "square,pad=0.1", "facecolor": "white", "edgecolor": "none", "alpha": 0.8},
                )
        ax.set_ylabel(metric)
        ax.grid(True, color="#e0e0e0", linewidth=0.6)
        ax.spines[["top", "right"]].set_visible(False)
    axes[-1].set_xlim(-0.5, max(len(runs) - 0.5, 0.5))
    axes[-1].xaxis.set_major_locator(MaxNLocator(nbins=12, integer=True))
    axes[-1].xaxis.set_major_formatter(
        FuncFormatter(lambda x, _: runs[int(x)] if float(x).is_integer() and 0 <= x < len(runs) else "")
    )
    axes[-1].set_xlabel("run")
    if datasets:
        handles, labels = axes[0].get_legend_handles_labels()
        figure.legend(handles, labels, loc="outside lower center", ncols=min(len(labels), 3), fontsize=8,
                      frameon=False)
    return _save(figure, path)


def _outcome_runs(frames: pd.DataFrame) -> dict[str, list[tuple[float, float]]]:
    """Frames grouped by outcome into ``(start, width)`` runs of consecutive frames, for ``broken_barh``."""
    spans: dict[str, list[tuple[float, float]]] = {outcome: [] for outcome in OUTCOME_COLOURS}
    index = frames["frame"].to_numpy(dtype=int)
    outcome = frames["outcome"].fillna("unscored").astype(str).to_numpy()
    start = 0
    for i in range(1, len(index) + 1):
        if i == len(index) or outcome[i] != outcome[start] or index[i] != index[i - 1] + 1:
            spans.setdefault(outcome[start], []).append((index[start] - 0.5, float(index[i - 1] - index[start] + 1)))
            start = i
    return spans


def cell_figure(frames: pd.DataFrame, errors: Sequence[str], path: Path) -> Path:
    """Draw a cell's outcome strip over the error of each state variable against the frame, and save it as PNG.

    Parameters
    ----------
    frames : pandas.DataFrame
        The cell's frame table: ``frame``, ``outcome`` (None when unscored)
        and the error columns.
    errors : sequence of str
        The error columns to draw, one panel each, under the strip.
    path : pathlib.Path
        The PNG file to write.

    Returns
    -------
    pathlib.Path
        ``path``.
    """
    figure = Figure(figsize=(10, 0.9 + 1.5 * len(errors) + 0.5), layout="constrained")
    axes = figure.subplots(
        1 + len(errors), 1, sharex=True, squeeze=False, gridspec_kw={"height_ratios": [0.45] + [1.0] * len(errors)}
    )[:, 0]
    strip = axes[0]
    spans = _outcome_runs(frames)
    counts = frames["outcome"].fillna("unscored").value_counts()
    for outcome, colour in OUTCOME_COLOURS.items():
        if spans.get(outcome):
            strip.broken_barh(spans[outcome], (0, 1), facecolors=colour)
    strip.set_yticks([])
    strip.set_ylim(0, 1)
    strip.legend(
        handles=[Patch(color=colour, label=f"{outcome} ({counts.get(outcome, 0)})")
                 for outcome, colour in OUTCOME_COLOURS.items() if counts.get(outcome, 0)],
        loc="lower left", bbox_to_anchor=(0.0, 1.02), ncols=4, fontsize=9, frameon=False, borderaxespad=0.0,
    )
    for ax, column in zip(axes[1:], errors):
        values = frames[column].to_numpy(dtype=float)
        ax.axhline(0.0, color="#9e9e9e", linewidth=0.8)
        ax.plot(frames["frame"], np.where(np.isfinite(values), values, np.nan), marker="o", markersize=2.5,
                linewidth=1.0, color="#1565c0")
        ax.set_ylabel(column, fontsize=9)
        ax.grid(True, color="#e0e0e0", linewidth=0.6)
        ax.spines[["top", "right"]].set_visible(False)
    if len(frames):
        axes[-1].set_xlim(frames["frame"].min() - 0.5, frames["frame"].max() + 0.5)
    axes[-1].xaxis.set_major_locator(MaxNLocator(integer=True))
    axes[-1].set_xlabel("frame")
    return _save(figure, path)
