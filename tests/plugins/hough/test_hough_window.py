"""Tests of the tracking window that limits the Hough parameter space."""

from __future__ import annotations

import math

from trackbench_hough.lines import HoughLine
from trackbench_hough.window import SearchWindow

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
