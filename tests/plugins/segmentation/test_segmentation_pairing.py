"""Tests of border pairing and fusion (seeds/000, section 2.3)."""

from __future__ import annotations

import math

import pytest
from trackbench_segmentation.lines import Segments
from trackbench_segmentation.pairing import PairRules, border_pairs, fuse, pair_lines

from benchmark.modalities.camera.geometry import cable_borders, cable_from_borders

SIZE = (320, 240)
RULES = PairRules(max_skew=math.radians(10), min_width=5, max_width=100, min_overlap=0.5, width_tolerance=0.3)


def test_two_parallel_lines_make_a_pair_of_their_width(scene):
    lines = Segments.concatenate([scene.segment(140.0, 0.0, 0, 239), scene.segment(170.0, 0.0, 0, 239)])
    (pair,) = border_pairs(lines, SIZE, RULES)
    assert pair.state.w == pytest.approx(30.0)
    assert pair.state.alpha == pytest.approx(0.0) and pair.state.beta == pytest.approx(0.0)
    assert pair.state.d == pytest.approx(155.0 - 159.5)
    assert pair.score == pytest.approx(480.0)
    assert cable_from_borders(*pair.borders) == pair.state
    assert all(isinstance(line, type(cable_borders(pair.state)[0])) for line in pair.borders)


def test_longer_and_more_parallel_pairs_score_higher(scene):
    lines = Segments.concatenate(
        [scene.segment(100.0, 0.0, 0, 239), scene.segment(130.0, 0.0, 0, 239), scene.segment(200.0, 0.0, 100, 239),
         scene.segment(230.0, 0.05, 100, 239)]
    )
    pairs = border_pairs(lines, SIZE, RULES)
    assert {pairs[0].first, pairs[0].second} == {0, 1}
    assert [p.score for p in pairs] == sorted((p.score for p in pairs), reverse=True)


@pytest.mark.parametrize(
    "second",
    [(103.0, 0.0, 0, 239), (250.0, 0.0, 0, 239), (130.0, 0.5, 0, 239), (130.0, 0.0, 150, 239)],
    ids=["too narrow", "too wide", "not parallel", "rows barely overlap"],
)
def test_implausible_pairs_are_refused(scene, second):
    lines = Segments.concatenate([scene.segment(100.0, 0.0, 0, 119), scene.segment(*second)])
    assert border_pairs(lines, SIZE, RULES) == []


def test_the_expected_width_selects_among_pairs(scene):
    lines = Segments.concatenate([scene.segment(u, 0.0, 0, 239) for u in (100.0, 120.0, 160.0)])
    narrow = border_pairs(lines, SIZE, RULES, expected_width=20.0)
    wide = border_pairs(lines, SIZE, RULES, expected_width=60.0)
    assert [round(p.state.w) for p in narrow] == [20]
    assert [round(p.state.w) for p in wide] == [60]


def test_fusion_joins_a_border_found_in_two_cells(scene):
    top = Segments.concatenate([scene.segment(140.0, 0.1, 0, 119), scene.segment(170.0, 0.1, 0, 119)])
    bottom = Segments.concatenate([scene.segment(140.0, 0.1, 120, 239), scene.segment(170.0, 0.1, 120, 239)])
    pairs = fuse(
        [pair_lines(top, border_pairs(top, SIZE, RULES)), pair_lines(bottom, border_pairs(bottom, SIZE, RULES))],
        SIZE,
        RULES,
        strip_px=2.0,
        max_angle=math.radians(3.0),
        min_rows=200,
        min_gradient=5.0,
        max_rms=1.5,
        max_lines=12,
    )
    assert len(pairs) == 1
    (pair,) = pairs
    assert pair.score == pytest.approx(480.0 * math.cos(0.0))
    assert pair.state.w == pytest.approx(30.0 * math.cos(math.atan(0.1)))


def test_fusion_without_lines_has_no_pair():
    assert fuse([], SIZE, RULES, strip_px=2, max_angle=0.1, min_rows=1, min_gradient=0, max_rms=1, max_lines=3) == []
