"""A closed-loop run seen from above: the cable's route and the path the vehicle took over it.

The nightly site draws every closed-loop cell this way
(:func:`benchmark.site.figures.top_view_figure`).  What it needs is in
two places: the route, from the suite that declares it (its legs,
:class:`benchmark.closedloop.route.Route`), found by the dataset's
identity key (:func:`routes_by_dataset`); and the vehicle at each frame,
from the cell's frame table (:class:`benchmark.results.LoopValues`):
``loop_along_m`` is the arc length ``s`` of the route's point nearest the
vehicle and ``loop_offset_m`` the signed distance from it along the
route's normal there, so the vehicle stood at (:func:`vehicle_path`)::

    (x, z) = p(s) + offset * (cos psi(s), -sin psi(s))

with ``p(s)`` the centreline's point and ``psi(s)`` its heading
(:meth:`~benchmark.closedloop.route.Route.locate`, whose normal this is).
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass

import numpy as np
import pandas as pd

from benchmark.closedloop.route import Route
from benchmark.model import Sequence
from benchmark.results import LoopValues

CENTRELINE_STEP_M = 0.05
"""Spacing of the centreline's points drawn, m: finer than a pixel of a top view of a route of tens of metres."""


def routes_by_dataset(sequences: Iterable[Sequence]) -> dict[str, Route]:
    """The route of every closed-loop scene of ``sequences``, by its dataset identity key.

    Parameters
    ----------
    sequences : iterable of Sequence
        Any sequences (a registry's suites'); those that are not closed-loop
        scenes are skipped.
    """
    from benchmark.closedloop.scene import ClosedLoopScene  # the renderer: imported only where routes are looked up

    return {
        sequence.identity.key: sequence.spec.route for sequence in sequences if isinstance(sequence, ClosedLoopScene)
    }


@dataclass(frozen=True)
class TopView:
    """A closed-loop run from above, positions ``(x, z)`` in m (:mod:`benchmark.closedloop.route`).

    Attributes
    ----------
    centreline : numpy.ndarray
        ``(n, 2)``: the route's centreline from its start to its end.
    path : numpy.ndarray
        ``(frames, 2)``: where the vehicle stood at each frame with loop values.
    frames : numpy.ndarray
        The index of each of those frames.
    in_view : numpy.ndarray
        Per frame of ``path``, whether the cable was in view.
    """

    centreline: np.ndarray
    path: np.ndarray
    frames: np.ndarray
    in_view: np.ndarray


def vehicle_path(route: Route, along_m: np.ndarray, offset_m: np.ndarray) -> np.ndarray:
    """Where the vehicle stood: the route's point at each ``along_m``, moved ``offset_m`` along its normal.

    Returns
    -------
    numpy.ndarray
        ``(n, 2)`` positions ``(x, z)``, m.
    """
    points = np.array([route.point(float(s)) for s in along_m], dtype=float).reshape(-1, 2)
    headings = np.array([route.heading(float(s)) for s in along_m], dtype=float)
    normals = np.column_stack((np.cos(headings), -np.sin(headings)))
    return points + np.asarray(offset_m, dtype=float)[:, None] * normals


def top_view(route: Route, frames: pd.DataFrame) -> TopView:
    """The top view of one closed-loop cell from its frame table (``frame`` and the ``loop_*`` columns).

    Frames without loop values (none, or NaN) are left out.
    """
    along, offset, seen = (
        pd.to_numeric(frames.get(LoopValues.column(name), pd.Series(np.nan, index=frames.index)), errors="coerce")
        .to_numpy(dtype=float)
        for name in ("along_m", "offset_m", "in_view")
    )
    kept = np.isfinite(along) & np.isfinite(offset)
    steps = np.append(np.arange(0.0, route.length_m, CENTRELINE_STEP_M), route.length_m)
    centreline = np.array([route.point(float(s)) for s in steps], dtype=float)
    index = frames["frame"].to_numpy(dtype=int) if "frame" in frames else np.arange(len(frames))
    return TopView(
        centreline=centreline,
        path=vehicle_path(route, along[kept], offset[kept]),
        frames=index[kept],
        in_view=np.nan_to_num(seen[kept], nan=1.0) > 0.5,
    )


def has_loop_values(frames: pd.DataFrame) -> bool:
    """Whether a frame table holds the vehicle's place at any frame (a closed-loop cell's)."""
    columns = [LoopValues.column(name) for name in ("along_m", "offset_m")]
    return all(column in frames for column in columns) and bool(frames[columns].notna().all(axis=1).any())


__all__ = ["CENTRELINE_STEP_M", "TopView", "has_loop_values", "routes_by_dataset", "top_view", "vehicle_path"]
