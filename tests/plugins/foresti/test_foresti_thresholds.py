"""Tests of Canny's thresholds from a frame's own gradients (trackbench_foresti.thresholds)."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp
from trackbench_foresti.edges import canny_from_gradient, smoothed_gradient
from trackbench_foresti.features import FeatureExtractor, FeatureParams
from trackbench_foresti.thresholds import (
    THRESHOLD_RULES,
    fixed_thresholds,
    gradient_percentile,
    percentile_thresholds,
)

SHAPE = (60, 80)


def step(height: float, column: int = 40, base: float = 100.0, noise: float = 0.0, seed: int = 0) -> np.ndarray:
    """A vertical step of ``height`` grey levels at ``column``, with optional pixel noise, ``uint8``."""
    image = np.full(SHAPE, base, np.float64)
    image[:, column:] += height
    image += np.random.default_rng(seed).normal(0.0, noise, SHAPE)
    return np.clip(np.rint(image), 0, 255).astype(np.uint8)


derivatives = hnp.arrays(np.int16, (12, 14), elements=st.integers(-1020, 1020))


@settings(max_examples=60)
@given(gu=derivatives, gv=derivatives, percentile=st.floats(0, 100))
def test_the_percentile_is_the_order_statistic_of_every_second_row_and_column(gu, gv, percentile):
    sample = np.hypot(gu[::2, ::2].astype(float), gv[::2, ::2].astype(float)).ravel()
    expected = np.percentile(sample, percentile, method="lower")
    assert gradient_percentile(gu, gv, percentile) == pytest.approx(expected, rel=1e-12, abs=1e-12)


@settings(max_examples=40)
@given(image=hnp.arrays(np.uint8, (16, 20), elements=st.integers(0, 127)), percentile=st.floats(50, 100))
def test_below_the_ceiling_the_edges_do_not_depend_on_the_contrast(image, percentile):
    """Doubling every grey level doubles the gradients and the thresholds: Canny keeps the same edges."""
    low, high = 20.0, 1e4
    single, double = smoothed_gradient(image, 0.0), smoothed_gradient(image * np.uint8(2), 0.0)
    thresholds = percentile_thresholds(*single, low, high, percentile)
    doubled = percentile_thresholds(*double, low, high, percentile)
    assert doubled == pytest.approx((2 * thresholds[0], 2 * thresholds[1]))
    assert np.array_equal(canny_from_gradient(*single, *thresholds).mask, canny_from_gradient(*double, *doubled).mask)


def test_a_weak_frame_gets_the_pair_scaled_down_and_a_strong_one_keeps_it():
    stripes = np.where((np.arange(SHAPE[1]) // 4) % 2 == 0, 60, 180).astype(np.uint8)
    weak = smoothed_gradient(step(12.0, noise=2.0), 1.0)
    strong = smoothed_gradient(np.tile(stripes, (SHAPE[0], 1)), 1.0)
    low, high = percentile_thresholds(*weak, 20.0, 60.0, 95.0)
    assert 0 < high < 60.0 and low == pytest.approx(high / 3.0)
    assert percentile_thresholds(*strong, 20.0, 60.0, 95.0) == (20.0, 60.0)
    assert fixed_thresholds(*weak, 20.0, 60.0, 95.0) == (20.0, 60.0)
    assert percentile_thresholds(*weak, 0.0, 0.0, 95.0) == (0.0, 0.0)


def test_the_percentile_rule_finds_a_step_the_fixed_pair_misses():
    image = step(12.0, noise=1.0, seed=3)
    fixed = FeatureExtractor(FeatureParams(canny_rule="fixed")).edges(image)
    adaptive = FeatureExtractor(FeatureParams(canny_rule="percentile")).edges(image)
    assert not fixed.mask[:, 38:42].any()
    assert adaptive.mask[2:-2, 38:42].any(axis=1).all()


def test_the_rules_are_registered_by_name_and_validated():
    assert THRESHOLD_RULES == {"fixed": fixed_thresholds, "percentile": percentile_thresholds}
    gu, gv = smoothed_gradient(step(40.0), 1.0)
    with pytest.raises(ValueError, match="percentile"):
        gradient_percentile(gu, gv, 101.0)
    with pytest.raises(ValueError, match="shape"):
        gradient_percentile(gu, gv[:, :-1], 50.0)
    with pytest.raises(ValueError, match="low <= high"):
        percentile_thresholds(gu, gv, 60.0, 20.0, 95.0)
