"""Tests of the straight segments: fit, grouping in strips and the long-line filter (seeds/000, section 2.3)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from trackbench_segmentation.lines import Segments, _group, group_collinear, select_long

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


def _random_segments(seed: int, count: int) -> Segments:
    """``count`` segments of random pixels, each fitted from its own sums; the pixel count a float, as the tracker's."""
    rng = np.random.default_rng(seed)
    parts = []
    for _ in range(count):
        top = int(rng.integers(0, 200))
        v = np.arange(top, top + int(rng.integers(1, 40)), dtype=np.float64)
        u = rng.uniform(0, 320) + rng.uniform(-0.3, 0.3) * v + rng.normal(0, rng.uniform(0, 2), len(v))
        g = rng.uniform(0, 30, len(v))
        parts.append(Segments(*(np.array([x]) for x in (
            float(len(v)), v.sum(), u.sum(), (v * v).sum(), (u * v).sum(), (u * u).sum(), g.sum(), v[0], v[-1]))))
    return Segments.concatenate(parts)


def _joined_by_bincount(segments: Segments, labels: np.ndarray) -> Segments:
    """The groups' fields as first written: ``np.bincount`` sums and ``np.minimum.at``/``np.maximum.at`` rows."""
    count = int(labels.max()) + 1
    sums = {
        name: np.bincount(labels, weights=getattr(segments, name), minlength=count)
        for name in ("n", "sv", "su", "svv", "suv", "suu", "sg")
    }
    v_low, v_high = np.full(count, np.inf), np.full(count, -np.inf)
    np.minimum.at(v_low, labels, segments.v_low)
    np.maximum.at(v_high, labels, segments.v_high)
    joined = Segments(v_low=v_low, v_high=v_high, **sums)
    return joined.take(np.argsort(-joined.n, kind="stable"))


def _same(first: Segments, second: Segments) -> bool:
    return all(np.array_equal(getattr(first, name), getattr(second, name)) for name in Segments.__dataclass_fields__)


@settings(max_examples=60, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), count=st.integers(1, 60), strip=st.floats(0.5, 30.0), angle=st.floats(0.0, 0.8))
def test_grouping_equals_the_bincount_reading_bit_for_bit(seed, count, strip, angle):
    s = _random_segments(seed, count)
    labels = _group(s.n, s.sv, s.su, s.svv, s.suv, s.suu, s.v_low, s.v_high, np.argsort(-s.n, kind="stable"), strip, angle)
    assert _same(group_collinear(s, strip, angle), _joined_by_bincount(s, labels))


@settings(max_examples=60, deadline=None)
@given(
    seed=st.integers(0, 2**32 - 1),
    count=st.integers(1, 60),
    min_rows=st.floats(0.0, 40.0),
    min_gradient=st.floats(0.0, 30.0),
    max_rms=st.floats(0.01, 3.0),
    max_count=st.integers(2, 20),
)
def test_the_long_line_test_equals_the_segments_properties_bit_for_bit(seed, count, min_rows, min_gradient, max_rms, max_count):
    # The compiled test repeats the properties' operations in their order, so the kept lines are the same.
    s = _random_segments(seed, count)
    keep = np.flatnonzero((s.span >= min_rows) & (s.mean_gradient >= min_gradient) & (s.rms <= max_rms))
    expected = s.take(keep[np.argsort(-s.n[keep], kind="stable")[:max_count]])
    found = select_long(s, min_rows=min_rows, min_gradient=min_gradient, max_rms=max_rms, max_count=max_count)
    assert len(expected) > 0 or len(found) == 0
    assert _same(found, expected)
