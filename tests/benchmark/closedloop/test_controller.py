"""Tests of benchmark.closedloop.controller: the PD law's signs, its derivative, its hold and its search."""

from __future__ import annotations

import math

import pytest

from benchmark.closedloop.controller import CableFollower, FollowerGains
from benchmark.modalities.camera.model import CableState

GAINS = FollowerGains(k_offset_rate_m=0.0, k_angle_rate=0.0, hold_s=0.5, search_sway_mps=0.1)


def follower(gains: FollowerGains = GAINS) -> CableFollower:
    return CableFollower(gains, interval_s=0.25, width_px=320)


def test_a_cable_right_of_centre_asks_for_sway_to_the_right() -> None:
    command = follower().command(CableState(80.0, 0.0, 30.0, 0.0))
    assert command.sway_mps == pytest.approx(GAINS.k_offset_mps * 0.5)
    assert command.yaw_rate == 0.0


def test_a_cable_leaning_left_asks_for_a_turn_to_the_left() -> None:
    command = follower().command(CableState(0.0, 0.2, 30.0, 0.0))
    assert command.yaw_rate == pytest.approx(-GAINS.k_angle_per_s * 0.2)
    assert command.sway_mps == 0.0


def test_the_derivative_term_uses_consecutive_estimates_and_restarts_after_a_gap() -> None:
    gains = FollowerGains(k_offset_mps=0.0, k_offset_rate_m=1.0, k_angle_per_s=0.0, k_angle_rate=0.0)
    controller = follower(gains)
    controller.command(CableState(0.0, 0.0, 30.0, 0.0))
    moving = controller.command(CableState(16.0, 0.0, 30.0, 0.0))
    assert moving.sway_mps == pytest.approx((16.0 / 160.0) / 0.25)
    controller.command(None)
    assert controller.command(CableState(32.0, 0.0, 30.0, 0.0)).sway_mps == 0.0


def test_without_an_estimate_it_holds_then_searches_towards_the_side_last_seen() -> None:
    controller = follower()
    seen = controller.command(CableState(-40.0, 0.1, 30.0, 0.0))
    assert controller.command(None) == seen and controller.command(None) == seen
    assert not controller.searching
    search = controller.command(None)
    assert controller.searching
    assert search.sway_mps == pytest.approx(-GAINS.search_sway_mps) and search.yaw_rate == 0.0
    assert controller.command(CableState(-40.0, 0.1, 30.0, 0.0)) == seen
    assert not controller.searching


def test_an_unknown_state_counts_as_no_estimate() -> None:
    controller = follower()
    unknown = CableState(math.nan, math.nan, math.nan, math.nan)
    assert controller.command(unknown).sway_mps == 0.0
