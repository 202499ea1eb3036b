"""Pipes on the seabed: the cross-section's width, where a proud pipe rests, how burial sinks it."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from benchmark.modalities.sonar.scenes.pipes import crossing_half_width, pipe_track, resting_depth
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
