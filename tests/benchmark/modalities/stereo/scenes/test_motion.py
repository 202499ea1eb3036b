"""Boat trajectories: constant-acceleration speed profiles, paths, and the geometry between boats."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st

from benchmark.modalities.stereo.scenes.motion import (
    BoatTrack,
    boat_track,
    path_offset,
    profile_distance,
    profile_speed,
    relative_geometry,
)
from benchmark.modalities.stereo.scenes.spec import BoatSpec, PathSpec

WEAVE = PathSpec(course_deg=120.0, amplitude_m=6.0, wavelength_m=60.0, onset_m=20.0, ramp_m=40.0)


@st.composite
def profiles(draw):
    n = draw(st.integers(1, 6))
    gaps = draw(st.lists(st.floats(0.5, 20.0), min_size=n - 1, max_size=n - 1))
    speeds = draw(st.lists(st.floats(0.0, 12.0), min_size=n, max_size=n))
    times = np.concatenate(([0.0], np.cumsum(gaps)))
    return tuple((float(t), v) for t, v in zip(times, speeds))


@settings(max_examples=60, deadline=None)
@given(knots=profiles())
@example(knots=((0.0, 5.0), (0.5, 0.0), (20.0, 0.0)))
def test_distance_is_the_exact_integral_of_the_speed(knots) -> None:
    end = knots[-1][0] + 10.0
    # With the knots on the grid the speed is linear between grid points, so the trapezoid rule is exact.
    fine = np.union1d(np.linspace(0.0, end, 2001), [time for time, _ in knots])
    speed = profile_speed(knots, fine)
    numeric = np.concatenate(([0.0], np.cumsum(0.5 * (speed[1:] + speed[:-1]) * np.diff(fine))))
    np.testing.assert_allclose(profile_distance(knots, fine), numeric, rtol=0.0, atol=1e-9 * (1.0 + numeric[-1]))


def test_speed_is_linear_between_knots_and_held_after_the_last() -> None:
    knots = ((0.0, 2.0), (10.0, 4.0), (20.0, 4.0), (25.0, 1.0))
    t = np.array([0.0, 5.0, 10.0, 15.0, 22.5, 25.0, 100.0])
    np.testing.assert_allclose(profile_speed(knots, t), [2.0, 3.0, 4.0, 4.0, 2.5, 1.0, 1.0])
    acceleration = np.diff(profile_speed(knots, np.arange(0.0, 10.0, 0.5))) / 0.5
    np.testing.assert_allclose(acceleration, 0.2)


def test_a_straight_track_runs_along_its_course() -> None:
    boat = BoatSpec(PathSpec(origin_m=(5.0, -3.0), course_deg=90.0), start_m=2.0, speed_knots=((0.0, 3.0),))
    track = boat_track(boat, np.array([0.0, 1.0, 4.0]))
    np.testing.assert_allclose(track.position_m, [[5.0, -1.0], [5.0, 2.0], [5.0, 11.0]], atol=1e-12)
    np.testing.assert_allclose(track.velocity_mps, [[0.0, 3.0]] * 3, atol=1e-12)
    np.testing.assert_allclose(track.heading, math.pi / 2)


def test_a_weaving_boat_moves_at_its_profile_speed_along_its_heading() -> None:
    boat = BoatSpec(WEAVE, start_m=3.0, speed_knots=((0.0, 2.0), (20.0, 9.0), (40.0, 5.0)))
    dt = 0.01
    track = boat_track(boat, np.arange(0.0, 60.0, dt))
    step = np.diff(track.position_m, axis=0)
    mid_velocity = 0.5 * (track.velocity_mps[1:] + track.velocity_mps[:-1])
    np.testing.assert_allclose(step / dt, mid_velocity, atol=2e-3)
    np.testing.assert_allclose(track.speed_mps, profile_speed(boat.speed_knots, track.times_s), atol=1e-12)
    np.testing.assert_allclose(
        track.heading, np.arctan2(track.velocity_mps[:, 1], track.velocity_mps[:, 0]), atol=1e-12
    )


def test_the_sinusoid_grows_smoothly_from_its_onset() -> None:
    u = np.linspace(0.0, 200.0, 20001)
    offset, _ = path_offset(WEAVE, u)
    assert np.all(offset[u <= 20.0] == 0.0)
    assert np.max(np.abs(offset[u >= 60.0])) == pytest.approx(6.0, abs=1e-3)
    boat = BoatSpec(WEAVE, speed_knots=((0.0, 5.0),))
    heading = np.unwrap(boat_track(boat, np.arange(0.0, 40.0, 0.2)).heading)
    turn = np.diff(heading)
    assert heading[0] == pytest.approx(math.radians(120.0))
    # No jump where the sinusoid begins: the turn per step grows gradually from zero.
    assert np.max(np.abs(np.diff(turn))) < 0.2 * np.max(np.abs(turn))


def test_without_a_ramp_the_heading_jumps_at_the_onset() -> None:
    abrupt = PathSpec(amplitude_m=6.0, wavelength_m=60.0, onset_m=20.0)
    heading = boat_track(BoatSpec(abrupt, speed_knots=((0.0, 5.0),)), np.arange(0.0, 8.0, 0.2)).heading
    assert np.max(np.abs(np.diff(heading))) > math.radians(25.0)


@pytest.mark.parametrize("ramp_m", [1e-310, 1e-300])
def test_a_ramp_too_short_to_resolve_is_the_abrupt_onset_without_a_warning(ramp_m: float) -> None:
    u = np.array([0.0, 19.0, 20.0, 21.0, 100.0])
    abrupt = PathSpec(amplitude_m=6.0, wavelength_m=60.0, onset_m=20.0)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        short = path_offset(PathSpec(amplitude_m=6.0, wavelength_m=60.0, onset_m=20.0, ramp_m=ramp_m), u)
    np.testing.assert_allclose(short[0], path_offset(abrupt, u)[0], rtol=0.0, atol=1e-12)


def _track(position, heading, velocity=(1.0, 0.0)) -> BoatTrack:
    return BoatTrack(
        times_s=np.zeros(1),
        position_m=np.array([position], dtype=float),
        velocity_mps=np.array([velocity], dtype=float),
        heading=np.array([heading], dtype=float),
    )


@pytest.mark.parametrize(
    ("target", "ahead", "starboard", "bearing_deg"),
    [((10.0, 0.0), 10.0, 0.0, 0.0), ((0.0, 5.0), 0.0, 5.0, 90.0), ((3.0, -3.0), 3.0, -3.0, -45.0)],
)
def test_relative_position_of_a_target_seen_from_a_northbound_boat(target, ahead, starboard, bearing_deg) -> None:
    geometry = relative_geometry(_track((0.0, 0.0), 0.0), _track(target, 0.0))
    assert (geometry.ahead_m[0], geometry.starboard_m[0]) == pytest.approx((ahead, starboard))
    assert math.degrees(geometry.bearing[0]) == pytest.approx(bearing_deg)
    assert geometry.range_m[0] == pytest.approx(math.hypot(*target))


@settings(max_examples=100, deadline=None)
@given(
    chase=st.tuples(st.floats(-100, 100), st.floats(-100, 100)),
    target=st.tuples(st.floats(-100, 100), st.floats(-100, 100)),
    psi=st.floats(-math.pi, math.pi),
    target_heading=st.floats(-math.pi, math.pi),
)
def test_equation_10_maps_the_relative_position_back(chase, target, psi, target_heading) -> None:
    g = relative_geometry(_track(chase, psi), _track(target, target_heading))
    x_v, y_v = g.ahead_m[0], g.starboard_m[0]
    absolute = (
        math.cos(psi) * x_v - math.sin(psi) * y_v + chase[0],
        math.sin(psi) * x_v + math.cos(psi) * y_v + chase[1],
    )
    assert absolute == pytest.approx(target, abs=1e-9)
    assert -math.pi <= g.aspect[0] < math.pi
    assert math.cos(g.aspect[0]) == pytest.approx(math.cos(target_heading - psi))
