"""Figures of the site as plotly figures: a tracker's metrics over the runs, a cell's frames, a closed-loop run's path.

Both are interactive (hover names each point's run or frame and value;
drag zooms, double click resets), because both are read point by point:
which run moved a level, which frames a tracker lost.  A figure is a
plotly JSON specification drawn in the browser by ``assets/plotly.js``,
the plotly.js bundle written once per site (:func:`write_plotly`) and
loaded by a classic ``<script src>``, so pages work from ``file://``
offline.  Drawing a cell's figure this way takes milliseconds, where the
matplotlib PNG it replaces took about 0.2 s per cell page.

Specifications are plain dictionaries, not :class:`plotly.graph_objects.Figure`
objects: the site writes hundreds of them and needs no validation of its
own literal layout; :func:`figure_json` serialises them (NaN as ``null``,
a gap in a line).
"""

from __future__ import annotations

import json
import math
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

import pandas as pd
from markupsafe import Markup

from benchmark.history.regressions import Step
from benchmark.metrics import CORE, Metrics
from benchmark.report.display import format_value

if TYPE_CHECKING:
    from benchmark.closedloop.topview import TopView

OUTCOME_COLOURS = {
    "correct": "#2e7d32",
    "false": "#ef6c00",
    "missed": "#c62828",
    "unscored": "#cfd8dc",
}
"""Colour of each frame outcome in the outcome strip; ``unscored`` is a frame without truth."""

PLOTLY_ASSET = "assets/plotly.js"
"""Where the plotly.js bundle is written, relative to the site's root."""

PALETTE = ("#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22",
           "#17becf")
"""One colour per dataset of a trend, in turn."""

_CONFIG = {"displaylogo": False, "responsive": True, "modeBarButtonsToRemove": ["select2d", "lasso2d"]}
_FONT = {"family": "system-ui, sans-serif", "size": 12}

Figure = dict[str, Any]
"""A plotly figure specification: ``data`` (traces) and ``layout``."""


def write_plotly(site: Path) -> Path:
    """Write the plotly.js bundle as :data:`PLOTLY_ASSET` under ``site`` and return its path."""
    from plotly.offline import get_plotlyjs

    path = site / PLOTLY_ASSET
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(get_plotlyjs(), encoding="utf-8")
    return path


def _finite(values: Sequence[float] | pd.Series) -> list[float | None]:
    return [float(v) if v is not None and math.isfinite(float(v)) else None for v in values]


def figure_json(figure: Figure) -> str:
    """``figure`` as JSON for a page's script: NaN as ``null``, and ``</`` escaped so it cannot end the script."""
    return json.dumps(figure, separators=(",", ":"), allow_nan=False).replace("</", "<\\/")


def plot(figure: Figure, height: int, element_id: str) -> Markup:
    """The HTML of a figure: a ``div`` and the script that draws ``figure`` into it with plotly.js."""
    return Markup(
        '<div class="plot" id="{id}" style="height: {height}px"></div>\n'
        '<script>(function () {{ const figure = {spec}; '
        'Plotly.newPlot("{id}", figure.data, figure.layout, {config}); }})();</script>'
    ).format(id=element_id, height=height, spec=Markup(figure_json(figure)), config=Markup(json.dumps(_CONFIG)))


def trend_figure(
    levels: Mapping[str, pd.DataFrame],
    runs: Sequence[str],
    found: Mapping[tuple[str, str], list[Step]],
    metrics: Metrics = CORE,
) -> tuple[Figure, int]:
    """One panel per metric of a tracker's levels over the runs, one point per run, steps marked.

    Parameters
    ----------
    levels : Mapping
        Metric name to a table with one row per run position (``0`` is the
        oldest run of ``runs``) and one column per dataset: the metric's mean
        over seeds, NaN where the dataset did not run.
    runs : sequence of str
        The label of each run position on the x axis (``#id · commit · date``),
        distinct for two runs of one day.
    found : Mapping
        ``(metric, dataset)`` to the steps found in that series, whose
        ``run_id`` is a run position.
    metrics : Metrics
        The catalogue that rounds each metric's values for the labels.

    Returns
    -------
    tuple
        The figure, and its height in pixels.
    """
    shown = list(levels)
    datasets = sorted({str(column) for table in levels.values() for column in table.columns})
    colours = {name: PALETTE[i % len(PALETTE)] for i, name in enumerate(datasets)}
    panels = len(shown)
    gap = 0.06 if panels > 1 else 0.0
    height = (1.0 - gap * (panels - 1)) / max(panels, 1)
    positions = list(range(len(runs)))
    traces, shapes, notes = [], [], []
    layout: dict[str, Any] = {}
    for i, metric in enumerate(shown):
        axis = "" if i == 0 else str(i + 1)
        top = 1.0 - i * (height + gap)
        layout[f"yaxis{axis}"] = {"title": {"text": metric, "font": {"size": 11}}, "domain": [top - height, top],
                                  "gridcolor": "#e0e0e0", "zeroline": False}
        table = levels[metric]
        for dataset in table.columns:
            name = str(dataset)
            values = table[dataset].reindex(positions)
            traces.append(
                {"type": "scatter", "mode": "lines+markers", "x": positions, "y": _finite(values), "name": name,
                 "legendgroup": name, "showlegend": i == 0, "xaxis": "x", "yaxis": f"y{axis}",
                 "line": {"color": colours[name], "width": 1.6}, "marker": {"size": 6}, "connectgaps": False,
                 "text": [format_value(metric, v, metrics) for v in values], "customdata": list(runs),
                 "hovertemplate": f"%{{customdata}}<br>{metric} %{{text}}<extra>{name}</extra>"}
            )
            for step in found.get((metric, name), []):
                x = step.run_id - 0.5
                shapes.append({"type": "line", "xref": "x", "yref": f"y{axis} domain", "x0": x, "x1": x, "y0": 0,
                               "y1": 1, "line": {"color": colours[name], "dash": "dash", "width": 1}})
                notes.append(
                    {"xref": "x", "yref": f"y{axis} domain", "x": x, "y": 1, "xanchor": "left", "yanchor": "top",
                     "showarrow": False, "font": {"size": 10, "color": colours[name]}, "bgcolor": "rgba(255,255,255,0.8)",
                     "text": f"{format_value(metric, step.before, metrics)} \u2192 "
                             f"{format_value(metric, step.after, metrics)}"}
                )
    layout |= {
        "xaxis": {"tickmode": "array", "tickvals": positions, "ticktext": list(runs), "tickangle": -30,
                  "range": [-0.5, max(len(runs) - 0.5, 0.5)], "anchor": f"y{'' if panels < 2 else panels}",
                  "gridcolor": "#e0e0e0", "automargin": True},
        "shapes": shapes, "annotations": notes, "hovermode": "closest", "font": _FONT,
        "margin": {"l": 70, "r": 20, "t": 40, "b": 20},
        "legend": {"orientation": "h", "x": 0, "y": 1.0, "yanchor": "bottom"},
        "plot_bgcolor": "white",
    }
    return {"data": traces, "layout": layout}, 220 * panels + 180


def _outcome_spans(frames: pd.DataFrame) -> dict[str, list[tuple[int, int]]]:
    """Frames grouped by outcome into ``(first, last)`` runs of consecutive frames."""
    spans: dict[str, list[tuple[int, int]]] = {outcome: [] for outcome in OUTCOME_COLOURS}
    index = frames["frame"].to_numpy(dtype=int)
    outcome = frames["outcome"].fillna("unscored").astype(str).to_numpy()
    start = 0
    for i in range(1, len(index) + 1):
        if i == len(index) or outcome[i] != outcome[start] or index[i] != index[i - 1] + 1:
            spans.setdefault(outcome[start], []).append((int(index[start]), int(index[i - 1])))
            start = i
    return spans


def cell_figure(frames: pd.DataFrame, errors: Sequence[str]) -> tuple[Figure, int]:
    """A cell's outcome strip over the error of each state variable against the frame.

    Parameters
    ----------
    frames : pandas.DataFrame
        The cell's frame table: ``frame``, ``outcome`` (None when unscored)
        and the error columns.
    errors : sequence of str
        The error columns to draw, one panel each, under the strip.

    Returns
    -------
    tuple
        The figure, and its height in pixels.
    """
    strip, panel, gap = 60, 150, 30
    total = strip + (panel + gap) * len(errors)
    counts = frames["outcome"].fillna("unscored").value_counts()
    traces, shapes = [], []
    for outcome, spans in _outcome_spans(frames).items():
        colour = OUTCOME_COLOURS.get(outcome, "#333333")
        shapes += [{"type": "rect", "xref": "x", "yref": "y domain", "x0": first - 0.5, "x1": last + 0.5, "y0": 0,
                    "y1": 1, "fillcolor": colour, "line": {"width": 0}, "layer": "below"} for first, last in spans]
        if spans:
            # An invisible point per frame of the outcome, so that hovering the strip names frame and outcome.
            frames_of = [f for first, last in spans for f in range(first, last + 1)]
            traces.append({"type": "scatter", "mode": "markers", "x": frames_of, "y": [0.5] * len(frames_of),
                           "xaxis": "x", "yaxis": "y", "name": f"{outcome} ({int(counts.get(outcome, 0))})",
                           "marker": {"color": colour, "symbol": "square", "size": 10, "opacity": 0},
                           "hovertemplate": f"frame %{{x}}: {outcome}<extra></extra>", "showlegend": True})
    layout: dict[str, Any] = {"yaxis": {"domain": [1 - strip / total, 1], "showticklabels": False, "range": [0, 1],
                                        "fixedrange": True, "showgrid": False, "zeroline": False}}
    for i, column in enumerate(errors):
        axis = str(i + 2)
        top = 1 - (strip + gap + i * (panel + gap)) / total
        layout[f"yaxis{axis}"] = {"title": {"text": column, "font": {"size": 11}}, "domain": [top - panel / total, top],
                                  "gridcolor": "#e0e0e0", "zerolinecolor": "#9e9e9e"}
        traces.append({"type": "scatter", "mode": "lines+markers", "x": frames["frame"].tolist(),
                       "y": _finite(pd.to_numeric(frames[column], errors="coerce")), "xaxis": "x",
                       "yaxis": f"y{axis}", "name": column, "showlegend": False, "connectgaps": False,
                       "line": {"color": "#1565c0", "width": 1}, "marker": {"size": 4},
                       "hovertemplate": f"frame %{{x}}<br>{column} %{{y:.4g}}<extra></extra>"})
    low, high = (int(frames["frame"].min()), int(frames["frame"].max())) if len(frames) else (0, 1)
    layout |= {
        "xaxis": {"range": [low - 0.5, high + 0.5], "anchor": f"y{len(errors) + 1 if errors else ''}",
                  "title": {"text": "frame", "font": {"size": 11}}, "gridcolor": "#e0e0e0"},
        "shapes": shapes, "hovermode": "closest", "font": _FONT, "plot_bgcolor": "white",
        "margin": {"l": 70, "r": 20, "t": 30, "b": 50},
        "legend": {"orientation": "h", "x": 0, "y": 1.0, "yanchor": "bottom", "itemclick": False,
                   "itemdoubleclick": False},
    }
    return {"data": traces, "layout": layout}, total + 100


OUT_OF_VIEW_COLOUR = "#c62828"
"""Colour of the frames of a top view at which the cable was out of view."""


def top_view_figure(view: TopView) -> tuple[Figure, int]:
    """A closed-loop cell from above: the route's centreline, the vehicle's path, the frames the cable was out of view.

    Both axes are metres (``x`` to the right of the route's first
    heading, ``z`` along it, :mod:`benchmark.closedloop.route`), each
    fitted to the plot on its own: drawn at one scale, the offsets of a few
    centimetres that tell trackers apart would vanish beside a route of
    tens of metres, so the lateral axis is stretched (the page says so).

    Parameters
    ----------
    view : TopView
        The cell's route and path (:func:`benchmark.closedloop.topview.top_view`).

    Returns
    -------
    tuple
        The figure, and its height in pixels.
    """
    hidden = ~view.in_view
    traces = [
        {"type": "scatter", "mode": "lines", "x": _finite(view.centreline[:, 0]), "y": _finite(view.centreline[:, 1]),
         "name": "cable", "line": {"color": "#9e9e9e", "width": 6}, "hoverinfo": "skip"},
        {"type": "scatter", "mode": "lines", "x": _finite(view.path[:, 0]), "y": _finite(view.path[:, 1]),
         "name": "vehicle", "line": {"color": "#1565c0", "width": 1.6}, "customdata": view.frames.tolist(),
         "hovertemplate": "frame %{customdata}<br>x %{x:.3f} m, z %{y:.2f} m<extra></extra>"},
        {"type": "scatter", "mode": "markers", "x": _finite(view.path[hidden, 0]), "y": _finite(view.path[hidden, 1]),
         "name": f"cable out of view ({int(hidden.sum())} frames)", "customdata": view.frames[hidden].tolist(),
         "marker": {"color": OUT_OF_VIEW_COLOUR, "size": 5},
         "hovertemplate": "frame %{customdata}: cable out of view<extra></extra>"},
    ]
    layout = {
        "xaxis": {"title": {"text": "x (m)", "font": {"size": 11}}, "gridcolor": "#e0e0e0", "zeroline": False},
        "yaxis": {"title": {"text": "z along the route's start (m)", "font": {"size": 11}}, "gridcolor": "#e0e0e0",
                  "zeroline": False},
        "hovermode": "closest", "font": _FONT, "plot_bgcolor": "white",
        "margin": {"l": 70, "r": 20, "t": 30, "b": 50},
        "legend": {"orientation": "h", "x": 0, "y": 1.0, "yanchor": "bottom"},
    }
    return {"data": traces, "layout": layout}, 560
