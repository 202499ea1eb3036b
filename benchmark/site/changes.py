"""Changes grouped by cause for the site's pages.

:func:`group_changes` folds the rows of
:func:`benchmark.history.regressions.find_changes` into one row per
verdict, kind (accuracy or speed), tracker and cause, regressions first,
accuracy before speed, the largest relative change first.
"""

from __future__ import annotations

import pandas as pd

from benchmark.metrics import CORE, Metrics
from benchmark.report.display import format_value

GROUP_COLUMNS = ["verdict", "kind", "tracker", "cause", "datasets", "metrics", "count", "largest", "headline", "rows"]


def _relative(changes: pd.DataFrame) -> pd.Series:
    """Each change's size as a share of its earlier value (the change itself where that was zero)."""
    before = changes["before"].astype(float).abs()
    return (changes["change"].astype(float).abs() / before.where(before > 0, 1.0)).fillna(0.0)


def group_changes(changes: pd.DataFrame, metrics: Metrics = CORE) -> pd.DataFrame:
    """One row per verdict, kind, tracker and cause of ``changes``, with the changes folded inside.

    Parameters
    ----------
    changes : pandas.DataFrame
        A table of :data:`benchmark.history.regressions.CHANGE_COLUMNS`.
    metrics : Metrics
        The catalogue that rounds the headline's value.

    Returns
    -------
    pandas.DataFrame
        Columns :data:`GROUP_COLUMNS`: ``datasets`` and ``metrics`` (lists in
        order of first appearance), ``count``, ``largest`` (the largest
        relative change), ``headline`` (``correct_pct -12.3 on camera/S1``)
        and ``rows`` (the group's changes, largest first).
    """
    groups = []
    sized = changes.assign(_size=_relative(changes)) if len(changes) else changes.assign(_size=[])
    for (verdict, kind, tracker, cause), rows in sized.groupby(["verdict", "kind", "tracker", "cause"], sort=False):
        rows = rows.sort_values("_size", ascending=False, kind="stable").reset_index(drop=True)
        top = rows.iloc[0]
        change = format_value(str(top["metric"]), float(top["change"]), metrics)
        groups.append(dict(
            verdict=verdict, kind=kind, tracker=tracker, cause=cause,
            datasets=list(dict.fromkeys(rows["dataset"])), metrics=list(dict.fromkeys(rows["metric"])),
            count=len(rows), largest=float(top["_size"]),
            headline=f"{top['metric']} {'+' if top['change'] > 0 else ''}{change} on {top['dataset']}",
            rows=rows.drop(columns="_size"),
        ))
    table = pd.DataFrame(groups, columns=GROUP_COLUMNS)
    order = table.assign(_speed=table["kind"] == "speed", _regression=table["verdict"] != "regression")
    return (
        order.sort_values(["_regression", "_speed", "largest"], ascending=[True, True, False], kind="stable")
        .drop(columns=["_speed", "_regression"])
        .reset_index(drop=True)
    )
