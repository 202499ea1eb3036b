"""Grid tables: one metric per tracker, laid out as case x condition.

Suites whose sequences are named ``suite/CASE-CONDITION`` (``stereo/case1-slow``)
vary two things at once.  The paper behind the stereo suite reports them as
one table per case, with a row per metric and method and a column per speed
(seeds/002, Tables 6-8); :func:`grid_tables` gives the same layout from a
leaderboard, so our figures can be set beside the paper's.
"""

from __future__ import annotations

from collections.abc import Sequence

import pandas as pd

from benchmark.leaderboard import is_pooled


def split_grid_name(dataset: str) -> tuple[str, str] | None:
    """``"stereo/case1-slow"`` to ``("case1", "slow")``; None for a name without a ``-``."""
    stem = dataset.rsplit("/", 1)[-1]
    case, sep, condition = stem.rpartition("-")
    return (case, condition) if sep and case and condition else None


def grid_tables(board: pd.DataFrame, metrics: Sequence[str], order: Sequence[str] = ()) -> dict[str, pd.DataFrame]:
    """Lay a leaderboard out as one table per case.

    Parameters
    ----------
    board : pandas.DataFrame
        A leaderboard (:func:`benchmark.leaderboard.modality_board`).
    metrics : sequence of str
        Board columns to show, e.g. ``rmse_position_m``; each gets one row
        per tracker, in this order.
    order : sequence of str
        Dataset names in the order their conditions should appear as
        columns (a suite's sequence order); other datasets follow by name.

    Returns
    -------
    dict
        Case name to a table whose index is ``"<metric> <tracker>"`` and
        whose columns are the conditions.

    References
    ----------
    seeds/002, Tables 6-8 (position, speed and heading RMSE of the EKF and
    of the raw measurements, per case and speed).
    """
    rank = {name: position for position, name in enumerate(order)}
    rows = board[~board["dataset"].map(is_pooled)].copy()
    parts = [split_grid_name(name) for name in rows["dataset"]]
    rows["case"] = [part[0] if part else None for part in parts]
    rows["condition"] = [part[1] if part else None for part in parts]
    rows = rows.dropna(subset=["case"])
    rows["_order"] = [rank.get(name, len(rank)) for name in rows["dataset"]]
    rows = rows.sort_values(["_order", "dataset"], kind="stable")
    conditions = list(dict.fromkeys(rows["condition"]))
    trackers = list(dict.fromkeys(board["tracker"]))
    tables = {}
    for case in dict.fromkeys(rows["case"]):
        part = rows[rows["case"] == case]
        index = [f"{metric} {tracker}" for metric in metrics for tracker in trackers]
        table = pd.DataFrame(index=index, columns=conditions, dtype=float)
        for _, row in part.iterrows():
            for metric in metrics:
                table.loc[f"{metric} {row['tracker']}", row["condition"]] = row[metric]
        tables[str(case)] = table.dropna(how="all")
    return tables


def grid_markdown(tables: dict[str, pd.DataFrame], title: str) -> str:
    """The tables as Markdown, values rounded to 0.01."""
    parts = [f"# {title}", ""]
    for case, table in tables.items():
        parts += [f"## {case}", "", table.to_markdown(floatfmt=".2f"), ""]
    return "\n".join(parts)
