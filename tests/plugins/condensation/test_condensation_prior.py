"""Tests of the initial particle sets (seeds/000, section 4.3, eq. 4.1, Table 5.2)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from trackbench_condensation.prior import InitLimits, particles_at, uniform_particles

from benchmark.modalities.camera.model import UNKNOWN_CABLE, CableState


@pytest.mark.parametrize("dims", [6, 8])
def test_uniform_particles_fill_the_table_5_2_box(dims):
    states = uniform_particles(20_000, dims, InitLimits(), np.random.default_rng(0))
    assert states.shape == (20_000, dims)
    low = [-150, -math.radians(45), 5, 0, -1, -math.radians(0.1)]
    high = [150, math.radians(45), 100, math.radians(10), 1, math.radians(0.1)]
    for column in range(6):
        values = states[:, column]
        span = high[column] - low[column]
        assert values.min() >= low[column] and values.max() <= high[column]
        # Uniform: both ends are reached and the mean is in the middle.
        assert values.min() < low[column] + 0.01 * span and values.max() > high[column] - 0.01 * span
        assert values.mean() == pytest.approx(0.5 * (low[column] + high[column]), abs=0.02 * span)
    assert np.all(states[:, 6:] == 0)


def test_same_generator_state_gives_the_same_particles():
    a = uniform_particles(10, 6, InitLimits(), np.random.default_rng(5))
    b = uniform_particles(10, 6, InitLimits(), np.random.default_rng(5))
    np.testing.assert_array_equal(a, b)


def test_particles_at_a_known_state_have_zero_velocities():
    state = CableState(3.0, 0.1, 25.0, 0.02)
    states = particles_at(state, 7, 8)
    np.testing.assert_array_equal(states, np.tile([3.0, 0.1, 25.0, 0.02, 0, 0, 0, 0], (7, 1)))
    with pytest.raises(ValueError, match="unknown"):
        particles_at(UNKNOWN_CABLE, 7, 6)


@pytest.mark.parametrize("limits", [{"w_px": (10.0, 5.0)}, {"d_px": (0.0, float("inf"))}, {"alpha_deg": (1.0,)}])
def test_bad_limits_are_rejected(limits):
    with pytest.raises(ValueError, match="init limits"):
        InitLimits(**limits)


@settings(max_examples=50, deadline=None)
@given(st.floats(0.1, 10.0), st.floats(0.1, 10.0))
def test_scaling_the_limits_scales_only_the_pixel_ranges(first, second):
    table = InitLimits()
    scaled = table.scaled(first).scaled(second)
    for name in ("d_px", "w_px", "v_d_px"):
        np.testing.assert_allclose(getattr(scaled, name), np.multiply(getattr(table, name), first * second))
    for name in ("alpha_deg", "beta_deg", "v_alpha_deg"):
        assert getattr(scaled, name) == getattr(table, name)


@pytest.mark.parametrize("factor", [0.0, -2.0, float("nan"), float("inf")])
def test_a_bad_scale_factor_is_rejected(factor):
    with pytest.raises(ValueError, match="scale factor"):
        InitLimits().scaled(factor)
