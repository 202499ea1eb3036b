"""Tests of border-pair grouping (seeds/004, section IV)."""

from __future__ import annotations

import math
import struct
from dataclasses import astuple

import numpy as np
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from trackbench_hough.lines import HoughLine, normal_form
from trackbench_hough.pairing import BorderPair, best_pair, choose_pair, compatible_pairs
from trackbench_hough.window import SearchWindow

from benchmark.modalities.camera.geometry import Line, cable_borders, cable_from_borders
from benchmark.modalities.camera.model import CableState

SIZE = (320, 240)
LIMITS = dict(max_skew=math.radians(10.0), max_divergence=math.radians(1.0), min_width=5.0, max_width=100.0)


def hough_line(line: Line, votes: float) -> HoughLine:
    """The HoughLine (with OpenCV's rho, theta) of a model-coordinate line."""
    r, phi = normal_form(line)
    theta = (-phi) % math.pi
    cu, cv = (SIZE[0] - 1) / 2.0, (SIZE[1] - 1) / 2.0
    # OpenCV's theta is -phi folded into [0, pi); folding flips the normal when phi > 0.
    sign = 1.0 if phi <= 0 else -1.0
    rho = sign * r + cu * math.cos(theta) + cv * math.sin(theta)
    return HoughLine.from_opencv(rho, theta, votes, SIZE)


def cable_lines(state: CableState, votes: tuple[float, float] = (100.0, 90.0)) -> list[HoughLine]:
    left, right = cable_borders(state)
    return [hough_line(left, votes[0]), hough_line(right, votes[1])]


def borders_cross_in_the_image(state: CableState) -> bool:
    """Whether the two borders of a converging cable meet inside the image (such a pair is rejected)."""
    a, b = cable_borders(state)
    det = a.dx * b.dy - a.dy * b.dx
    if abs(det) < 1e-12:
        return False
    s = ((b.x0 - a.x0) * b.dy - (b.y0 - a.y0) * b.dx) / det
    return abs(a.x0 + s * a.dx) <= (SIZE[0] - 1) / 2.0 and abs(a.y0 + s * a.dy) <= (SIZE[1] - 1) / 2.0


@settings(max_examples=50, deadline=None)
@given(
    d=st.floats(-80.0, 80.0),
    alpha_deg=st.floats(-40.0, 40.0),
    w=st.floats(6.0, 99.0),
    beta_deg=st.floats(0.0, 1.0),
)
def test_a_cable_pair_is_compatible_and_gives_back_its_state(d, alpha_deg, w, beta_deg):
    truth = CableState(d, math.radians(alpha_deg), w, math.radians(beta_deg))
    assume(not borders_cross_in_the_image(truth))  # a narrow converging cable may close inside the image
    pairs = compatible_pairs(cable_lines(truth), SIZE, **LIMITS)
    assert len(pairs) == 1
    state = pairs[0].state
    assert math.isclose(state.d, truth.d, abs_tol=1e-6) and math.isclose(state.w, truth.w, abs_tol=1e-6)
    assert math.isclose(state.alpha, truth.alpha, abs_tol=1e-9) and math.isclose(state.beta, truth.beta, abs_tol=1e-9)
    assert pairs[0].votes == 190.0


def test_implausible_pairs_are_rejected():
    cases = {
        "too narrow": CableState(0.0, 0.0, 4.0, 0.0),
        "too wide": CableState(0.0, 0.0, 120.0, 0.0),
        "too skewed": CableState(0.0, 0.0, 90.0, math.radians(12.0)),
        "diverging": CableState(0.0, 0.0, 40.0, -math.radians(3.0)),
        "crossing in the image": CableState(0.0, 0.0, 20.0, math.radians(8.0)),
    }
    for why, state in cases.items():
        assert compatible_pairs(cable_lines(state), SIZE, **LIMITS) == [], why
    assert compatible_pairs(cable_lines(CableState(0.0, 0.0, 40.0, -math.radians(0.5))), SIZE, **LIMITS)


def test_the_pair_with_most_votes_wins_without_a_window():
    weak = cable_lines(CableState(-60.0, 0.0, 30.0, 0.0), (80.0, 80.0))
    strong = cable_lines(CableState(60.0, 0.0, 30.0, 0.0), (120.0, 110.0))
    pairs = compatible_pairs(weak + strong, SIZE, **LIMITS)
    chosen = choose_pair(pairs)
    assert chosen is not None and math.isclose(chosen.state.d, 60.0, abs_tol=1e-6)
    assert choose_pair([]) is None


def test_a_window_keeps_out_far_pairs_and_favours_near_ones():
    previous = cable_lines(CableState(-60.0, 0.0, 30.0, 0.0))
    window = SearchWindow.around(previous[0], previous[1], 15.0, math.radians(5.0))
    near = cable_lines(CableState(-55.0, 0.0, 30.0, 0.0), (80.0, 80.0))
    far = cable_lines(CableState(60.0, 0.0, 30.0, 0.0), (150.0, 150.0))
    edge = cable_lines(CableState(-47.0, 0.0, 30.0, 0.0), (90.0, 90.0))
    assert choose_pair(compatible_pairs(far, SIZE, **LIMITS), window) is None
    chosen = choose_pair(compatible_pairs(near + far + edge, SIZE, **LIMITS), window, closeness_weight=0.5)
    assert chosen is not None and math.isclose(chosen.state.d, -55.0, abs_tol=1e-6)
    chosen = choose_pair(compatible_pairs(near + edge, SIZE, **LIMITS), window, closeness_weight=0.0)
    assert chosen is not None and math.isclose(chosen.state.d, -47.0, abs_tol=1e-6)


def test_the_stronger_border_must_reach_the_anchor_votes():
    cable = CableState(10.0, 0.0, 30.0, 0.0)
    # One clear border vouches for a faint one ...
    assert compatible_pairs(cable_lines(cable, (100.0, 30.0)), SIZE, **LIMITS, anchor_votes=100.0)
    # ... two faint ones do not make a cable.
    assert compatible_pairs(cable_lines(cable, (99.0, 99.0)), SIZE, **LIMITS, anchor_votes=100.0) == []
    assert compatible_pairs(cable_lines(cable, (99.0, 99.0)), SIZE, **LIMITS) != []


def crossing_inside_by_objects(a: Line, b: Line, size) -> bool:
    """Whether two lines cross inside the image, as trackbench_hough.pairing first tested it."""
    det = a.dx * b.dy - a.dy * b.dx
    if abs(det) < 1e-12:
        return False
    s = ((b.x0 - a.x0) * b.dy - (b.y0 - a.y0) * b.dx) / det
    x, y = a.x0 + s * a.dx, a.y0 + s * a.dy
    return abs(x) <= (size[0] - 1) / 2.0 and abs(y) <= (size[1] - 1) / 2.0


def compatible_pairs_by_objects(lines: list[HoughLine], size, *, max_skew, max_divergence, min_width, max_width, anchor_votes=0.0):
    """trackbench_hough.pairing.compatible_pairs as first written: line objects, Python geometry."""
    models = [line.line(size) for line in lines]
    pairs = []
    angle_limit = 2.0 * max(max_skew, max_divergence)
    for i, first in enumerate(lines):
        for j in range(i + 1, len(lines)):
            second = lines[j]
            if max(first.votes, second.votes) < anchor_votes:
                continue
            if first.distance_to(second.r, second.phi)[1] > angle_limit:
                continue
            a, b = models[i], models[j]
            if crossing_inside_by_objects(a, b, size):
                continue
            state = cable_from_borders(a, b)
            if not (-max_divergence <= state.beta <= max_skew and min_width <= state.w <= max_width):
                continue
            pairs.append(BorderPair(first, second, (a, b), state, first.votes + second.votes))
    return pairs


def choose_pair_by_objects(pairs: list[BorderPair], window: SearchWindow | None = None, closeness_weight: float = 0.5):
    """trackbench_hough.pairing.choose_pair as first written, with the window's Python fits."""
    best, best_score = None, -math.inf
    for pair in pairs:
        score = pair.votes
        if window is not None:
            deviation = window.deviation_of_fits(window.fits(pair.first), window.fits(pair.second))
            if deviation is None:
                continue
            score *= 1.0 - closeness_weight * deviation
        if score > best_score:
            best, best_score = pair, score
    return best


nearly_parallel_lines = st.lists(
    st.tuples(
        st.floats(-400.0, 400.0),
        st.floats(0.0, math.pi - 0.05),
        st.integers(1, 200),
        st.floats(-120.0, 120.0),
        st.floats(-0.04, 0.04),
        st.integers(1, 200),
    ),
    max_size=6,
)


def couples(raw) -> list[HoughLine]:
    """Lines in nearly parallel couples, so that some pairs pass the first tests and reach the geometry."""
    return [
        HoughLine.from_opencv(rho + shift * side, (theta + turn * side) % math.pi, votes, SIZE)
        for rho, theta, votes, shift, turn, other_votes in raw
        for side, votes in ((0, votes), (1, other_votes))
    ]


@settings(max_examples=100, deadline=None)
@given(
    raw=nearly_parallel_lines,
    anchor_votes=st.sampled_from([0.0, 60.0, 150.0]),
    max_skew_deg=st.sampled_from([1.0, 10.0]),
)
def test_compatible_pairs_are_those_the_line_objects_gave(raw, anchor_votes, max_skew_deg):
    lines = couples(raw)
    limits = dict(LIMITS, max_skew=math.radians(max_skew_deg), anchor_votes=anchor_votes)
    got = compatible_pairs(lines, SIZE, **limits)
    expected = compatible_pairs_by_objects(lines, SIZE, **limits)
    assert got == expected
    # Equal floats could still differ in sign of zero; the states must be the same bits.
    assert [struct.pack("4d", *astuple(pair.state)) for pair in got] == [
        struct.pack("4d", *astuple(pair.state)) for pair in expected
    ]


@settings(max_examples=150, deadline=None)
@given(
    raw=nearly_parallel_lines,
    previous=st.tuples(st.floats(-150.0, 150.0), st.floats(-0.3, 0.3), st.floats(5.0, 60.0)),
    r_half=st.floats(2.0, 60.0),
    phi_half_deg=st.floats(0.5, 10.0),
    closeness_weight=st.sampled_from([0.0, 0.5, 1.0]),
    tracking=st.booleans(),
)
def test_the_compiled_choice_is_the_one_the_line_objects_gave(raw, previous, r_half, phi_half_deg, closeness_weight, tracking):
    lines = couples(raw)
    r, phi, w = previous
    window = SearchWindow(((r, phi), (r + w, phi)), r_half, math.radians(phi_half_deg)) if tracking else None
    expected = choose_pair_by_objects(compatible_pairs_by_objects(lines, SIZE, **LIMITS), window, closeness_weight)
    assert choose_pair(compatible_pairs(lines, SIZE, **LIMITS), window, closeness_weight) == expected
    rows = np.array([astuple(line) for line in lines], np.float64).reshape(-1, 5)
    fused = best_pair(rows, SIZE, window, closeness_weight, **LIMITS)
    assert fused == expected
    if expected is not None:
        assert struct.pack("4d", *astuple(fused.state)) == struct.pack("4d", *astuple(expected.state))
