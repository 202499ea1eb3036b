"""Tests of the movement model, eq. (4.9), and its units."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from trackbench_condensation.movement import diffusion_std, movement_model, transition_matrix

finite = st.floats(-1e3, 1e3)


@given(st.lists(st.tuples(finite, finite, finite, finite, finite, finite), min_size=1, max_size=20))
def test_drift_without_noise_is_exact(rows):
    states = np.array(rows, dtype=float)
    model = movement_model(diffusion_std(0, 0, 0, 0, 0, 0))
    moved = model.propagate(states, np.random.default_rng(0))
    expected = states.copy()
    expected[:, 0] += states[:, 4]
    expected[:, 1] += states[:, 5]
    np.testing.assert_array_equal(moved, expected)


def test_eight_dimensional_drift_moves_width_and_skew_too():
    states = np.array([[1.0, 0.1, 30.0, 0.02, 2.0, 0.01, -0.5, 0.003]])
    model = movement_model(diffusion_std(0, 0, 0, 0, 0, 0, 0, 0))
    moved = model.propagate(states, np.random.default_rng(0))
    np.testing.assert_allclose(moved, [[3.0, 0.11, 29.5, 0.023, 2.0, 0.01, -0.5, 0.003]])


def test_transition_matrices():
    six = transition_matrix(6)
    assert six.shape == (6, 6) and six[0, 4] == six[1, 5] == 1.0 and six.sum() == 8
    eight = transition_matrix(8)
    assert eight[2, 6] == eight[3, 7] == 1.0 and eight.sum() == 12
    with pytest.raises(ValueError):
        transition_matrix(4)


def test_angle_variances_are_converted_from_degrees():
    std = diffusion_std(0.5, 0.01, 4.0, 0.1, 8.0, 0.005)
    np.testing.assert_allclose(std[[0, 2, 4]], np.sqrt([0.5, 4.0, 8.0]))
    np.testing.assert_allclose(std[[1, 3, 5]], np.radians(np.sqrt([0.01, 0.1, 0.005])))


def test_diffusion_has_the_stated_variances():
    model = movement_model(diffusion_std(0.5, 0.01, 4.0, 0.1, 8.0, 0.005))
    moved = model.propagate(np.zeros((200_000, 6)), np.random.default_rng(1))
    variances = moved.var(axis=0)
    rad2 = (math.pi / 180) ** 2
    expected = np.array([0.5, 0.01 * rad2, 4.0, 0.1 * rad2, 8.0, 0.005 * rad2])
    np.testing.assert_allclose(variances, expected, rtol=0.02)


@pytest.mark.parametrize("bad", [(-1.0, 0, 0, 0, 0, 0), (0, float("nan"), 0, 0, 0, 0), (0, 0, 0, 0, 0, 0, 1.0, None)])
def test_bad_variances_are_rejected(bad):
    with pytest.raises(ValueError):
        diffusion_std(*bad)
