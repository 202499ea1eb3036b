import math

import pytest
from hypothesis import given
from hypothesis import strategies as st

from benchmark.modalities.camera.geometry import (
    DetectionRule,
    Line,
    cable_borders,
    cable_from_borders,
    chord_midpoint,
    model_to_pixel,
    orientation_difference,
    pixel_to_model,
    score_line_pair,
    state_errors,
)
from benchmark.modalities.camera.model import CableState
from benchmark.model import Outcome

SIZE = (320, 240)

states = st.builds(
    CableState,
    d=st.floats(-150, 150),
    alpha=st.floats(-math.pi / 2 + 0.01, math.pi / 2 - 0.01),
    w=st.floats(1, 100),
    beta=st.floats(-0.3, 0.3),
)
lines = st.builds(
    Line,
    x0=st.floats(-200, 200),
    y0=st.floats(-200, 200),
    dx=st.floats(-1, 1).filter(lambda v: abs(v) > 1e-3),
    dy=st.floats(-1, 1).filter(lambda v: abs(v) > 1e-3),
)


def same_line(a: Line, b: Line, tol: float = 1e-6) -> bool:
    cross = a.dx * b.dy - a.dy * b.dx
    # distance of b's point from line a
    offset = (b.x0 - a.x0) * a.dy - (b.y0 - a.y0) * a.dx
    return abs(cross) < tol and abs(offset) < tol * 1e3


def test_pixel_and_model_coordinates_follow_the_convention():
    assert pixel_to_model(0, 0, SIZE) == (-159.5, 119.5)
    assert pixel_to_model(159.5, 119.5, SIZE) == (0.0, 0.0)
    assert model_to_pixel(*pixel_to_model(12.0, 200.0, SIZE), SIZE) == (12.0, 200.0)


def test_vertical_cable_has_borders_left_and_right_of_the_centreline():
    left, right = cable_borders(CableState(d=10.0, alpha=0.0, w=20.0, beta=0.0))
    assert left.x0 == pytest.approx(0.0) and right.x0 == pytest.approx(20.0)
    assert left.orientation == pytest.approx(math.pi / 2)


def test_positive_skew_makes_borders_converge_towards_the_top():
    left, right = cable_borders(CableState(d=0.0, alpha=0.0, w=40.0, beta=0.1))
    # x of each border at the top and bottom rows of the image
    def x_at(line: Line, y: float) -> float:
        return line.x0 + (y - line.y0) / line.dy * line.dx

    assert x_at(right, 100) - x_at(left, 100) < x_at(right, -100) - x_at(left, -100)


def test_positive_alpha_turns_the_cable_counter_clockwise():
    left, _ = cable_borders(CableState(d=0.0, alpha=0.3, w=10.0, beta=0.0))
    # going up (dy > 0) the top leans left (dx < 0)
    dx, dy = (left.dx, left.dy) if left.dy > 0 else (-left.dx, -left.dy)
    assert dx < 0


@given(states)
def test_state_to_lines_to_state_round_trips(state):
    left, right = cable_borders(state)
    back = cable_from_borders(left, right)
    assert back.d == pytest.approx(state.d, abs=1e-6)
    assert back.alpha == pytest.approx(state.alpha, abs=1e-9)
    assert back.w == pytest.approx(state.w, abs=1e-6)
    assert back.beta == pytest.approx(state.beta, abs=1e-9)


@given(states)
def test_order_of_the_borders_does_not_matter(state):
    left, right = cable_borders(state)
    a, b = cable_from_borders(left, right), cable_from_borders(right, left)
    assert a.as_array() == pytest.approx(b.as_array(), abs=1e-9)


@given(lines, lines)
def test_lines_to_state_to_lines_gives_the_same_lines(first, second):
    if orientation_difference(first, second) > math.radians(80):
        return  # the cable model only describes nearly parallel borders
    state = cable_from_borders(first, second)
    borders = cable_borders(state)
    assert (same_line(borders[0], first) and same_line(borders[1], second)) or (
        same_line(borders[0], second) and same_line(borders[1], first)
    )


def test_chord_midpoint_of_a_line_through_the_image():
    assert chord_midpoint(Line(0.0, 0.0, 1.0, 0.0), SIZE) == pytest.approx((0.0, 0.0))
    # a vertical line at x = 50 spans all rows: its chord mid-point is at y = 0
    assert chord_midpoint(Line(50.0, -300.0, 0.0, 1.0), SIZE) == pytest.approx((50.0, 0.0))
    # y = x - 40 enters at the bottom edge (x = -79.5) and leaves at the right edge (x = 159.5)
    assert chord_midpoint(Line(159.5, 119.5, 1.0, 1.0), SIZE) == pytest.approx((40.0, 0.0))


def test_chord_midpoint_of_a_line_missing_the_image_is_nearest_the_centre():
    assert chord_midpoint(Line(500.0, 0.0, 0.0, 1.0), SIZE) == pytest.approx((500.0, 0.0))


@given(lines)
def test_chord_midpoint_lies_on_the_line_and_inside_when_the_line_crosses(line):
    x, y = chord_midpoint(line, SIZE)
    offset = (x - line.x0) * line.dy - (y - line.y0) * line.dx
    assert abs(offset) < 1e-6
    near = line.nearest_point_to_origin()
    if abs(near[0]) < 159 and abs(near[1]) < 119:
        assert abs(x) <= 159.5 + 1e-9 and abs(y) <= 119.5 + 1e-9


@given(states)
def test_a_pair_scores_correct_against_itself(state):
    pair = cable_borders(state)
    assert score_line_pair(pair, pair, SIZE) is Outcome.CORRECT


@given(states, states)
def test_rule_is_symmetric_in_the_order_of_lines(reported, truth):
    r, t = cable_borders(reported), cable_borders(truth)
    outcomes = {
        score_line_pair(r, t, SIZE),
        score_line_pair(r[::-1], t, SIZE),
        score_line_pair(r, t[::-1], SIZE),
        score_line_pair(r[::-1], t[::-1], SIZE),
    }
    assert len(outcomes) == 1


def test_rule_thresholds():
    truth = CableState(0.0, 0.0, 30.0, 0.0)
    shifted = lambda dd: cable_borders(CableState(dd, 0.0, 30.0, 0.0))  # noqa: E731
    assert score_line_pair(shifted(4.9), cable_borders(truth), SIZE) is Outcome.CORRECT
    assert score_line_pair(shifted(5.1), cable_borders(truth), SIZE) is Outcome.FALSE
    turned = cable_borders(CableState(0.0, math.radians(3.1), 30.0, 0.0))
    assert score_line_pair(turned, cable_borders(truth), SIZE) is Outcome.FALSE
    assert score_line_pair(turned, cable_borders(truth), SIZE, DetectionRule(max_angle_deg=4)) is Outcome.CORRECT
    assert score_line_pair(None, cable_borders(truth), SIZE) is Outcome.MISSED


def test_state_errors_compare_alpha_modulo_pi():
    truth = CableState(10.0, math.radians(89), 20.0, 0.0)
    estimate = CableState(-11.0, math.radians(-89), 21.0, 0.01)
    d, alpha, w, beta = state_errors(estimate, truth)
    assert d == pytest.approx(1.0)
    assert alpha == pytest.approx(math.radians(2))
    assert (w, beta) == pytest.approx((1.0, 0.01))


def test_a_degenerate_line_is_rejected():
    with pytest.raises(ValueError):
        Line(0.0, 0.0, 0.0, 0.0)
    with pytest.raises(ValueError):
        Line(math.nan, 0.0, 1.0, 0.0)
