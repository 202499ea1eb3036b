"""Tests of benchmark.closedloop.loop: a perfect tracker follows a route to its end, a biased one drives off it."""

from __future__ import annotations

import math

import numpy as np
import pytest

from benchmark.closedloop.controller import CableFollower, FollowerGains
from benchmark.closedloop.loop import CameraMount, Loop, bend_sag_m
from benchmark.closedloop.route import Leg, Route, RouteSpec
from benchmark.closedloop.vehicle import Kinematics
from benchmark.modalities.camera.model import CableState
from benchmark.modalities.camera.scenes.silhouette import cable_truth

RADIUS_M, FOCAL_PX, SIZE, INTERVAL_S = 0.1, 380.0, (320, 240), 0.2
S_BEND = RouteSpec((Leg(10.0), Leg(20.0, 30.0), Leg(20.0, -30.0), Leg(10.0)))


def follow(bias_px: float = 0.0, route: RouteSpec = S_BEND) -> Loop:
    """Drive the loop with the true cable, shifted ``bias_px`` along its normal, until the route ends."""
    loop = Loop(Route(route), Kinematics(), CameraMount(), CableFollower(FollowerGains(), INTERVAL_S, SIZE[0]), INTERVAL_S)
    for _ in range(2000):
        if loop.ended:
            break
        truth = cable_truth(loop.pose(), RADIUS_M, FOCAL_PX, SIZE)
        loop.steer(CableState(truth.d + bias_px, truth.alpha, truth.w, truth.beta))
    return loop


def test_a_tracker_reporting_the_truth_follows_the_s_bend_to_its_end() -> None:
    loop = follow()
    offsets = np.array([place.offset_m for place in loop.track.places])
    headings = np.array([place.heading_error for place in loop.track.places])
    assert loop.ended
    assert np.abs(offsets).max() < RADIUS_M
    assert np.degrees(np.abs(headings)).max() < 5.0


def test_a_tracker_reporting_the_cable_20_px_to_one_side_drives_the_vehicle_off_it() -> None:
    loop = follow(bias_px=20.0)
    offsets = np.array([place.offset_m for place in loop.track.places])
    settled = offsets[len(offsets) // 3 :]
    assert np.all(np.abs(settled) > RADIUS_M)
    assert abs(follow(bias_px=-20.0).track.places[-1].offset_m + offsets[-1]) < 0.05  # the mirror image


def test_the_sag_of_a_bend_over_the_seen_length_is_small() -> None:
    assert bend_sag_m(3.0, 20.0 / math.radians(30.0)) < 0.05
    assert bend_sag_m(2.0, 1.0) == pytest.approx(1.0)
