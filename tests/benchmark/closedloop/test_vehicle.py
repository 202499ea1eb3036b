"""Tests of benchmark.closedloop.vehicle: commands move the vehicle along arcs, within limits, through a lag."""

from __future__ import annotations

import math

import pytest
from hypothesis import given
from hypothesis import strategies as st

from benchmark.closedloop.vehicle import Command, Kinematics, VehicleState


def test_no_command_goes_straight_at_the_surge_speed() -> None:
    state = Kinematics(surge_mps=0.5, lag_s=0.0).advance(VehicleState(0.0, 0.0, 0.0), Command(), 2.0)
    assert (state.x, state.z, state.psi) == pytest.approx((0.0, 1.0, 0.0))


def test_a_constant_turn_traces_a_circle_of_radius_surge_over_rate() -> None:
    kinematics = Kinematics(surge_mps=0.5, max_yaw_rate_dps=90.0, lag_s=0.0)
    rate = math.radians(10.0)
    state = VehicleState(0.0, 0.0, 0.0)
    for _ in range(90):
        state = kinematics.advance(state, Command(yaw_rate=rate), 0.1)
    radius = 0.5 / rate
    assert state.psi == pytest.approx(math.radians(90.0))
    assert (state.x, state.z) == pytest.approx((radius, radius))


def test_sway_moves_the_vehicle_to_its_right() -> None:
    state = Kinematics(lag_s=0.0).advance(VehicleState(0.0, 0.0, math.pi / 2), Command(sway_mps=0.2), 1.0)
    assert state.z == pytest.approx(-0.2)  # heading +x, its right is -z


def test_commands_are_clamped_to_the_limits() -> None:
    kinematics = Kinematics(max_sway_mps=0.3, max_yaw_rate_dps=15.0)
    limited = kinematics.limited(Command(sway_mps=-2.0, yaw_rate=1.0))
    assert limited == Command(-0.3, math.radians(15.0))


@given(interval=st.floats(0.01, 1.0), lag=st.floats(0.05, 3.0))
def test_the_lag_moves_speeds_part_of_the_way_monotonically(interval: float, lag: float) -> None:
    kinematics = Kinematics(lag_s=lag)
    state = kinematics.advance(VehicleState(0.0, 0.0, 0.0), Command(sway_mps=0.2), interval)
    assert 0.0 < state.sway_mps < 0.2
    assert state.sway_mps == pytest.approx(0.2 * (1.0 - math.exp(-interval / lag)))
    again = kinematics.advance(state, Command(sway_mps=0.2), interval)
    assert state.sway_mps < again.sway_mps <= 0.2
