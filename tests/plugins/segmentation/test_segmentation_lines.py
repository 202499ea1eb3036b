"""Tests of the straight segments: fit, grouping in strips and the long-line filter (seeds/000, section 2.3)."""

from __future__ import annotations

import math

import pytest
from trackbench_segmentation.lines import Segments, group_collinear, select_long

from benchmark.modalities.camera.geometry import chord_midpoint, model_to_pixel


def test_the_fit_recovers_the_line_and_its_extent(scene):
    s = scene.segment(40.0, 0.25, 10, 109)
    assert s.intercept[0] == pytest.approx(40.0) and s.slope[0] == pytest.approx(0.25)
    assert s.rms[0] == pytest.approx(0.0, abs=1e-6)
    assert (s.v_low[0], s.v_high[0], s.span[0], s.n[0]) == (10, 109, 100, 100)
    assert s.mean_gradient[0] == pytest.approx(20.0)
    assert s.angle[0] == pytest.approx(math.atan(0.25))


def test_rms_measures_the_spread_about_the_line(scene):
    s = scene.segment(40.0, 0.0, 0, 99, wobble=1.0)
    assert s.rms[0] == pytest.approx(1.0, rel=1e-3)


def test_the_model_line_passes_through_the_segment(scene):
    size = (320, 240)
    s = scene.segment(100.0, 0.1, 0, 239)
    line = s.line(0, size)
    x, y = chord_midpoint(line, size)
    u, v = model_to_pixel(x, y, size)
    assert u == pytest.approx(100.0 + 0.1 * v, abs=1e-6)


def test_collinear_pieces_join_and_a_parallel_neighbour_stays_apart(scene):
    pieces = Segments.concatenate(
        [
            scene.segment(50.0, 0.2, 0, 39),
            scene.segment(50.3, 0.2, 60, 119),
            scene.segment(50.0, 0.2, 140, 199),
            scene.segment(62.0, 0.2, 0, 199),
        ]
    )
    grouped = group_collinear(pieces, strip_px=2.0, max_angle=math.radians(3.0))
    assert len(grouped) == 2
    assert grouped.n.tolist() == [200.0, 160.0]
    assert grouped.v_low[1] == 0 and grouped.v_high[1] == 199
    assert grouped.n.sum() == pieces.n.sum()


def test_grouping_respects_the_angle_limit(scene):
    pieces = Segments.concatenate([scene.segment(50.0, 0.0, 0, 99), scene.segment(50.0, 0.01, 100, 110)])
    assert len(group_collinear(pieces, strip_px=2.0, max_angle=math.radians(3.0))) == 1
    assert len(group_collinear(pieces, strip_px=2.0, max_angle=0.0)) == 2


def test_the_long_line_filter_drops_short_weak_and_ragged_lines(scene):
    lines = Segments.concatenate(
        [
            scene.segment(10.0, 0.0, 0, 99),
            scene.segment(30.0, 0.0, 0, 29),
            scene.segment(50.0, 0.0, 0, 99, gradient=2.0),
            scene.segment(70.0, 0.0, 0, 99, wobble=3.0),
            scene.segment(90.0, 0.0, 0, 79),
        ]
    )
    kept = select_long(lines, min_rows=50, min_gradient=5.0, max_rms=1.5, max_count=10)
    assert sorted(kept.intercept.round(3).tolist()) == [10.0, 90.0]
    assert len(select_long(lines, min_rows=50, min_gradient=5.0, max_rms=1.5, max_count=1)) == 1


def test_empty_segments_pass_through():
    empty = Segments.empty()
    assert len(group_collinear(empty, 2.0, 0.1)) == 0
    assert len(select_long(empty, min_rows=1, min_gradient=0, max_rms=1, max_count=3)) == 0
