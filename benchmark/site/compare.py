"""Two runs side by side: the site's compare page, and ``trackbench compare A B --html``'s page.

The site's ``compare.html`` lets the reader pick any two runs in the
browser: the page embeds, per run, tracker, dataset and metric, the mean
over seeds of the run's cells that ended ok (:func:`run_means`), and a
small script shows the differences of the two runs picked (also from the
address: ``compare.html#a=3&b=7``).  :func:`comparison_page` writes the
same comparison of two given runs as one self-contained page, with the
verdicts of :func:`~benchmark.history.regressions.find_changes` grouped
by cause on top.
"""

from __future__ import annotations

import json
import math
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import pandas as pd

from benchmark.errors import DataError
from benchmark.history.database import History
from benchmark.history.regressions import Thresholds, judged_metrics
from benchmark.metrics import Metrics
from benchmark.modality import Modality
from benchmark.report.display import format_value
from benchmark.site.pages import Drawn, Night, grouped_changes, render, run_label, signed


def run_means(cells: pd.DataFrame, metrics: Metrics) -> dict[str, Any]:
    """Per run, tracker, dataset and metric, the mean over seeds of the cells that ended ok, for the page's script.

    Returns
    -------
    dict
        ``metrics`` (names, in catalogue order), ``digits`` (decimals each
        is shown with), ``rows`` (``[tracker, dataset]`` pairs) and
        ``values``: run id (as text) to ``{row index: [value or None per metric]}``.
    """
    ok = cells[cells["status"] == "ok"]
    judged = [metric for metric in judged_metrics(ok, metrics) if ok[metric.name].notna().any()]
    names = [metric.name for metric in judged]
    means = ok.groupby(["run_id", "tracker", "dataset"], sort=True)[names].mean()
    pairs = sorted({(str(tracker), str(dataset)) for _, tracker, dataset in means.index})
    row_of = {pair: i for i, pair in enumerate(pairs)}
    values: dict[str, dict[int, list[float | None]]] = {}
    for (run_id, tracker, dataset), row in zip(means.index, means.to_numpy(dtype=float)):
        values.setdefault(str(int(run_id)), {})[row_of[(str(tracker), str(dataset))]] = [
            float(v) if math.isfinite(v) else None for v in row
        ]
    digits = [_digits(metric.name, metrics) for metric in judged]
    return {"metrics": names, "digits": digits, "lower": [m.lower_is_better for m in judged],
            "rows": [list(pair) for pair in pairs], "values": values}


def _digits(metric: str, metrics: Metrics) -> int:
    """The decimals a metric is shown with, read from how it formats a value."""
    shown = format_value(metric, 1.0, metrics)
    return len(shown.split(".")[1]) if "." in shown else 0


def compare_page(night: Night, key: None, site: Path) -> Drawn:
    """``compare.html``: pick two runs of the history and see every metric's difference."""
    runs = [dict(id=int(run["id"]), label=run_label(run)) for run in night.runs.to_dict("records")]
    data = run_means(night.cells, night.metrics)
    html = render(
        "compare.html", night, night.run.to_dict(), "", "compare runs \u00b7 trackbench nightly",
        runs=runs, data=json.dumps(data, separators=(",", ":")).replace("</", "<\\/"), datatables=False,
    )
    (site / "compare.html").write_text(html, encoding="utf-8")
    return Drawn(["compare.html"])


def _side_by_side(night: Night, run_a: int, run_b: int) -> list[dict[str, Any]]:
    """Every tracker, dataset and metric of either run: both means over seeds and the change, largest share first."""
    data = run_means(night.cells[night.cells["run_id"].isin([run_a, run_b])], night.metrics)
    a, b = data["values"].get(str(run_a), {}), data["values"].get(str(run_b), {})
    rows = []
    for index, (tracker, dataset) in enumerate(data["rows"]):
        for position, metric in enumerate(data["metrics"]):
            before = (a.get(index) or [None] * len(data["metrics"]))[position]
            after = (b.get(index) or [None] * len(data["metrics"]))[position]
            if before is None and after is None:
                continue
            change = after - before if before is not None and after is not None else None
            share = abs(change) / abs(before) if change is not None and before else 0.0
            rows.append(dict(
                tracker=tracker, dataset=dataset, metric=metric,
                before=format_value(metric, before, night.metrics), after=format_value(metric, after, night.metrics),
                change=signed(metric, change, night.metrics) if change is not None else "",
                share=f"{100 * share:+.1f} %" if change is not None and before else "", size=share,
            ))
    return sorted(rows, key=lambda row: -row["size"])


def comparison_page(night: Night, run_a: int, run_b: int, changes: pd.DataFrame) -> str:
    """A self-contained page comparing run ``run_a`` with ``run_b``: the verdicts grouped, then every metric.

    Parameters
    ----------
    night : Night
        The history's runs and cells (at least those of both runs).
    run_a, run_b : int
        The earlier and the later run.
    changes : pandas.DataFrame
        :func:`~benchmark.history.regressions.find_changes` of ``run_b``
        against ``run_a``.

    Returns
    -------
    str
        The HTML page: no script, style inline, no link to any other file.
    """
    cells = night.cells[night.cells["run_id"] == run_b]
    labels: Mapping[int, str] = {int(run["id"]): run_label(run) for run in night.runs.to_dict("records")}
    return render(
        "comparison.html", night, night.run_row(run_b).to_dict(), "", f"run {run_a} \u2192 {run_b}",
        run_a=labels[run_a], run_b=labels[run_b], changes=grouped_changes(night, changes, cells.iloc[0:0], ""),
        rows=_side_by_side(night, run_a, run_b), datatables=False, standalone=True,
    )


def write_comparison(
    path: Path,
    history: History,
    run_a: int,
    run_b: int,
    changes: pd.DataFrame,
    modalities: Mapping[str, Modality],
    thresholds: Thresholds,
    metrics: Metrics,
) -> Path:
    """Write :func:`comparison_page` of two runs of ``history`` to ``path`` and return it.

    Raises
    ------
    DataError
        If the page cannot be written, naming the file.
    """
    cells = history.cells([run_a, run_b])
    night = Night(history, modalities, metrics, thresholds, history.runs(), cells, {}, {})
    page = comparison_page(night, run_a, run_b, changes)
    try:
        path.write_text(page, encoding="utf-8")
    except OSError as exc:
        raise DataError(f"comparison page {path}: cannot write it: {exc.strerror or exc}") from None
    return path
