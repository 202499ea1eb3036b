"""Following: how far, and how closely, a vehicle steered by the tracker followed the cable.

Open-loop scores miss what a controller feels; a closed-loop run
(:mod:`benchmark.closedloop`) measures it.  The thesis names the test:
"putting the system on an underwater robot and let it follow a cable"
(seeds/000, chapter 5).  Every frame of a closed-loop run records where
the vehicle stood when the camera took it (:class:`benchmark.results.LoopValues`,
the frame table's ``loop_*`` columns); four metrics read them, added as any
plugin adds metrics (through the ``trackbench_register_metrics`` hook,
registered under the ``trackbench`` entry-point group):

``followed_m``
    Distance along the route followed before the cable was first out of
    view for longer than :data:`LOST_S`: the farthest point along the
    route at which the cable was in view before that, m; the mean over
    cells (higher is better).  The cable is out of view for longer than
    ``LOST_S`` at the first frame whose time is more than ``LOST_S`` after
    the last frame that had it in view (or after the run's first frame).
    A run never lost whose vehicle passed the route's end after its last
    frame followed the whole route: its ``followed_m`` is the route's
    length, not the last frame's place short of the end, which differs
    between runs by a fraction of a frame's travel and would rank them by
    chance.
``followed_pct``
    The share of the route followed: the distance followed over the
    route's length (``loop_route_m``), per cent; cells pool by adding
    both, so that a longer route weighs more (higher is better).
``offset_mean_m``, ``offset_max_m``
    The mean and the largest absolute lateral offset of the vehicle from
    the cable over every frame, m (lower is better; pooled cells take the
    largest).
``heading_error_deg``
    The mean absolute heading error against the cable, deg (lower is better).

A closed-loop board (:mod:`benchmark.leaderboard`) shows them first and
ranks by ``followed_m``, then ``offset_mean_m`` (:attr:`~benchmark.metrics.Metric.ranks`).
Frame tables without the ``loop_*`` columns (open-loop cells) give them no
value, and a board whose frames hold none leaves them out
(:attr:`benchmark.metrics.Metric.requires`).  A pooled table is split into
cells as the robustness metrics split it (:func:`benchmark.metrics.sequence_starts`).
"""

from __future__ import annotations

import functools
import itertools
from typing import TYPE_CHECKING

import numpy as np

from benchmark.hookspecs import hookimpl
from benchmark.metrics import Effect, Metric, percentage, ratio, sequence_starts, single
from benchmark.results import LoopValues

if TYPE_CHECKING:
    import pandas as pd

    from benchmark.registry import Registry

LOST_S = 2.0
"""How long the cable may be out of view before the run counts it lost, s.

Twice the controller's hold of the routes suite (``hold_s = 1.0``,
:class:`benchmark.closedloop.controller.FollowerGains`): a tracker that
misses the cable for a moment is not charged, one whose vehicle has spent
a second searching without bringing the cable back into view is.
"""

OFFSET = LoopValues.column("offset_m")
HEADING = LoopValues.column("heading_error_deg")
ALONG = LoopValues.column("along_m")
TIME = LoopValues.column("time_s")
IN_VIEW = LoopValues.column("in_view")
ROUTE = LoopValues.column("route_m")


def _column(frames: pd.DataFrame, column: str) -> np.ndarray:
    return frames[column].to_numpy(dtype=float) if column in frames else np.full(len(frames), np.nan)


def followed_distance(
    along_m: np.ndarray, time_s: np.ndarray, in_view: np.ndarray, lost_s: float = LOST_S, route_m: float = np.nan
) -> float:
    """The distance one run followed: the farthest ``along_m`` in view before the cable was out of view over ``lost_s``.

    Parameters
    ----------
    along_m, time_s : numpy.ndarray
        Per frame in order, the distance along the route (m) and the time (s).
    in_view : numpy.ndarray
        Per frame, whether the cable was in view (bool, or 1.0 and 0.0).
    lost_s : float
        How long the cable may be out of view.
    route_m : float, optional
        The route's length, m.  A run never lost whose last frame lies
        within one frame's travel (the largest step between frames) of it
        passed the route's end: it followed all of it.

    Returns
    -------
    float
        0 when the cable was never in view before it was lost.
    """
    seen = np.asarray(in_view, dtype=bool)
    if seen.size == 0:
        return 0.0
    last_seen_s = np.maximum.accumulate(np.where(seen, time_s, time_s[0]))
    lost = np.flatnonzero(~seen & (time_s - last_seen_s > lost_s))
    if lost.size == 0 and seen.size > 1 and along_m[-1] + np.max(np.diff(along_m)) >= route_m:
        return float(route_m)
    end = lost[0] if lost.size else seen.size
    return float(np.max(along_m[:end][seen[:end]], initial=0.0))


def _loop_rows(frames: pd.DataFrame) -> tuple[np.ndarray, list[tuple[int, int]]]:
    """The frames with ``loop_*`` values (a mask), and each cell's ``(first, end)`` among them."""
    along, time, in_view = _column(frames, ALONG), _column(frames, TIME), _column(frames, IN_VIEW)
    rows = np.isfinite(along) & np.isfinite(time) & np.isfinite(in_view)
    bounds = [*np.flatnonzero(sequence_starts(frames, rows)), int(np.count_nonzero(rows))]
    return rows, list(itertools.pairwise(bounds))


def followed_per_cell(frames: pd.DataFrame, lost_s: float = LOST_S) -> np.ndarray:
    """:func:`followed_distance` of each cell of a frame table with ``loop_*`` values, in order."""
    return _followed_and_routes(frames, lost_s)[0]


def _route_lengths(route: np.ndarray, cells: list[tuple[int, int]]) -> np.ndarray:
    said = np.isfinite(route)
    return np.array([route[a:b][said[a:b]].max() if said[a:b].any() else np.nan for a, b in cells])


def _followed_and_routes(frames: pd.DataFrame, lost_s: float = LOST_S) -> tuple[np.ndarray, np.ndarray]:
    """Each cell's distance followed and route length, the cells split once."""
    rows, cells = _loop_rows(frames)
    along, time, in_view, route = (_column(frames, column)[rows] for column in (ALONG, TIME, IN_VIEW, ROUTE))
    routes = _route_lengths(route, cells)
    followed = [
        followed_distance(along[a:b], time[a:b], in_view[a:b] > 0.5, lost_s, length)
        for (a, b), length in zip(cells, routes, strict=True)
    ]
    return np.array(followed), routes


def _followed_sums(frames: pd.DataFrame, scale: float) -> tuple[float, float]:
    """Cells, and the distance they followed."""
    followed = followed_per_cell(frames)
    return float(followed.size), float(followed.sum())


def _share_sums(frames: pd.DataFrame, scale: float) -> tuple[float, float]:
    """The length of the routes of the cells that say it, and the distance those cells followed, m."""
    followed, route = _followed_and_routes(frames)
    known = np.isfinite(route)
    return float(route[known].sum()), float(followed[known].sum())


def _absolute(frames: pd.DataFrame, column: str) -> np.ndarray:
    values = _column(frames, column)
    return np.abs(values[np.isfinite(values)])


def _mean_sums(column: str, frames: pd.DataFrame, scale: float) -> tuple[float, float]:
    """Frames with a value in ``column``, and the sum of its absolute values."""
    values = _absolute(frames, column)
    return float(values.size), float(values.sum())


def _largest_sums(frames: pd.DataFrame, scale: float) -> tuple[float]:
    """The largest absolute offset; NaN without one, so that pooling skips it."""
    values = _absolute(frames, OFFSET)
    return (float(values.max()) if values.size else float("nan"),)


FOLLOWED = Metric(
    name="followed_m",
    better="higher",
    kind="following",
    columns=(ALONG, TIME, IN_VIEW),
    requires=(ALONG, TIME, IN_VIEW),
    sums=_followed_sums,
    value=ratio,
    digits=2,
    minimum_effect=Effect(0.10, relative=True),
    description=f"distance along the route followed before the cable was out of view for over {LOST_S:g} s, "
    "mean over cells",
    spread=True,
    ranks=True,
    headline=True,
)
"""Distance followed; a change of a tenth counts (the RMSEs' share, set by reasoning, not fitted)."""

FOLLOWED_SHARE = Metric(
    name="followed_pct",
    better="higher",
    kind="following",
    columns=(ALONG, TIME, IN_VIEW, ROUTE),
    requires=(ALONG, TIME, IN_VIEW, ROUTE),
    sums=_share_sums,
    value=percentage,
    digits=1,
    minimum_effect=Effect(5.0),
    description="share of the route followed (followed_m over the route's length), pooled over cells",
)
"""Share of the route followed; a change of five points counts (a twentieth of the route: 0.6 to 1.5 m on the
routes suite's 12 to 30 m routes; set by reasoning, not fitted)."""

OFFSET_MEAN = Metric(
    name="offset_mean_m",
    better="lower",
    kind="following",
    columns=(OFFSET,),
    requires=(OFFSET,),
    sums=functools.partial(_mean_sums, OFFSET),
    value=ratio,
    digits=3,
    minimum_effect=Effect(0.10, relative=True),
    description="mean absolute lateral offset of the vehicle from the cable",
    ranks=True,
)
"""Mean absolute offset; a change of a tenth counts, as for an RMSE."""

OFFSET_MAX = Metric(
    name="offset_max_m",
    better="lower",
    kind="following",
    columns=(OFFSET,),
    requires=(OFFSET,),
    sums=_largest_sums,
    value=single,
    pool="max",
    digits=3,
    minimum_effect=Effect(0.20, relative=True),
    description="largest absolute lateral offset of the vehicle from the cable",
)
"""Largest offset; a change of a fifth counts, as for the longest failure (one frame decides it)."""

HEADING_ERROR = Metric(
    name="heading_error_deg",
    better="lower",
    kind="following",
    columns=(HEADING,),
    requires=(HEADING,),
    sums=functools.partial(_mean_sums, HEADING),
    value=ratio,
    digits=1,
    minimum_effect=Effect(0.10, relative=True),
    description="mean absolute heading error of the vehicle against the cable",
)
"""Mean absolute heading error; a change of a tenth counts, as for an RMSE."""

METRICS = (FOLLOWED, FOLLOWED_SHARE, OFFSET_MEAN, OFFSET_MAX, HEADING_ERROR)


@hookimpl
def trackbench_register_metrics(registry: Registry) -> None:
    """Add the following metrics, for every modality (only closed-loop frames feed them)."""
    for metric in METRICS:
        registry.add_metric(metric)
