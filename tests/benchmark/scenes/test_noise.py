"""Noise every scene draws: smoothed Gaussian noise and the table of normal quantiles."""

from __future__ import annotations

import math
import statistics

import numpy as np
import pytest

from benchmark.scenes.noise import gaussian_table, smoothed_noise


def _rng(seed: int = 0) -> np.random.Generator:
    return np.random.default_rng(seed)


def test_smoothed_noise_has_unit_variance_and_the_kernel_correlation() -> None:
    smooth = 2.0
    noise = smoothed_noise(_rng(1), 40000, smooth)
    assert noise.std() == pytest.approx(1.0, abs=0.05)
    lag_one = np.corrcoef(noise[:-1], noise[1:])[0, 1]
    # A Gaussian kernel of std s gives correlation exp(-1 / (4 s^2)) at lag one.
    assert lag_one == pytest.approx(math.exp(-1.0 / (4 * smooth**2)), abs=0.02)


def test_zero_smoothing_is_the_generator_s_white_noise() -> None:
    np.testing.assert_array_equal(smoothed_noise(_rng(3), 50, 0.0), _rng(3).standard_normal(50))
    assert smoothed_noise(_rng(3), 7, 1.5).shape == (7,)


def test_the_gaussian_table_holds_sorted_normal_quantiles() -> None:
    table = gaussian_table(8)
    assert table.shape == (256,) and table.dtype == np.float32 and not table.flags.writeable
    assert np.all(np.diff(table) > 0)
    np.testing.assert_allclose(table, -table[::-1], atol=1e-6)
    assert table[0] == pytest.approx(statistics.NormalDist().inv_cdf(0.5 / 256), rel=1e-6)
    assert gaussian_table(8) is table
