"""Cleaning and resampling a swath onto a uniform across-track grid (seeds/003, section 2)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays
from trackbench_sonar.profile import MAX_GRID_POINTS, resample_swath, running_median, spike_mask, upper_envelope

from benchmark.errors import DataError
from benchmark.modalities.sonar.model import Swath


def test_grid_is_uniform_on_whole_multiples_between_the_outermost_returns(swaths):
    swath = swaths.make(1.0, slope=0.05)
    profile = resample_swath(swath, 0.05)
    steps = np.diff(profile.across_m)
    assert np.allclose(steps, 0.05)
    assert np.allclose(profile.across_m / 0.05, np.rint(profile.across_m / 0.05))
    assert profile.across_m[0] >= np.nanmin(swath.across_m) - 1e-9
    assert profile.across_m[-1] <= np.nanmax(swath.across_m) + 1e-9
    assert np.nanmax(swath.across_m) - profile.across_m[-1] < 0.05


def test_a_plane_seabed_is_resampled_exactly(swaths):
    profile = resample_swath(swaths.make(None, slope=0.1, altitude=12.0), 0.1)
    assert np.allclose(profile.depth_m, 12.0 + 0.1 * profile.across_m, atol=1e-9)


def test_missing_beams_are_dropped_and_the_gap_bridged(swaths):
    swath = swaths.make(None, slope=-0.05, missing=0.3, seed=4)
    assert np.isnan(swath.depth_m).any()
    profile = resample_swath(swath, 0.05)
    assert np.all(np.isfinite(profile.depth_m))
    assert np.allclose(profile.depth_m, 10.0 - 0.05 * profile.across_m, atol=1e-9)


def test_a_fold_under_the_pipe_is_seen_from_above():
    # In beam order: up the pipe's far flank, over its widest point at x = 1.0, back under it to
    # x = 0.9 on its lower flank, and out onto the seabed.
    across = np.array([0.0, 0.5, 1.0, 0.9, 1.5, 2.0])
    depth = np.array([9.0, 9.0, 9.5, 9.9, 10.0, 10.0])
    profile = resample_swath(Swath(across, depth), 0.1, min_beams=2)
    at = dict(zip(np.round(profile.across_m, 6), profile.depth_m))
    assert at[1.0] == pytest.approx(9.5)
    assert at[0.9] == pytest.approx(9.4)  # on the rising segment, not on the fold at 9.9
    assert at[1.2] == pytest.approx(9.9 + 0.3 / 0.6 * 0.1)  # beyond the widest point: the way out
    assert np.all(np.diff(profile.depth_m[profile.across_m >= 1.0 - 1e-9]) >= -1e-12)


def test_the_envelope_is_the_shallowest_crossing_of_every_segment():
    rng = np.random.default_rng(3)
    across = np.cumsum(rng.normal(0.2, 0.3, 40))
    depth = rng.uniform(5.0, 6.0, 40)
    profile = resample_swath(Swath(across, depth), 0.05, min_beams=2)
    for x, z in zip(profile.across_m[::7], profile.depth_m[::7]):
        crossings = [
            z0 + (x - x0) / (x1 - x0) * (z1 - z0)
            for x0, x1, z0, z1 in zip(across[:-1], across[1:], depth[:-1], depth[1:])
            if min(x0, x1) <= x <= max(x0, x1) and x0 != x1
        ]
        assert z == pytest.approx(min(crossings))


def sorted_envelope(across, depth, grid_m, first, last):
    """The upper envelope as one sort of every (grid point, crossing) pair: the loop's bit-for-bit reference."""
    x0, x1, z0, z1 = across[:-1], across[1:], depth[:-1], depth[1:]
    low = np.maximum(np.ceil(np.minimum(x0, x1) / grid_m).astype(np.int64), first)
    high = np.minimum(np.floor(np.maximum(x0, x1) / grid_m).astype(np.int64), last)
    count = np.maximum(high - low + 1, 0)
    segment = np.repeat(np.arange(x0.size), count)
    index = low[segment] + np.arange(segment.size) - (np.cumsum(count) - count)[segment]
    run = x1[segment] - x0[segment]
    share = np.where(run != 0.0, (index * grid_m - x0[segment]) / np.where(run != 0.0, run, 1.0), 0.0)
    crossing = z0[segment] + np.clip(share, 0.0, 1.0) * (z1[segment] - z0[segment])
    order = np.lexsort((crossing, index))
    winners = order[np.flatnonzero(np.diff(index[order], prepend=first - 1))]
    return crossing[winners], segment[winners]


@settings(max_examples=200, deadline=None)
@given(
    arrays(float, st.integers(2, 40), elements=st.floats(-3.0, 3.0).map(lambda v: round(v, 2))),
    st.data(),
    st.sampled_from([0.05, 0.06, 0.037, 0.1]),
)
def test_the_envelope_equals_the_sorted_form_bit_for_bit(across, data, grid_m):
    depth = data.draw(arrays(float, across.size, elements=st.floats(5.0, 6.0).map(lambda v: round(v, 1))))
    first, last = math.ceil(across.min() / grid_m), math.floor(across.max() / grid_m)
    if last < first:
        return
    envelope, segment = upper_envelope(across, depth, grid_m, first, last)
    expected, expected_segment = sorted_envelope(across, depth, grid_m, first, last)
    np.testing.assert_array_equal(envelope, expected)  # ties (rounded values) keep the first segment
    np.testing.assert_array_equal(segment, expected_segment)


@settings(max_examples=100, deadline=None)
@given(arrays(float, st.integers(1, 30), elements=st.floats(-1e3, 1e3)), st.sampled_from([1, 3, 5, 7]))
def test_running_median_equals_pandas_bit_for_bit(values, window):
    import pandas as pd

    expected = pd.Series(values).rolling(window, center=True, min_periods=1).median().to_numpy()
    np.testing.assert_array_equal(running_median(values, window), expected)


def test_a_spike_along_its_beam_is_removed_but_the_pipe_is_kept(swaths):
    clean = swaths.make(2.0, diameter=0.6, seed=3)
    spiky_across, spiky_depth = clean.across_m.copy(), clean.depth_m.copy()
    beam = 40  # far to port: a shorter range moves the return up and towards nadir
    spiky_across[beam] *= 0.8
    spiky_depth[beam] *= 0.8
    keep = spike_mask(spiky_across, spiky_depth, 5, 0.3)
    assert not keep[beam]
    assert keep.sum() == keep.size - 1
    assert spike_mask(clean.across_m, clean.depth_m, 5, 0.3).all()  # every return on the pipe stays
    cleaned = resample_swath(Swath(spiky_across, spiky_depth), 0.05, spike_m=0.3)
    far = np.abs(cleaned.across_m - spiky_across[beam]) < 1.0
    assert np.all(cleaned.depth_m[far] > 9.5)  # no ramp up to the spike


def test_the_spike_test_compares_ranges_as_depths():
    across = np.zeros(7)
    depth = np.array([10.0, 10.0, 10.0, 10.4, 10.0, 10.0, 10.0])
    assert spike_mask(across, depth, 5, 0.5).all()
    assert not spike_mask(across, depth, 5, 0.3)[3]
    # At 60 deg from nadir a 0.4 m range error is a 0.2 m error in depth.
    angle = math.radians(60.0)
    ranges = np.array([20.0, 20.0, 20.0, 20.4, 20.0, 20.0, 20.0])
    assert spike_mask(ranges * math.sin(angle), ranges * math.cos(angle), 5, 0.25).all()
    assert not spike_mask(ranges * math.sin(angle), ranges * math.cos(angle), 5, 0.15)[3]


def test_running_median_is_centred_and_cut_at_the_ends():
    values = np.array([5.0, 1.0, 3.0, 2.0, 4.0])
    assert np.allclose(running_median(values, 3), [3.0, 3.0, 2.0, 3.0, 3.0])


def test_gaps_are_the_distance_between_the_returns_read(swaths):
    swath = swaths.make(None, seed=0)
    across, depth = swath.across_m.copy(), swath.depth_m.copy()
    lost = slice(118, 124)
    across[lost] = np.nan
    depth[lost] = np.nan
    profile = resample_swath(Swath(across, depth), 0.02)
    inside = (profile.across_m > across[117]) & (profile.across_m < across[124])
    assert np.allclose(profile.gap_m[inside], across[124] - across[117])
    beside = (profile.across_m > across[130]) & (profile.across_m < across[131])
    assert np.allclose(profile.gap_m[beside], across[131] - across[130])


def test_too_few_returns_give_an_empty_profile():
    nothing = Swath(np.full(10, np.nan), np.full(10, np.nan))
    assert resample_swath(nothing, 0.05).is_empty
    few = Swath(np.array([0.0, 1.0, 2.0, np.nan]), np.array([10.0, 10.0, 10.0, np.nan]))
    assert resample_swath(few, 0.05, min_beams=5).is_empty
    assert not resample_swath(few, 0.05, min_beams=3).is_empty
    narrow = Swath(np.array([0.0, 0.01, 0.02, 0.03, 0.04]), np.full(5, 10.0))
    assert resample_swath(narrow, 0.05).is_empty


def test_an_impossible_extent_is_a_data_error():
    far = Swath(np.linspace(-1e9, 1e9, 10), np.full(10, 10.0))
    with pytest.raises(DataError, match="across track"):
        resample_swath(far, 0.05)
    assert 2e9 / 0.05 > MAX_GRID_POINTS


@settings(max_examples=60, deadline=None)
@given(
    arrays(float, st.integers(0, 60), elements=st.floats(-60, 60) | st.just(math.nan)),
    st.randoms(use_true_random=False),
)
def test_any_swath_gives_a_finite_profile(across, random):
    depth = np.array([random.choice([math.nan, random.uniform(0.0, 80.0)]) for _ in across])
    profile = resample_swath(Swath(across, depth), 0.1)
    assert profile.across_m.shape == profile.depth_m.shape
    assert np.all(np.isfinite(profile.depth_m)) and np.all(np.diff(profile.across_m) > 0)
