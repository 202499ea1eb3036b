"""Tests of the Hough line detection and its (r, phi) bookkeeping."""

from __future__ import annotations

import math

import cv2
import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from trackbench_hough.lines import (
    HoughLine,
    hough_lines,
    normal_form,
    suppress_duplicates,
    theta_intervals,
    wrap_half_turn,
)

from benchmark.modalities.camera.geometry import Line, pixel_to_model

SIZE = (320, 240)


@settings(max_examples=60, deadline=None)
@given(rho=st.floats(-300.0, 300.0), theta=st.floats(0.0, math.pi, exclude_max=True))
def test_centred_normal_form_describes_the_opencv_line(rho, theta):
    line = HoughLine.from_opencv(rho, theta, 10.0, SIZE)
    assert -math.pi / 2 < line.phi <= math.pi / 2
    # Two pixel points of OpenCV's line u cos(theta) + v sin(theta) = rho satisfy the centred form.
    for s in (-50.0, 80.0):
        u = rho * math.cos(theta) - s * math.sin(theta)
        v = rho * math.sin(theta) + s * math.cos(theta)
        x, y = pixel_to_model(u, v, SIZE)
        assert math.isclose(x * math.cos(line.phi) + y * math.sin(line.phi), line.r, abs_tol=1e-6)
    r, phi = normal_form(line.line(SIZE))
    assert math.isclose(r, line.r, abs_tol=1e-6)
    assert abs(wrap_half_turn(phi - line.phi)) < 1e-9


def test_distance_is_taken_across_the_half_turn():
    a = HoughLine(0.0, 0.0, 1.0, 20.0, math.pi / 2 - 0.01)
    b = HoughLine(0.0, 0.0, 1.0, -21.0, -math.pi / 2 + 0.01)
    dr, dphi = a.distance_to(b.r, b.phi)
    assert math.isclose(dr, 1.0, abs_tol=1e-9) and math.isclose(dphi, 0.02, abs_tol=1e-9)


@settings(max_examples=60, deadline=None)
@given(centre=st.floats(-math.pi / 2, math.pi / 2), half=st.floats(1e-3, 0.5), probe=st.floats(-1.0, 1.0))
def test_theta_intervals_cover_the_phi_window(centre, half, probe):
    intervals = theta_intervals(centre - half, centre + half)
    assert all(0.0 <= low <= high <= math.pi for low, high in intervals)
    assert sum(high - low for low, high in intervals) <= 2 * half + 1e-9
    theta = (-(centre + probe * half)) % math.pi
    # theta and theta + pi name the same line; OpenCV's range is [0, pi).
    assert any(low - 1e-9 <= t <= high + 1e-9 for low, high in intervals for t in (theta, theta + math.pi))


def drawn_lines() -> np.ndarray:
    edges = np.zeros(SIZE[::-1], np.uint8)
    cv2.line(edges, (100, 0), (120, 239), 255, 1)
    cv2.line(edges, (250, 0), (250, 239), 255, 1)
    return edges


def test_hough_finds_drawn_lines_strongest_first():
    lines = suppress_duplicates(hough_lines(drawn_lines(), 1.0, math.radians(1.0), 150), 3.0, math.radians(3.0))
    assert len(lines) == 2
    assert lines[0].votes >= lines[1].votes
    vertical = next(line for line in lines if abs(line.phi) < 1e-6)
    assert vertical.votes == SIZE[1]
    assert math.isclose(vertical.r, 250 - (SIZE[0] - 1) / 2, abs_tol=1.0)
    slanted = next(line for line in lines if line is not vertical)
    expected = Line.from_pixels((100, 0), (120, 239), SIZE)
    assert math.degrees(abs(wrap_half_turn(slanted.phi - normal_form(expected)[1]))) <= 1.0


def test_hough_searches_only_the_given_intervals():
    window = theta_intervals(-math.radians(3.0), math.radians(3.0))
    lines = hough_lines(drawn_lines(), 1.0, math.radians(1.0), 150, window)
    assert lines and all(abs(line.phi) <= math.radians(3.0) + 1e-9 for line in lines)
    assert all(abs(line.r - (250 - (SIZE[0] - 1) / 2)) <= 2.0 for line in lines)
    assert hough_lines(np.zeros_like(drawn_lines()), 1.0, math.radians(1.0), 10) == []


def test_suppression_keeps_the_strongest_of_a_cluster():
    lines = [
        HoughLine(0.0, 0.0, 90.0, 10.0, 0.0),
        HoughLine(0.0, 0.0, 80.0, 11.5, 0.02),
        HoughLine(0.0, 0.0, 70.0, 40.0, 0.0),
        HoughLine(0.0, 0.0, 60.0, 10.0, 0.3),
    ]
    kept = suppress_duplicates(lines, 3.0, math.radians(3.0))
    assert [line.votes for line in kept] == [90.0, 70.0, 60.0]


@settings(max_examples=40, deadline=None)
@given(
    lines=st.lists(
        st.tuples(st.floats(-100.0, 100.0), st.floats(0.0, math.pi, exclude_max=True), st.integers(1, 500)),
        max_size=30,
    ),
    limit=st.integers(1, 12),
)
def test_a_limited_suppression_is_the_start_of_the_full_one(lines, limit):
    candidates = sorted((HoughLine.from_opencv(r, t, v, SIZE) for r, t, v in lines), key=lambda line: -line.votes)
    full = suppress_duplicates(candidates, 3.0, math.radians(3.0))
    assert suppress_duplicates(candidates, 3.0, math.radians(3.0), limit) == full[:limit]
