"""Tests of benchmark.closedloop.topview: the vehicle's path from its frames, over the route from its legs."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from benchmark.closedloop.route import Leg, Route, RouteSpec
from benchmark.closedloop.scene import ClosedLoopScene
from benchmark.closedloop.topview import has_loop_values, routes_by_dataset, top_view, vehicle_path
from benchmark.results import LoopValues

from .test_scene import ROUTE


def frames_of(along: list[float], offsets: list[float], seen: list[bool]) -> pd.DataFrame:
    rows = [
        {"frame": i, "outcome": "correct", **LoopValues(o, 0.0, s, 0.04 * i, v).columns()}
        for i, (s, o, v) in enumerate(zip(along, offsets, seen, strict=True))
    ]
    return pd.DataFrame(rows)


def test_on_a_straight_route_the_path_is_the_offset_to_the_side_of_the_distance_along() -> None:
    route = Route(RouteSpec((Leg(10.0),)))
    path = vehicle_path(route, np.array([0.0, 2.5, 7.0]), np.array([0.3, -0.1, 0.0]))
    assert path == pytest.approx(np.array([[0.3, 0.0], [-0.1, 2.5], [0.0, 7.0]]))


def test_on_a_right_turn_the_normal_turns_with_the_route() -> None:
    route = Route(RouteSpec((Leg(1.0), Leg(math.pi / 2 * 4.0, turn_deg=90.0))))  # a quarter circle of radius 4 m
    (x, z), = vehicle_path(route, np.array([route.length_m]), np.array([0.5]))
    # At the end the route heads along +x from (4, 5); its right-hand normal points along -z.
    assert (x, z) == pytest.approx((4.0, 4.5), abs=1e-3)


@settings(max_examples=40, deadline=None)
@given(
    turn=st.floats(-60.0, 60.0),
    s=st.floats(0.5, 7.5),
    offset=st.floats(-0.8, 0.8),
)
def test_the_route_locates_the_path_it_gives_back_where_it_was(turn: float, s: float, offset: float) -> None:
    route = Route(RouteSpec((Leg(2.0), Leg(6.0, turn_deg=turn))))
    (x, z), = vehicle_path(route, np.array([s]), np.array([offset]))
    place = route.locate(x, z, route.heading(s), near_s_m=s)
    assert (place.s_m, place.offset_m) == pytest.approx((s, offset), abs=2e-3)


def test_the_top_view_keeps_frames_with_loop_values_and_marks_those_out_of_view() -> None:
    route = Route(RouteSpec((Leg(3.0),)))
    frames = frames_of([0.0, 1.0, 2.0], [0.2, 0.1, 0.0], [True, False, True])
    frames = pd.concat([frames, pd.DataFrame([{"frame": 3, "outcome": "correct"}])], ignore_index=True)
    view = top_view(route, frames)
    assert view.frames.tolist() == [0, 1, 2] and view.in_view.tolist() == [True, False, True]
    assert view.path[:, 0] == pytest.approx([0.2, 0.1, 0.0])
    assert view.centreline[0] == pytest.approx([0.0, 0.0]) and view.centreline[-1] == pytest.approx([0.0, 3.0])
    assert has_loop_values(frames) and not has_loop_values(frames.iloc[3:]) and not has_loop_values(pd.DataFrame())


def test_routes_are_found_by_dataset_key_among_any_sequences() -> None:
    scene = ClosedLoopScene.from_dict(ROUTE)
    found = routes_by_dataset([scene, object()])  # type: ignore[list-item]
    assert list(found) == [scene.identity.key]
    assert found[scene.identity.key].length_m == pytest.approx(2.5)
