"""Tests of what the condensation tracker reports: the too-wide rule and the mode beside the mean."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from trackbench_condensation.detect import LocalAscent
from trackbench_condensation.report import Report, spread_of_distance

from benchmark.filters import ParticleSet

LOW = np.array([-np.inf, -math.pi / 4, 5.0, 0.0])
HIGH = np.array([np.inf, math.pi / 4, 100.0, math.radians(10.0)])
MEAN = np.array([0.0, 0.0, 30.0, math.radians(1.0)])


def particles_in_d(d: np.ndarray) -> ParticleSet:
    states = np.tile(MEAN, (len(d), 1))
    states[:, 0] = d
    return ParticleSet.equally_weighted(states)


def peak_in_d(centre: float, height: float, floor: float):
    """A score with one peak of ``height`` over ``floor`` at ``d = centre``, 4 px wide."""
    return lambda states: floor + height * np.exp(-0.5 * ((states[:, 0] - centre) / 4.0) ** 2)


def test_the_spread_of_a_gaussian_cloud_is_its_standard_deviation():
    d = np.random.default_rng(0).normal(10.0, 3.0, 4000)
    assert spread_of_distance(particles_in_d(d)) == pytest.approx(3.0, rel=0.05)


def test_a_few_particles_proposed_far_off_do_not_widen_the_spread():
    d = np.r_[np.random.default_rng(1).normal(0.0, 1.0, 450), np.full(50, 80.0)]
    assert np.std(d) > 20 and spread_of_distance(particles_in_d(d)) < 1.5


def test_too_wide_compares_the_spread_with_the_limit_and_zero_turns_it_off():
    wide = particles_in_d(np.random.default_rng(2).normal(0.0, 6.0, 1000))
    narrow = particles_in_d(np.random.default_rng(3).normal(0.0, 1.0, 1000))
    assert Report(3.0, None).too_wide(wide, 30.0) and not Report(3.0, None).too_wide(narrow, 30.0)
    assert not Report(0.0, None).too_wide(wide, 30.0)


@settings(max_examples=40, deadline=None)
@given(st.floats(0.5, 10.0), st.floats(0.0, 0.2), st.floats(1.0, 400.0))
def test_the_spread_limit_is_the_floor_or_the_share_of_the_width_whichever_is_larger(floor, share, width):
    report = Report(floor, None, spread_share=share)
    limit = report.spread_limit(width)
    assert limit == max(floor, share * width)
    cloud = particles_in_d(np.random.default_rng(4).normal(0.0, 1.0, 2000))
    spread = spread_of_distance(cloud)
    assert report.too_wide(cloud, width) == (spread > limit)


def test_a_wide_cable_may_spread_further_before_it_is_too_wide():
    cloud = particles_in_d(np.random.default_rng(5).normal(0.0, 4.0, 2000))
    report = Report(3.0, None, spread_share=0.04)
    assert report.too_wide(cloud, 30.0) and not report.too_wide(cloud, 150.0)


def test_the_peak_is_reported_when_it_clearly_beats_the_mean():
    score = peak_in_d(centre=6.0, height=1000.0, floor=100.0)
    mean_score = float(score(MEAN[None, :])[0])
    state = Report(3.0, 1.2).state(MEAN, mean_score, score, LOW, HIGH)
    assert state[0] == pytest.approx(6.0, abs=0.3)
    np.testing.assert_array_equal(state[1:], MEAN[1:])


def test_the_mean_is_kept_when_the_peak_is_barely_better_or_the_rule_is_off():
    score = peak_in_d(centre=1.0, height=100.0, floor=1000.0)
    mean_score = float(score(MEAN[None, :])[0])
    assert float(score(np.array([[1.0, *MEAN[1:]]]))[0]) / mean_score < 1.2
    np.testing.assert_array_equal(Report(3.0, 1.2).state(MEAN, mean_score, score, LOW, HIGH), MEAN)
    clear = peak_in_d(centre=6.0, height=1000.0, floor=100.0)
    np.testing.assert_array_equal(Report(3.0, None).state(MEAN, 100.0, clear, LOW, HIGH), MEAN)


@settings(max_examples=40, deadline=None)
@given(st.floats(-20.0, 20.0), st.floats(1.0, 1e4), st.floats(0.0, 1e4), st.floats(1.0, 3.0))
def test_the_reported_state_never_scores_below_the_mean(centre, height, floor, gain):
    score = peak_in_d(centre, height, floor)
    mean_score = float(score(MEAN[None, :])[0])
    state = Report(3.0, gain, LocalAscent()).state(MEAN, mean_score, score, LOW, HIGH)
    reported = float(score(state[None, :])[0])
    assert reported >= mean_score
    assert np.array_equal(state, MEAN) or reported >= gain * mean_score
