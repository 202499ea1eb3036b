"""Tests of benchmark.closedloop.route: legs make the centreline, and a vehicle is located against it."""

from __future__ import annotations

import math

import pytest
from hypothesis import given
from hypothesis import strategies as st

from benchmark.closedloop.route import Leg, Route, RouteSpec, wrap_angle
from benchmark.errors import DataError

S_BEND = RouteSpec((Leg(20.0), Leg(15.0, 30.0), Leg(15.0, -30.0), Leg(20.0)))


def test_a_straight_route_runs_along_z() -> None:
    route = Route(RouteSpec((Leg(50.0),)))
    assert route.length_m == 50.0
    assert route.point(10.0) == pytest.approx((0.0, 10.0))
    place = route.locate(0.7, 12.0, math.radians(5.0))
    assert place.s_m == pytest.approx(12.0)
    assert place.offset_m == pytest.approx(0.7)
    assert place.heading_error == pytest.approx(math.radians(5.0))


def test_an_arc_turns_by_its_angle_on_a_circle_of_its_radius() -> None:
    route = Route(RouteSpec((Leg(math.pi * 10.0 / 2.0, 90.0),)))  # a quarter circle of radius 10 m, turning right
    assert route.heading(route.length_m) == pytest.approx(math.pi / 2)
    assert route.point(route.length_m) == pytest.approx((10.0, 10.0), abs=1e-6)


def test_an_s_bend_ends_with_the_heading_it_started_with() -> None:
    route = Route(S_BEND)
    assert route.heading(route.length_m) == pytest.approx(0.0, abs=1e-12)
    assert route.point(route.length_m)[0] > 1.0


@given(s=st.floats(0.0, 70.0), offset=st.floats(-1.5, 1.5), turn=st.floats(-0.5, 0.5))
def test_a_point_moved_along_the_normal_is_located_at_its_offset(s: float, offset: float, turn: float) -> None:
    route = Route(S_BEND)
    x, z = route.point(s)
    psi = route.heading(s)
    place = route.locate(x + offset * math.cos(psi), z - offset * math.sin(psi), psi + turn, near_s_m=s)
    assert place.s_m == pytest.approx(s, abs=0.02)
    assert place.offset_m == pytest.approx(offset, abs=2e-3)
    assert place.heading_error == pytest.approx(turn, abs=2e-3)


def test_a_hint_keeps_the_search_on_the_stretch_being_followed() -> None:
    hairpin = Route(RouteSpec((Leg(20.0), Leg(math.pi * 1.0, 179.0), Leg(20.0))))
    x, z = hairpin.point(5.0)
    assert hairpin.locate(x, z, 0.0, near_s_m=5.0).s_m == pytest.approx(5.0, abs=0.02)


def test_angles_wrap_into_the_half_open_turn() -> None:
    assert wrap_angle(3 * math.pi) == pytest.approx(math.pi)
    assert wrap_angle(-math.pi) == math.pi
    assert wrap_angle(0.25) == 0.25


@pytest.mark.parametrize(
    ("data", "message"),
    [({"legs": []}, "at least one leg"), ({"legs": [{"length_m": -1.0}]}, "length_m"), ({"legs": [{"length_m": 5.0, "turn_deg": 200.0}]}, "180")],
)
def test_a_bad_route_is_a_data_error_naming_the_key(data: dict[str, object], message: str) -> None:
    with pytest.raises(DataError, match=message):
        RouteSpec.from_dict(data, "routes.toml [route r]")
