"""Tests of the Hough line detection and its (r, phi) bookkeeping."""

from __future__ import annotations

import math

from collections.abc import Iterable

import cv2
import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp
from trackbench_hough.line_loops import distance, most_votes_first, remainder_half_turn
from trackbench_hough.lines import (
    HoughLine,
    accumulator_maxima,
    distinct_lines,
    hough_lines,
    normal_form,
    theta_intervals,
    wrap_half_turn,
)
from trackbench_hough.window import SearchWindow

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
    edges = drawn_lines()
    lines = distinct_lines(accumulator_maxima(edges, 1.0, math.radians(1.0), 150), SIZE, 3.0, math.radians(3.0), 12)
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
    cu = (SIZE[0] - 1) / 2.0
    raw = np.array(
        [[cu + 10.0, 0.0, 90.0], [cu + 11.5, 0.02, 80.0], [cu + 40.0, 0.0, 70.0], [cu + 10.0, 0.3, 60.0]], np.float32
    )
    kept = distinct_lines(raw, SIZE, 3.0, math.radians(3.0), 12)
    assert [line.votes for line in kept] == [90.0, 70.0, 60.0]
    assert [line.votes for line in distinct_lines(raw, SIZE, 3.0, math.radians(3.0), 2)] == [90.0, 70.0]


def suppress_duplicates(
    lines: Iterable[HoughLine], r_tolerance: float, phi_tolerance: float, limit: int | None = None
) -> list[HoughLine]:
    """Duplicate suppression as trackbench_hough.lines did it, line object by line object, before it was compiled."""
    kept: list[HoughLine] = []
    for line in lines:
        for other in kept:
            dr, dphi = line.distance_to(other.r, other.phi)
            if dr < r_tolerance and dphi < phi_tolerance:
                break
        else:
            kept.append(line)
            if limit is not None and len(kept) >= limit:
                break
    return kept


def distinct_lines_by_objects(
    raw: np.ndarray, size, r_tolerance: float, phi_tolerance: float, limit: int, window: SearchWindow | None
) -> list[HoughLine]:
    """What the tracker did with the transform's maxima before the compiled loop: sort, admit, suppress."""
    rows = np.asarray(raw, dtype=np.float64).reshape(-1, 3)
    rows = rows[np.argsort(-rows[:, 2], kind="stable")]
    lines = (HoughLine.from_opencv(rho, theta, votes, size) for rho, theta, votes in rows.tolist())
    admitted = lines if window is None else (line for line in lines if window.admits(line))
    return suppress_duplicates(admitted, r_tolerance, phi_tolerance, limit)


def bits(lines: list[HoughLine]) -> bytes:
    return np.array([(line.rho, line.theta, line.votes, line.r, line.phi) for line in lines], np.float64).tobytes()


# OpenCV's maxima: rho of either sign, theta on a grid of steps (and at its ends), votes with ties.
maxima = hnp.arrays(
    np.float32,
    st.tuples(st.integers(0, 40), st.just(3)),
    elements=st.floats(-400.0, 400.0, width=32),
).flatmap(
    lambda rows: st.tuples(
        st.just(rows),
        st.lists(st.integers(0, 360), min_size=len(rows), max_size=len(rows)),
        st.lists(st.integers(1, 8), min_size=len(rows), max_size=len(rows)),
    )
)


def opencv_rows(drawn, theta_step: float) -> np.ndarray:
    rows, steps, votes = drawn
    rows = rows.copy()
    rows[:, 1] = np.minimum(np.float32(np.array(steps, np.float64) * theta_step), np.float32(math.pi) - 1e-6)
    rows[:, 2] = np.array(votes, np.float32) * 10
    return rows


@settings(max_examples=150, deadline=None)
@given(
    drawn=maxima,
    theta_step_deg=st.sampled_from([0.5, 1.0, 2.5]),
    size=st.sampled_from([(320, 240), (640, 480), (33, 17)]),
    tolerances=st.tuples(st.sampled_from([0.0, 3.0, 12.0]), st.sampled_from([0.0, 0.02, 0.05, 0.5])),
    limit=st.integers(2, 14),
    window=st.none()
    | st.builds(
        lambda a, b, r_half, phi_half: SearchWindow((a, b), r_half, phi_half),
        st.tuples(st.floats(-300.0, 300.0), st.floats(-math.pi / 2, math.pi / 2, exclude_min=True)),
        st.tuples(st.floats(-300.0, 300.0), st.floats(-math.pi / 2, math.pi / 2, exclude_min=True)),
        st.floats(1.0, 60.0),
        st.floats(0.01, 0.5),
    ),
)
def test_distinct_lines_are_those_the_line_objects_gave(drawn, theta_step_deg, size, tolerances, limit, window):
    raw = opencv_rows(drawn, math.radians(theta_step_deg))
    expected = distinct_lines_by_objects(raw, size, *tolerances, limit, window)
    borders = () if window is None else (window.borders, window.r_half, window.phi_half)
    found = distinct_lines(raw, size, *tolerances, limit, *borders)
    assert bits(found) == bits(expected)


@settings(max_examples=300, deadline=None)
@given(
    angle=st.floats(-2 * math.pi, 2 * math.pi)
    | st.sampled_from([k * math.pi / 2 for k in range(-4, 5)])
    | st.integers(-4, 4).flatmap(
        lambda k: st.sampled_from([np.nextafter(k * math.pi / 2, -9.0), np.nextafter(k * math.pi / 2, 9.0)])
    ).map(float)
)
def test_remainder_half_turn_is_ieee_remainder(angle):
    expected = math.remainder(angle, math.pi)
    found = remainder_half_turn(angle)
    assert found == expected and math.copysign(1.0, found) == math.copysign(1.0, expected)


phis = st.floats(-math.pi / 2, math.pi / 2, exclude_min=True) | st.sampled_from([math.pi / 2, 0.0, -0.0, 1e-300])


@settings(max_examples=200, deadline=None)
@given(r=st.floats(-500.0, 500.0), phi=phis, other_r=st.floats(-500.0, 500.0), other_phi=phis)
def test_compiled_distance_is_the_line_objects(r, phi, other_r, other_phi):
    expected = HoughLine(0.0, 0.0, 1.0, r, phi).distance_to(other_r, other_phi)
    assert np.array(distance(r, phi, other_r, other_phi)).tobytes() == np.array(expected).tobytes()


@settings(max_examples=40, deadline=None)
@given(drawn=maxima, limit=st.integers(2, 12))
def test_a_limited_suppression_is_the_start_of_the_full_one(drawn, limit):
    raw = opencv_rows(drawn, math.radians(1.0))
    full = distinct_lines(raw, SIZE, 3.0, math.radians(3.0), 100)
    assert distinct_lines(raw, SIZE, 3.0, math.radians(3.0), limit) == full[:limit]


def test_hough_lines_are_every_maximum_strongest_first():
    edges = drawn_lines()
    raw = accumulator_maxima(edges, 1.0, math.radians(1.0), 50)
    assert bits(hough_lines(edges, 1.0, math.radians(1.0), 50)) == bits(
        distinct_lines_by_objects(raw, SIZE, 0.0, 0.0, None, None)
    )


@settings(max_examples=100, deadline=None)
@given(votes=hnp.arrays(np.float32, st.integers(0, 60), elements=st.sampled_from([1.0, 2.0, 3.0, 10.0, 250.0])))
def test_most_votes_first_is_numpys_stable_argsort(votes):
    np.testing.assert_array_equal(most_votes_first(votes), np.argsort(-votes, kind="stable"))
