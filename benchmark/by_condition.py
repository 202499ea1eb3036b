"""Boards by condition: where each tracker fails, split by the conditions its sequences were made under.

A suite drawn from a wide world (:mod:`benchmark.scenes.draws`) records,
for each sequence, the conditions it was drawn under (water type, light,
polarity, altitude, ...) and what it measures of itself (a camera scene's
cable contrast): :meth:`benchmark.model.Sequence.conditions`.  A run keeps
them beside its cells (:meth:`benchmark.store.ResultStore.add_conditions`),
and :func:`condition_board` pools each tracker's frames per suite,
condition and *bin*:

* a condition whose values are words (a water type, a polarity) or lists
  (a frame size) has a bin per value;
* a numeric condition is binned by rank among the suite's sequences: the
  lowest tenth, the rest up to the median, the rest up to the highest
  tenth, and the highest tenth (each at least one sequence), labelled with
  the range of values it holds, so a board says "on the lowest-contrast
  tenth of camera-test" in so many words.

Rates pool every scored frame of every seed and sequence in a bin, as the
leaderboard's ``(all)`` rows do (:func:`benchmark.results.summarise`).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from numbers import Real
from typing import Any

import pandas as pd

from benchmark.leaderboard import key_labels, suite_of
from benchmark.metrics import RATES
from benchmark.results import summarise
from benchmark.scenes.draws import condition_label

RATE_COLUMNS = tuple(metric.name for metric in RATES)
COLUMNS = ("modality", "suite", "condition", "bin", "order", "tracker", "init", "sequences", "frames", *RATE_COLUMNS)
"""Columns of a board by condition, one row per tracker and bin."""

RANK_BINS = ("lowest tenth", "10-50 %", "50-90 %", "highest tenth")
"""Names of the bins of a numeric condition, lowest values first."""


def _numeric(values: list[Any]) -> bool:
    return all(isinstance(value, Real) and not isinstance(value, bool) for value in values)


def condition_bins(values: Mapping[str, Any]) -> dict[str, tuple[int, str]]:
    """Each dataset's bin of one condition: its order among the bins and its label.

    Parameters
    ----------
    values : Mapping
        Dataset key to the condition's value, for the sequences of one suite.

    Returns
    -------
    dict
        Dataset key to ``(order, label)``.  Words and lists: one bin per
        value, in order of first appearance among sorted labels.  Numbers:
        :data:`RANK_BINS` by rank (ties broken by dataset key), each label
        with the range of its values, e.g. ``"lowest tenth (14.2-19.8)"``.
    """
    if not values:
        return {}
    if not _numeric(list(values.values())):
        labels = sorted({condition_label(value) for value in values.values()})
        order = {label: position for position, label in enumerate(labels)}
        return {key: (order[condition_label(value)], condition_label(value)) for key, value in values.items()}
    ranked = sorted(values, key=lambda key: (float(values[key]), key))
    count = len(ranked)
    tenth = max(1, math.ceil(count / 10))
    middle = count // 2
    edges = [0, min(tenth, count), max(min(tenth, count), middle), max(min(tenth, count), middle, count - tenth), count]
    bins: dict[str, tuple[int, str]] = {}
    for position, name in enumerate(RANK_BINS):
        members = ranked[edges[position] : edges[position + 1]]
        if not members:
            continue
        low, high = (condition_label(float(values[key])) for key in (members[0], members[-1]))
        label = f"{name} ({low})" if low == high else f"{name} ({low}-{high})"
        bins.update({key: (position, label) for key in members})
    return bins


def condition_board(
    cells: pd.DataFrame, frames: pd.DataFrame, conditions: Mapping[str, Mapping[str, Any]]
) -> pd.DataFrame:
    """Correct, false and missed per cent of each tracker, per suite, condition and bin.

    Parameters
    ----------
    cells : pandas.DataFrame
        Cells as :meth:`benchmark.store.ResultStore.cells` returns them.
    frames : pandas.DataFrame
        Their frame scores (``cell_id``, ``outcome``, ...).
    conditions : Mapping
        Dataset key to its conditions by name
        (:meth:`benchmark.store.ResultStore.conditions`); datasets without
        conditions are left out.

    Returns
    -------
    pandas.DataFrame
        Columns :data:`COLUMNS`, sorted by modality, suite, the condition's
        first appearance, bin order and tracker; empty when no cell's dataset
        has conditions.
    """
    cells = cells[cells["dataset_key"].isin([key for key, found in conditions.items() if found])]
    if cells.empty:
        return pd.DataFrame(columns=list(COLUMNS))
    cells = cells.assign(label=key_labels(cells, "tracker", "tracker_key"), suite=cells["dataset"].map(suite_of))
    by_cell = {int(cell_id): group for cell_id, group in frames.groupby("cell_id", sort=False)}
    rows: list[dict[str, Any]] = []
    for (modality, suite), suite_cells in cells.groupby(["modality", "suite"], sort=True):
        keys = list(dict.fromkeys(suite_cells["dataset_key"]))
        names = list(dict.fromkeys(name for key in keys for name in conditions[key]))
        for name in names:
            bins = condition_bins({key: conditions[key][name] for key in keys if name in conditions[key]})
            binned = suite_cells[suite_cells["dataset_key"].isin(bins)]
            binned = binned.assign(
                order=binned["dataset_key"].map(lambda key: bins[key][0]),
                bin=binned["dataset_key"].map(lambda key: bins[key][1]),
            )
            for (order, label, tracker, init), group in binned.groupby(["order", "bin", "label", "init"], sort=True):
                parts = [by_cell[int(i)] for i in group["id"] if int(i) in by_cell]
                pooled = pd.concat(parts, ignore_index=True) if parts else frames.iloc[0:0]
                summary = summarise(pooled, RATES)
                rows.append(
                    {
                        "modality": modality,
                        "suite": suite,
                        "condition": name,
                        "bin": label,
                        "order": int(order),
                        "tracker": tracker,
                        "init": init,
                        "sequences": int(group["dataset_key"].nunique()),
                        "frames": int(summary["frames"]),
                        **{column: summary[column] for column in RATE_COLUMNS},
                    }
                )
    return pd.DataFrame(rows, columns=list(COLUMNS))


def condition_tables(board: pd.DataFrame, metric: str = "correct_pct") -> dict[tuple[str, str, str], pd.DataFrame]:
    """The board laid out for reading: one table per suite and condition, a row per tracker, a column per bin.

    Parameters
    ----------
    board : pandas.DataFrame
        As :func:`condition_board` returns it.
    metric : str
        The rate shown in the cells.

    Returns
    -------
    dict
        ``(modality, suite, condition)`` to a table whose first column is
        ``tracker`` (with `` (init none)`` added where a tracker also ran
        without ground-truth initialisation) and whose other columns are the
        bins, headed ``label, n sequences``; trackers in order of their mean
        over the bins, best first.
    """
    tables: dict[tuple[str, str, str], pd.DataFrame] = {}
    if board.empty:
        return tables
    board = board.assign(
        who=[tracker if init == "truth" else f"{tracker} (init {init})" for tracker, init in zip(board["tracker"], board["init"])]
    )
    for (modality, suite, condition), part in board.groupby(["modality", "suite", "condition"], sort=False):
        part = part.sort_values(["order", "bin"], kind="stable")
        counts = part.groupby("bin", sort=False)["sequences"].max()
        headers = {label: f"{label}, {int(count)} seq." for label, count in counts.items()}
        wide = part.pivot_table(index="who", columns="bin", values=metric, aggfunc="first", sort=False)
        wide = wide[[label for label in headers if label in wide.columns]]
        wide = wide.loc[wide.mean(axis=1).sort_values(ascending=False, kind="stable").index]
        wide.columns = [headers[label] for label in wide.columns]
        tables[(str(modality), str(suite), str(condition))] = wide.rename_axis("tracker").reset_index()
    return tables
