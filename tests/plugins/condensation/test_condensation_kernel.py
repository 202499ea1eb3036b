"""Tests of the derivative-of-Gaussian taps (seeds/000, eq. 4.10)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from trackbench_condensation.kernel import dog_sigma, dog_taps


def test_sigma_of_the_thesis_filter_size_is_about_1_6():
    assert round(dog_sigma(11), 1) == 1.6
    assert dog_sigma(5) == pytest.approx(5 / 7)


@given(st.integers(1, 20))
def test_taps_are_odd_with_unit_step_response(radius):
    taps = dog_taps(2 * radius + 1)
    assert taps.shape == (2 * radius + 1,)
    np.testing.assert_allclose(taps, -taps[::-1], atol=1e-15)
    assert taps[radius] == 0.0
    assert np.all(taps[:radius] > 0)
    # A step one grey level brighter on the negative side answers 1.
    step = np.where(np.arange(-radius, radius + 1) < 0, 1.0, 0.0)
    assert float(taps @ step) == pytest.approx(1.0)


def test_taps_follow_eq_4_10_up_to_scale():
    sigma = dog_sigma(11)
    x = np.arange(-5, 6, dtype=float)
    shape = -x / (sigma**3 * math.sqrt(2 * math.pi)) * np.exp(-(x**2) / (2 * sigma**2))
    taps = dog_taps(11)
    np.testing.assert_allclose(taps / taps[4], shape / shape[4])


@pytest.mark.parametrize("size", [0, 1, 2, 4, 10, 7.5])
def test_even_or_tiny_sizes_are_rejected(size):
    with pytest.raises(ValueError, match="odd"):
        dog_taps(size)
