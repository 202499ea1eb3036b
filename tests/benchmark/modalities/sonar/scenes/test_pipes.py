"""Pipes on the seabed: the cross-section's width, where a proud pipe rests, how burial sinks it."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from benchmark.modalities.sonar.scenes.pipes import crossing_half_width, pipe_track, resting_depth, span_depth
from benchmark.modalities.sonar.scenes.seabed import across_grid

ACROSS = across_grid(8.0, 0.05)


def test_a_pipe_along_the_track_is_a_circle_and_an_oblique_one_wider() -> None:
    straight = crossing_half_width(np.full(5, 2.0), 0.3, 0.5)
    assert np.allclose(straight, 0.3)
    oblique = crossing_half_width(np.arange(5) * 0.5, 0.3, 0.5)  # 45 deg to the track
    assert np.allclose(oblique, 0.3 * np.sqrt(2.0))
    assert crossing_half_width(np.array([1.0]), 0.3, 0.5).tolist() == [0.3]


@given(st.floats(-6.0, 6.0), st.floats(2.0, 20.0), st.floats(0.05, 1.0))
def test_on_a_level_seabed_a_proud_pipe_touches_it(centre: float, depth: float, radius: float) -> None:
    base = np.full((1, len(ACROSS)), depth)
    axis = resting_depth(base, ACROSS, np.array([centre]), np.array([radius]), radius)
    assert axis[0] == pytest.approx(depth - radius)


def test_a_pipe_rests_on_the_highest_point_under_it() -> None:
    base = np.full((2, len(ACROSS)), 10.0)
    bump = np.argmin(np.abs(ACROSS - 0.2))
    base[0, bump] = 9.9  # a 10 cm high point 0.2 m from the axis
    axis = resting_depth(base, ACROSS, np.array([0.0, 0.0]), np.array([0.5, 0.5]), 0.5)
    x = ACROSS[bump]
    assert axis[0] == pytest.approx(9.9 - 0.5 * np.sqrt(1 - (x / 0.5) ** 2))
    assert axis[0] < axis[1] == pytest.approx(9.5)


def test_on_a_slope_the_ellipse_stays_above_the_seabed() -> None:
    base = 10.0 + 0.2 * ACROSS[None, :]
    axis = resting_depth(base, ACROSS, np.array([1.0]), np.array([0.4]), 0.4)
    inside = np.abs(ACROSS - 1.0) < 0.4
    lower_edge = axis[0] + 0.4 * np.sqrt(1 - ((ACROSS[inside] - 1.0) / 0.4) ** 2)
    assert np.all(lower_edge <= base[0, inside] + 1e-9)
    assert np.min(base[0, inside] - lower_edge) < 0.003


def test_burial_sinks_the_pipe_by_that_share_of_its_diameter() -> None:
    base = np.full((4, len(ACROSS)), 12.0)
    track = pipe_track(np.zeros(4), np.array([-0.2, 0.0, 0.5, 1.7]), 0.45, 0.7, base, ACROSS)
    assert track.burial.tolist() == [0.0, 0.0, 0.5, 1.0]
    assert np.allclose(track.axis_depth_m, [11.55, 11.55, 12.0, 12.45])
    assert track.visible.tolist() == [True, True, True, False]
    assert track.radius_m == 0.45 and np.allclose(track.half_width_m, 0.45)


@given(st.floats(20.0, 2000.0), st.floats(0.2, 3.0), st.floats(5.0, 80.0))
def test_a_stiff_pipe_never_sinks_below_where_it_would_rest(radius: float, height: float, wavelength: float) -> None:
    along = np.arange(300) * 0.5
    rest = 10.0 + 0.5 * height * np.sin(2 * np.pi * along / wavelength)
    spanned = span_depth(rest, 0.5, radius)
    assert np.all(spanned <= rest + 1e-12)
    assert np.all(np.abs(np.diff(spanned, 2)) / 0.25 <= 1.0 / radius + 1e-9 + np.abs(np.diff(rest, 2)) / 0.25)


def test_over_a_narrow_trough_the_pipe_hangs_in_a_parabola_between_the_crests() -> None:
    along = np.arange(201) * 0.5
    rest = np.where(np.abs(along - 50.0) < 10.0, 11.0, 10.0)  # a 20 m trough 1 m deep
    spanned = span_depth(rest, 0.5, 200.0)
    middle = 100
    assert spanned[middle] == pytest.approx(10.0 + 10.0**2 / (2 * 200.0), abs=0.01)  # the sag over 10 m either side
    assert np.all(spanned[np.abs(along - 50.0) >= 10.0] == 10.0)
    assert np.array_equal(span_depth(rest, 0.5, 0.0), rest)
    assert np.all(span_depth(rest, 0.5, 1.0)[np.abs(along - 50.0) < 8.0] == 11.0)  # pliant: it follows the trough


def test_a_spanning_pipe_reports_no_burial() -> None:
    base = np.full((60, len(ACROSS)), 12.0)
    base[20:40] += 1.5  # a trough under pings 20-39
    track = pipe_track(np.zeros(60), np.zeros(60), 0.3, 0.5, base, ACROSS, bend_radius_m=400.0)
    assert np.all(track.axis_depth_m[20:40] < 13.5 - 0.3 - 0.5)
    assert np.all(track.burial == 0.0)
    following = pipe_track(np.zeros(60), np.zeros(60), 0.3, 0.5, base, ACROSS)
    assert np.allclose(following.axis_depth_m[20:40], 13.2)
