"""The compiled pairing equals the one-pair-at-a-time form bit for bit.

:func:`cells_pair_lines` and :func:`fuse_pairs` rank border pairs in
compiled passes, with CPython's ``math.hypot`` and the steps of
:func:`cable_from_borders` (:mod:`benchmark.modalities.camera.geometry_kernels`,
tested in tests/benchmark/modalities/camera/test_geometry_kernels.py); :func:`may_pass`
passes over the pairs that cannot be found before :func:`border_pairs`
builds them.  The oracles are :func:`border_pairs`, :func:`pair_lines` and
:func:`fuse` as first written, and the standard library.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from trackbench_segmentation import pairing
from trackbench_segmentation.lines import Segments
from trackbench_segmentation.pairing import (
    PairRules,
    border_pairs,
    cells_pair_lines,
    fuse,
    fuse_pairs,
    pair_lines,
)

SIZE = (160, 120)


def _cell(scene, rng: np.random.Generator, count: int) -> Segments:
    parts = []
    for _ in range(count):
        top = int(rng.integers(0, 60))
        parts.append(scene.segment(float(rng.uniform(10, 150)), float(rng.normal(0, 0.08)), top,
                                   top + int(rng.integers(1, 60)), gradient=float(rng.uniform(1, 30)),
                                   wobble=float(rng.uniform(0, 1.0))))
    return Segments.concatenate(parts) if parts else Segments.empty()


rules = st.builds(
    PairRules,
    max_skew=st.floats(0.01, 0.4),
    min_width=st.floats(0.0, 20.0),
    max_width=st.floats(20.0, 160.0),
    min_overlap=st.floats(0.0, 1.0),
    width_tolerance=st.floats(0.05, 1.0),
)


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(
    seed=st.integers(0, 2**16),
    counts=st.lists(st.integers(0, 9), min_size=1, max_size=5),
    rule=rules,
    expected=st.one_of(st.none(), st.floats(3.0, 120.0)),
    pairs_per_cell=st.integers(1, 4),
)
def test_each_cell_s_best_pair_lines_in_one_pass_are_the_one_cell_form_s(scene, seed, counts, rule, expected,
                                                                          pairs_per_cell):
    rng = np.random.default_rng(seed)
    cells = [_cell(scene, rng, count) for count in counts]
    joined = Segments.concatenate(cells)
    lines = np.stack([getattr(joined, name) for name in pairing._FIELDS]) if len(joined) else np.empty((9, 0))
    offsets = np.cumsum([0] + [len(cell) for cell in cells])
    got = cells_pair_lines(lines, offsets, SIZE, rule, expected, pairs_per_cell)
    oracle = Segments.concatenate(
        [pair_lines(cell, border_pairs(cell, SIZE, rule, expected)[:pairs_per_cell]) for cell in cells]
    )
    assert len(got) == len(oracle)
    assert all(np.array_equal(getattr(got, name), getattr(oracle, name)) for name in pairing._FIELDS)


def _described(pairs):
    return [(x.first, x.second, x.borders, x.state, x.score, type(x.score), type(x.state.w)) for x in pairs]


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(
    seed=st.integers(0, 2**16),
    count=st.integers(0, 14),
    rule=rules,
    expected=st.one_of(st.none(), st.floats(3.0, 120.0)),
    min_rows=st.floats(0.0, 60.0),
    max_lines=st.integers(2, 12),
)
def test_the_compiled_fusion_is_fuse(scene, seed, count, rule, expected, min_rows, max_lines):
    lines = _cell(scene, np.random.default_rng(seed), count)
    limits = dict(strip_px=2.0, max_angle=math.radians(3.0), min_rows=min_rows, min_gradient=5.0, max_rms=1.5,
                  max_lines=max_lines, expected_width=expected)
    assert _described(fuse_pairs(lines, SIZE, rule, **limits)) == _described(fuse([lines], SIZE, rule, **limits))


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(
    seed=st.integers(0, 2**16),
    count=st.integers(2, 12),
    rule=rules,
    expected=st.one_of(st.none(), st.floats(-5.0, 120.0).filter(lambda e: e != 0)),
)
def test_passing_over_the_pairs_that_cannot_pass_finds_the_same_pairs(scene, seed, count, rule, expected, monkeypatch):
    lines = _cell(scene, np.random.default_rng(seed), count)
    found = _described(border_pairs(lines, SIZE, rule, expected))
    with monkeypatch.context() as patch:
        patch.setattr(pairing, "may_pass", lambda a, b, low, high, first, second, *rest: np.ones(len(first), bool))
        assert _described(border_pairs(lines, SIZE, rule, expected)) == found


@pytest.mark.parametrize("expected", [0.0, 5e-324], ids=["zero", "its agreement's divisor rounds to zero"])
def test_an_expected_width_that_divides_by_zero_gives_the_one_pair_form_s_pairs(scene, expected):
    lines = Segments.concatenate([scene.segment(40.0, 0.0, 0, 100), scene.segment(70.0, 0.0, 0, 100),
                                  scene.segment(70.0, 0.0, 0, 100)])
    rule = PairRules(max_skew=0.2, min_width=0.0, max_width=100.0, min_overlap=0.5, width_tolerance=0.3)
    fields = np.stack([getattr(lines, name) for name in pairing._FIELDS])
    with np.errstate(divide="ignore", invalid="ignore"):
        got = cells_pair_lines(fields, np.array([0, 3]), SIZE, rule, expected, 3)
        oracle = pair_lines(lines, border_pairs(lines, SIZE, rule, expected)[:3])
        assert all(np.array_equal(getattr(got, name), getattr(oracle, name)) for name in pairing._FIELDS)
        limits = dict(strip_px=2.0, max_angle=0.05, min_rows=1.0, min_gradient=0.0, max_rms=2.0, max_lines=12)
        assert _described(fuse_pairs(lines, SIZE, rule, expected_width=expected, **limits)) == _described(
            fuse([lines], SIZE, rule, expected_width=expected, **limits)
        )
