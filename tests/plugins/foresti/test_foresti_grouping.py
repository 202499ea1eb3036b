"""Tests of the grouping of candidate lines into the pipeline's borders (seeds/004, section IV)."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from trackbench_foresti.grouping import (
    GroupingParams,
    choose_pair,
    compatible,
    compatible_pairs,
    convergence,
    encloses,
    outline,
    pair_reliability,
    symmetry,
)

from benchmark.modalities.camera.geometry import Line, cable_borders
from benchmark.modalities.camera.model import CableState

SIZE = (320, 240)


def pair_at(draw, top, bottom, reliabilities=(0.8, 0.8)):
    """Candidates through pixel columns ``top = (left, right)`` on row 0 and ``bottom`` on row H-1."""
    return [
        draw.candidate(draw.through_rows(top[0], bottom[0]), reliabilities[0]),
        draw.candidate(draw.through_rows(top[1], bottom[1]), reliabilities[1]),
    ]


def test_a_cable_gives_one_pair_ordered_left_to_right(draw):
    state = CableState(12.0, math.radians(8.0), 36.0, math.radians(2.0))
    left, right = (draw.candidate(border) for border in cable_borders(state))
    pairs = compatible_pairs([right, left], SIZE)
    assert len(pairs) == 1
    assert pairs[0].left is left and pairs[0].right is right
    (i1, i3), (i2, i4) = left.abscissae(SIZE), right.abscissae(SIZE)
    assert np.allclose(pairs[0].abscissae, [i1, i2, i3, i4])
    assert choose_pair([right, left], SIZE) == (left, right)


def test_lines_crossing_inside_the_image_are_not_a_pair(draw):
    cross = pair_at(draw, (100.0, 200.0), (200.0, 100.0))
    assert not compatible(cross[0], cross[1], SIZE) and not compatible(cross[1], cross[0], SIZE)
    assert compatible_pairs(cross, SIZE) == []
    assert choose_pair(cross, SIZE) is None


def test_lines_crossing_beside_the_image_within_its_rows_are_not_a_pair(draw):
    # They cross near row 16 at u of about -5: outside the image, but left and right swap within its rows.
    lines = pair_at(draw, (-10.0, -20.0), (60.0, 200.0))
    assert compatible_pairs(lines, SIZE) == []


def test_borders_may_not_diverge_towards_the_top_beyond_the_slack(draw):
    slack = (SIZE[1] - 1) * math.tan(math.radians(1.0))  # about 4.2 px
    diverging = pair_at(draw, (100.0, 200.0), (120.0, 180.0))
    assert not compatible(*diverging, SIZE)
    barely = pair_at(draw, (150.0, 190.0 + 0.9 * slack), (150.0, 190.0))
    assert compatible(*barely, SIZE)
    assert not compatible(*barely, SIZE, max_divergence=0.0)
    converging = pair_at(draw, (150.0, 170.0), (130.0, 190.0))
    parallel = pair_at(draw, (150.0, 190.0), (150.0, 190.0))
    assert compatible(*converging, SIZE) and compatible(*parallel, SIZE)
    assert not compatible(converging[1], converging[0], SIZE)  # rule (c): left must be left


def test_two_borders_stepping_the_same_way_do_not_bound_a_band(draw):
    left, right = pair_at(draw, (100.0, 140.0), (80.0, 160.0))
    signed = [dataclasses.replace(line, polarity=sign) for line, sign in zip((left, right), (-1, 1), strict=True)]
    assert compatible(*signed, SIZE)
    assert not compatible(signed[0], dataclasses.replace(signed[1], polarity=-1), SIZE)
    assert compatible(signed[0], dataclasses.replace(signed[1], polarity=0), SIZE)  # unknown: not ruled out
    assert choose_pair([signed[0], dataclasses.replace(signed[1], polarity=-1)], SIZE) is None


def test_lines_far_from_vertical_are_not_paired(draw):
    flat = [draw.candidate(Line.from_normal(rho, math.radians(80.0))) for rho in (-30.0, 30.0)]
    assert all(not line.by_rows for line in flat)
    assert compatible_pairs(flat, SIZE) == [] and not compatible(*flat, SIZE)


def test_grouping_reliability_by_hand(draw):
    full = np.ones(SIZE[1], bool)
    lower = np.zeros(SIZE[1], bool)
    lower[40:] = True
    left = draw.candidate(draw.through_rows(150.0, 140.0), 0.8, full)
    right = draw.candidate(draw.through_rows(170.0, 180.0), 0.6, lower)
    # Spans [0, 239] and [40, 239]: IoU = 200 / 240.  s_top / s_bottom = 20 / 40 = 1/2.
    assert math.isclose(symmetry(left, right), 0.5 * (1.0 + 200.0 / 240.0))
    assert math.isclose(convergence(left, right, SIZE), 1.0)
    assert math.isclose(pair_reliability(left, right, SIZE), 0.7 * 0.5 * (1.0 + 200.0 / 240.0))
    nearly_meeting = draw.candidate(draw.through_rows(154.0, 180.0), 0.6, full)  # r = 4 / 40 = 0.1
    assert math.isclose(convergence(left, nearly_meeting, SIZE), 0.5 + 0.5 * 0.1 / 0.25)
    parallel = draw.candidate(draw.through_rows(190.0, 180.0), 0.6, full)  # r = 40 / 40
    assert math.isclose(convergence(left, parallel, SIZE), 1.0)
    diverging = draw.candidate(draw.through_rows(192.0, 180.0), 0.6, full)
    assert math.isclose(convergence(left, diverging, SIZE), 0.5)
    assert math.isclose(symmetry(left, draw.candidate(draw.through_rows(0, 0), 0.6, np.zeros(240, bool))), 0.5)


def test_without_a_prediction_the_most_reliable_pair_wins(draw):
    weak = pair_at(draw, (40.0, 70.0), (30.0, 80.0), (0.6, 0.6))
    strong = pair_at(draw, (230.0, 260.0), (220.0, 270.0), (0.9, 0.9))
    assert choose_pair(weak + strong, SIZE) == tuple(strong)


NESTED = GroupingParams(nest_slack=0.2)


def banded(draw, columns, reliabilities, polarities):
    """Parallel vertical candidates at pixel ``columns`` with their reliabilities and polarities."""
    return [
        dataclasses.replace(draw.candidate(draw.through_rows(u, u), r), polarity=sign)
        for u, r, sign in zip(columns, reliabilities, polarities, strict=True)
    ]


def test_the_outline_of_a_painted_pipe_encloses_its_bands(draw):
    """Dark flanks around a bright crown: the crown's pair is the most reliable, the outline is the pipe."""
    lines = banded(draw, (100.0, 110.0, 130.0, 140.0), (0.8, 0.95, 0.95, 0.8), (-1, 1, -1, 1))
    crown = (lines[1], lines[2])
    assert choose_pair(lines, SIZE) == crown  # the paper's choice: the highest Delta R
    assert choose_pair(lines, SIZE, params=NESTED) == (lines[0], lines[3])
    # Below the slack the outline is too weak to be taken.
    weak = banded(draw, (100.0, 110.0, 130.0, 140.0), (0.5, 0.95, 0.95, 0.5), (-1, 1, -1, 1))
    assert choose_pair(weak, SIZE, params=NESTED) == (weak[1], weak[2])


def test_an_enclosing_pair_must_run_parallel_to_the_best_one(draw):
    lines = banded(draw, (100.0, 110.0, 130.0, 140.0), (0.8, 0.95, 0.95, 0.8), (-1, 1, -1, 1))
    tilted = dataclasses.replace(draw.candidate(draw.through_rows(140.0, 150.0), 0.8), polarity=1)  # 2.4 deg off
    pairs = compatible_pairs([*lines[:3], tilted], SIZE)
    best = max(pairs, key=lambda pair: pair.reliability)
    assert (best.left, best.right) == (lines[1], lines[2])
    assert choose_pair([*lines[:3], tilted], SIZE, params=NESTED) == (lines[1], lines[2])
    assert choose_pair([*lines[:3], tilted], SIZE, params=GroupingParams(nest_slack=0.2, nest_max_angle=0.05)) == (
        lines[0],
        tilted,
    )
    assert all(encloses(pair, pair, 0.0) for pair in pairs)
    assert outline(pairs, best, GroupingParams()) is best


def test_a_prediction_picks_the_nearby_weaker_pair_over_a_stronger_far_one(draw):
    weak = pair_at(draw, (40.0, 70.0), (30.0, 80.0), (0.6, 0.6))
    strong = pair_at(draw, (230.0, 260.0), (220.0, 270.0), (0.9, 0.9))
    near_weak = (43.0, 72.0, 28.0, 84.0)
    assert choose_pair(weak + strong, SIZE, near_weak) == tuple(weak)
    assert choose_pair(weak + strong, SIZE, np.array(near_weak)) == tuple(weak)
    # Nothing within the gate: no measure.
    assert choose_pair(weak + strong, SIZE, (140.0, 170.0, 130.0, 180.0)) is None
    assert choose_pair(weak + strong, SIZE, (140.0, 170.0, 130.0, 180.0), GroupingParams(gate_px=120.0)) is not None
    # Pairs below min_pair_reliability do not compete, however near: here the weak pair (Delta R 0.6) and the
    # pairs mixing a weak and a strong line (0.75); the strong pair is then the only one left.
    strict = GroupingParams(min_pair_reliability=0.8)
    assert choose_pair(weak + strong, SIZE, near_weak, strict) is None
    wide = GroupingParams(min_pair_reliability=0.8, gate_px=500.0)
    assert choose_pair(weak + strong, SIZE, near_weak, wide) == tuple(strong)


def test_with_the_predictions_covariance_the_gate_is_mahalanobis(draw):
    weak = pair_at(draw, (40.0, 70.0), (30.0, 80.0), (0.6, 0.6))
    strong = pair_at(draw, (230.0, 260.0), (220.0, 270.0), (0.9, 0.9))
    between = (140.0, 170.0, 130.0, 180.0)
    # 100 px from either pair: rejected when the prediction is sure (10 px), taken when it is not (60 px).
    assert choose_pair(weak + strong, SIZE, between, spread=np.diag([100.0] * 4)) is None
    assert choose_pair(weak + strong, SIZE, between, spread=np.diag([3600.0] * 4)) is not None
    # Uncertain along one direction only (all four abscissae shifting together), the pair shifted that way wins
    # over a nearer one in pixels that is not.
    shift = np.ones(4) / 2.0
    along = 10.0 * np.eye(4) + 1e5 * np.outer(shift, shift)
    shifted = pair_at(draw, (140.0, 170.0), (130.0, 180.0), (0.8, 0.8))
    narrower = pair_at(draw, (48.0, 62.0), (38.0, 72.0), (0.8, 0.8))
    assert choose_pair(shifted + narrower, SIZE, (45.0, 75.0, 35.0, 85.0), spread=along) == tuple(shifted)
    assert choose_pair(shifted + narrower, SIZE, (45.0, 75.0, 35.0, 85.0)) == tuple(narrower)


def test_no_lines_give_no_pair():
    assert choose_pair([], SIZE) is None
    assert choose_pair([], SIZE, (1.0, 2.0, 3.0, 4.0)) is None


@pytest.mark.parametrize(
    "predicted",
    [(1.0, 2.0, math.nan, 4.0), (1.0, 2.0, 3.0), (1.0, 2.0, 3.0, math.inf), "abcd", ((1.0, 2.0), (3.0, 4.0))],
    ids=["nan", "three", "inf", "text", "matrix"],
)
def test_bad_predictions_are_refused(draw, predicted):
    with pytest.raises(ValueError, match="predicted"):
        choose_pair(pair_at(draw, (40.0, 70.0), (30.0, 80.0)), SIZE, predicted)


@settings(max_examples=150, deadline=None)
@given(
    tops=st.tuples(st.floats(-50.0, 370.0), st.floats(-50.0, 370.0)),
    bottoms=st.tuples(st.floats(-50.0, 370.0), st.floats(-50.0, 370.0)),
    reliabilities=st.tuples(st.floats(0.0, 1.0), st.floats(0.0, 1.0)),
)
def test_compatible_pairs_converge_upwards_and_score_in_the_unit_interval(draw, tops, bottoms, reliabilities):
    lines = pair_at(draw, tops, bottoms, reliabilities)
    for pair in compatible_pairs(lines, SIZE):
        i1, i2, i3, i4 = pair.abscissae
        assert i3 < i4 and i1 < i2 and i2 - i1 <= i4 - i3 + 4.2
        assert 0.0 <= pair.reliability <= 0.5 * sum(reliabilities) + 1e-12
