"""Tests of the prior on the cable's width around its running mean."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from trackbench_condensation.width import WidthPrior


class Flat:
    """An observation model giving every state the same weight."""

    def likelihood(self, states: np.ndarray, observation: object) -> np.ndarray:
        return np.full(len(states), 5.0)


def states_with_width(widths) -> np.ndarray:
    states = np.zeros((len(widths), 6))
    states[:, 2] = widths
    return states


def test_without_a_width_the_weights_are_the_models():
    prior = WidthPrior(Flat(), spread=0.5, rate=0.05)
    np.testing.assert_array_equal(prior.likelihood(states_with_width([5.0, 30.0, 90.0]), None), 5.0)


def test_the_prior_is_a_gaussian_of_relative_spread_around_the_mean_width():
    prior = WidthPrior(Flat(), spread=0.5, rate=0.05)
    prior.reset(40.0)
    weights = prior.likelihood(states_with_width([40.0, 60.0, 20.0, 80.0]), None)
    np.testing.assert_allclose(weights, 5.0 * np.exp([0.0, -0.5, -0.5, -2.0]))


def test_reported_widths_move_the_mean_at_the_rate():
    prior = WidthPrior(Flat(), spread=0.5, rate=0.25)
    prior.update(20.0)
    assert prior.mean_width == 20.0
    prior.update(40.0)
    assert prior.mean_width == pytest.approx(25.0)


@pytest.mark.parametrize("width", [None, 0.0, -3.0])
def test_reset_without_a_usable_width_drops_the_prior(width):
    prior = WidthPrior(Flat(), spread=0.5, rate=0.05, mean_width=30.0)
    prior.reset(width)
    assert prior.mean_width is None


@pytest.mark.parametrize("spread, rate", [(0.0, 0.05), (-1.0, 0.05), (0.5, 0.0), (0.5, 1.5), (math.nan, 0.05)])
def test_bad_settings_are_rejected(spread, rate):
    with pytest.raises(ValueError, match="width prior"):
        WidthPrior(Flat(), spread=spread, rate=rate)


@settings(max_examples=50, deadline=None)
@given(
    st.floats(1.0, 200.0),
    st.lists(st.floats(-50.0, 300.0), min_size=1, max_size=30),
    st.floats(0.05, 3.0),
)
def test_the_prior_only_lowers_weights_and_keeps_them_finite(mean_width, widths, spread):
    prior = WidthPrior(Flat(), spread=spread, rate=0.05)
    prior.reset(mean_width)
    weights = prior.likelihood(states_with_width(widths), None)
    assert np.all(np.isfinite(weights)) and np.all(weights >= 0) and np.all(weights <= 5.0)
    nearest = int(np.argmin(np.abs(np.array(widths) - mean_width)))
    assert weights[nearest] == weights.max()


@settings(max_examples=100, deadline=None)
@given(
    st.floats(1.0, 500.0),
    st.lists(st.floats(-50.0, 600.0), min_size=1, max_size=40),
    st.floats(0.01, 2.0),
    st.floats(1e-3, 1e4),
)
def test_the_prior_is_the_closed_form_bit_for_bit(mean_width, widths, spread, weight):
    class Constant:
        def likelihood(self, states: np.ndarray, observation: object) -> np.ndarray:
            return np.full(len(states), weight)

    prior = WidthPrior(Constant(), spread=spread, rate=0.05)
    prior.reset(mean_width)
    states = states_with_width(widths)
    z = (states[:, 2] - mean_width) / (spread * mean_width)
    np.testing.assert_array_equal(prior.likelihood(states, None), np.full(len(widths), weight) * np.exp(-0.5 * z * z))
