"""Tests of the tracking window that limits the Hough parameter space."""

from __future__ import annotations

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from trackbench_hough.lines import HoughLine
from trackbench_hough.window import STRIP_ROWS, SearchWindow

from benchmark.modalities.camera.geometry import cable_borders
from benchmark.modalities.camera.model import CableState

HALF_PHI = math.radians(5.0)


def line(r: float, phi: float) -> HoughLine:
    return HoughLine(0.0, 0.0, 1.0, r, phi)


def test_window_around_vertical_borders_wraps_in_theta():
    window = SearchWindow.around_borders(cable_borders(CableState(0.0, 0.0, 30.0, 0.0)), 10.0, HALF_PHI)
    intervals = sorted(window.theta_intervals())
    assert len(intervals) == 2
    (low_a, high_a), (low_b, high_b) = intervals
    assert low_a == 0.0 and math.isclose(high_a, HALF_PHI)
    assert math.isclose(low_b, math.pi - HALF_PHI) and high_b == math.pi


def test_window_spans_both_border_angles():
    state = CableState(0.0, math.radians(30.0), 40.0, math.radians(4.0))
    window = SearchWindow.around_borders(cable_borders(state), 10.0, HALF_PHI)
    (low, high), = window.theta_intervals()
    assert math.isclose(high - low, 2 * HALF_PHI + math.radians(8.0), abs_tol=1e-9)
    assert low <= math.radians(180.0 - 30.0) <= high


def test_admits_lines_near_either_border_only():
    window = SearchWindow(((-15.0, 0.0), (15.0, 0.0)), 10.0, HALF_PHI)
    assert window.admits(line(-20.0, 0.05)) and window.admits(line(24.0, -0.05))
    assert not window.admits(line(40.0, 0.0))
    assert not window.admits(line(15.0, 0.2))
    # The same line written with the opposite normal is still admitted.
    assert SearchWindow(((10.0, math.pi / 2),) * 2, 5.0, HALF_PHI).admits(line(-10.0, -math.pi / 2 + 0.01))


def test_deviation_matches_borders_in_either_order():
    window = SearchWindow(((-15.0, 0.0), (15.0, 0.0)), 10.0, HALF_PHI)
    assert window.deviation(line(15.0, 0.0), line(-15.0, 0.0)) == 0.0
    assert math.isclose(window.deviation(line(-10.0, 0.0), line(15.0, 0.0)), 0.5)
    assert window.deviation(line(-15.0, 0.0), line(-16.0, 0.0)) is None
    assert window.deviation(line(-15.0, 0.0), line(40.0, 0.0)) is None


# The edge image outside the voting strips cannot change the lines the window admits.
border_angles = st.floats(-math.pi / 2 + 1e-3, math.pi / 2)


@settings(max_examples=60, deadline=None)
@given(
    size=st.sampled_from([(64, 48), (96, 72), (80, 80)]),
    r=st.floats(-40.0, 40.0),
    phi=border_angles,
    width=st.floats(3.0, 30.0),
    skew=st.floats(-0.1, 0.1),
    r_half=st.floats(2.0, 12.0),
    phi_half_deg=st.floats(1.0, 8.0),
    density=st.floats(0.01, 0.2),
    seed=st.integers(0, 2**32 - 1),
)
def test_edges_outside_the_voting_strips_change_no_admitted_line(
    size, r, phi, width, skew, r_half, phi_half_deg, density, seed
):
    from trackbench_hough.lines import accumulator_maxima, wrap_half_turn

    window = SearchWindow(((r, phi), (r + width, wrap_half_turn(phi + skew))), r_half, math.radians(phi_half_deg))
    rho_step, theta_step, min_votes = 1.0, math.radians(1.0), 3
    rng = np.random.default_rng(seed)
    edges = np.where(rng.random((size[1], size[0])) < density, 255, 0).astype(np.uint8)
    # Pixels on the borders' lines, so that the window has lines to admit.
    for border_r, border_phi in window.borders:
        v, u = np.mgrid[0 : size[1], 0 : size[0]]
        x, y = u - (size[0] - 1) / 2.0, (size[1] - 1) / 2.0 - v
        edges[np.abs(x * math.cos(border_phi) + y * math.sin(border_phi) - border_r) < 0.5] = 255
    masked = np.zeros_like(edges)
    for row0, row1, col0, col1 in window.voting_strips(size, rho_step, theta_step):
        masked[row0:row1, col0:col1] = edges[row0:row1, col0:col1]

    def admitted(image):
        found = accumulator_maxima(image, rho_step, theta_step, min_votes, window.theta_intervals())
        lines = (HoughLine.from_opencv(rho, theta, votes, size) for rho, theta, votes in found.tolist())
        return [line for line in lines if window.admits(line)]

    assert admitted(masked) == admitted(edges)


def test_voting_strips_cover_the_rows_near_a_horizontal_border():
    window = SearchWindow(((0.0, math.pi / 2), (10.0, math.pi / 2)), 2.0, math.radians(1.0))
    strips = window.voting_strips((640, 480), 1.0, math.radians(0.5))
    assert len(strips) and all(col0 == 0 and col1 == 640 for _, _, col0, col1 in strips)
    assert all(row0 > 0 and row1 < 480 for row0, row1, _, _ in strips)  # but not the far rows


def test_voting_strips_follow_a_vertical_border():
    window = SearchWindow(((0.0, 0.0), (20.0, 0.0)), 5.0, math.radians(1.0))
    strips = window.voting_strips((640, 480), 1.0, math.radians(0.5))
    assert [(row0, row1) for row0, row1, _, _ in strips] == [(row0, row0 + 60) for row0 in range(0, 480, 60)]
    assert all(100 < col0 < 319.5 < 339.5 < col1 < 540 for _, _, col0, col1 in strips)


def voting_strips_by_objects(window: SearchWindow, size, rho_step, theta_step) -> list[tuple[int, int, int, int]]:
    """SearchWindow.voting_strips as it was before it was compiled."""
    width, height = size
    cu, cv = (width - 1) / 2.0, (height - 1) / 2.0
    half_diagonal = math.hypot(cu, cv)
    reach = (
        window.r_half + 1.5 * rho_step + half_diagonal * theta_step + 1.0 + half_diagonal * (window.phi_half + theta_step)
    )
    spans = []
    for r, phi in window.borders:
        cos_phi, sin_phi = math.cos(phi), math.sin(phi)
        spans.append((r, sin_phi, cos_phi if cos_phi > 1e-6 else 0.0))
    strips = []
    for row0 in range(0, height, STRIP_ROWS):
        row1 = min(row0 + STRIP_ROWS, height)
        lowest, highest = math.inf, -math.inf
        for r, sin_phi, cos_phi in spans:
            offsets = [r - (cv - v) * sin_phi for v in (row0, row1 - 1)]
            if cos_phi:
                ends = [(offset + side * reach) / cos_phi + cu for offset in offsets for side in (-1, 1)]
                lowest, highest = min(lowest, *ends), max(highest, *ends)
            elif min(offsets) <= reach + 1.0 and max(offsets) >= -reach - 1.0:
                lowest, highest = -math.inf, math.inf
        if lowest > highest:
            continue
        col0 = max(0, math.floor(lowest) - 1) if math.isfinite(lowest) else 0
        col1 = min(width, math.ceil(highest) + 2) if math.isfinite(highest) else width
        if col0 < col1:
            strips.append((row0, row1, col0, col1))
    return strips


@settings(max_examples=150, deadline=None)
@given(
    size=st.sampled_from([(320, 240), (640, 480), (64, 48), (50, 200)]),
    first=st.tuples(st.floats(-400.0, 400.0), border_angles | st.sampled_from([math.pi / 2, 1.5707953, 0.0])),
    second=st.tuples(st.floats(-400.0, 400.0), border_angles | st.sampled_from([math.pi / 2, -1.5707953])),
    r_half=st.floats(1.0, 60.0),
    phi_half=st.floats(0.005, 0.3),
    steps=st.sampled_from([(1.0, math.radians(1.0)), (2.0, math.radians(0.5))]),
)
def test_voting_strips_are_those_the_python_loop_gave(size, first, second, r_half, phi_half, steps):
    window = SearchWindow((first, second), r_half, phi_half)
    found = window.voting_strips(size, *steps)
    assert found.dtype == np.int64
    assert [tuple(row) for row in found.tolist()] == voting_strips_by_objects(window, size, *steps)
