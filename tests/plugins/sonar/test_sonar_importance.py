"""The importance density: random walk and injected samples (seeds/003, eq. 3 and section 3.4)."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from trackbench_sonar.importance import RandomWalkInjection, uniform_positions


def test_the_walk_moves_every_particle_by_sigma():
    walk = RandomWalkInjection(0.2, 0.0, (-10.0, 10.0))
    start = np.zeros((20000, 1))
    moved = walk.propagate(start, np.random.default_rng(1))
    assert moved.shape == start.shape
    assert np.std(moved) == pytest.approx(0.2, rel=0.03)
    assert abs(np.mean(moved)) < 0.01


@settings(max_examples=50, deadline=None)
@given(st.integers(1, 400), st.floats(0.001, 1.0), st.integers(0, 2**16))
def test_injected_samples_are_uniform_over_the_extent_and_counted(n, fraction, seed):
    walk = RandomWalkInjection(0.0, fraction, (-3.0, 5.0))
    start = np.full((n, 1), 100.0)
    moved = walk.propagate(start, np.random.default_rng(seed))
    injected = moved[:, 0] != 100.0
    assert injected.sum() == walk.injected_count(n) == min(n, max(1, round(fraction * n)))
    assert np.all((moved[injected] >= -3.0) & (moved[injected] < 5.0))


@settings(max_examples=30, deadline=None)
@given(st.floats(-2.0, 2.0), st.floats(0.0, 0.5), st.integers(0, 2**16))
def test_the_drift_shifts_every_walked_particle(drift, sigma, seed):
    start = np.linspace(-3.0, 3.0, 500)[:, None]
    still = RandomWalkInjection(sigma, 0.0, (-10.0, 10.0)).propagate(start, np.random.default_rng(seed))
    moved = RandomWalkInjection(sigma, 0.0, (-10.0, 10.0), drift).propagate(start, np.random.default_rng(seed))
    assert np.allclose(moved - still, drift)


def test_nothing_is_injected_without_a_fraction_or_an_extent():
    start = np.full((50, 1), 2.0)
    assert np.all(RandomWalkInjection(0.0, 0.0, (-1.0, 1.0)).propagate(start, np.random.default_rng(0)) == 2.0)
    assert np.all(RandomWalkInjection(0.0, 0.5, None).propagate(start, np.random.default_rng(0)) == 2.0)


def test_uniform_positions_cover_the_extent():
    positions = uniform_positions(10000, (-2.0, 6.0), np.random.default_rng(3))
    assert positions.shape == (10000, 1)
    assert positions.min() >= -2.0 and positions.max() < 6.0
    assert np.histogram(positions, bins=4, range=(-2.0, 6.0))[0].min() > 2300


@pytest.mark.parametrize(("sigma", "fraction"), [(-0.1, 0.1), (np.inf, 0.1), (0.1, -0.1), (0.1, 1.5)])
def test_bad_settings_are_rejected(sigma, fraction):
    with pytest.raises(ValueError):
        RandomWalkInjection(sigma, fraction)
    with pytest.raises(ValueError, match="drift_m"):
        RandomWalkInjection(0.1, 0.1, None, np.nan)
