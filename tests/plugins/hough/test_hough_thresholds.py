"""Tests of the edge-threshold rules: the paper's fixed step and the frame's own median."""

from __future__ import annotations

import typing

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from trackbench_hough.edges import crossing_steps, log_response, zero_crossings
from trackbench_hough.params import EdgeRule, HoughParams
from trackbench_hough.thresholds import EDGE_THRESHOLDS, MEDIAN_STRIDE, fixed_step, median_step


def test_every_declared_rule_has_a_function():
    assert set(EDGE_THRESHOLDS) == set(typing.get_args(EdgeRule))


def test_the_fixed_rule_ignores_the_frame():
    params = HoughParams(edge_rule="step", edge_step=7.5)
    response = log_response(np.random.default_rng(0).normal(100.0, 30.0, (20, 30)), 2.0)
    assert fixed_step(response, 2.0, params) == 7.5 == fixed_step(np.zeros((4, 4)), 2.0, params)


def test_the_median_rule_is_a_multiple_of_the_median_crossing():
    response = log_response(np.random.default_rng(1).normal(100.0, 10.0, (40, 50)), 2.0)
    median = float(np.median(crossing_steps(response, 2.0, MEDIAN_STRIDE)))
    assert median > 0
    assert median_step(response, 2.0, HoughParams(edge_ratio=2.0)) == 2.0 * median
    assert median_step(np.ones((10, 10), np.float32), 2.0, HoughParams()) == 0.0


@settings(max_examples=15, deadline=None)
@given(gain=st.sampled_from([0.25, 0.5, 2.0, 4.0]), seed=st.integers(0, 2**16))
def test_the_median_rule_keeps_the_same_borders_when_the_grey_levels_scale(gain, seed):
    # A band of 20 grey levels on noise: a murkier or brighter copy loses or gains no border
    # under the median rule, while a fixed step keeps a different set.
    rng = np.random.default_rng(seed)
    image = rng.normal(0.0, 3.0, (60, 80)).astype(np.float32)
    image[:, 30:45] += 20.0
    edges = {}
    for factor in (1.0, gain):
        response = log_response(factor * image, 2.0)
        edges[factor] = zero_crossings(response, 2.0, median_step(response, 2.0, HoughParams()))
    assert np.count_nonzero(edges[1.0] != edges[gain]) <= 0.001 * image.size
    fixed = [zero_crossings(log_response(f * image, 2.0), 2.0, 12.0) for f in (1.0, gain)]
    assert np.count_nonzero(fixed[0]) != np.count_nonzero(fixed[1])
