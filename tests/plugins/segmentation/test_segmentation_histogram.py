"""Tests of the grey level x gradient histogram segmentation (seeds/000, section 2.3, Fig. 2.4)."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays
from trackbench_segmentation.histogram import (
    back_project,
    contour_cut,
    gradient_bins,
    gradient_modulus,
    grey_projection,
    joint_histogram,
    mountains,
    segment_cell,
)

cells = arrays(np.uint8, st.tuples(st.integers(3, 24), st.integers(3, 24)))


@settings(max_examples=60, deadline=None)
@given(grey=cells, share=st.floats(0.05, 1.0), bin_width=st.floats(0.25, 8.0), n_bins=st.integers(2, 40))
def test_projection_counts_exactly_the_low_gradient_pixels(grey, share, bin_width, n_bins):
    modulus = gradient_modulus(grey)
    histogram = joint_histogram(grey, modulus, bin_width, n_bins)
    assert histogram.shape == (n_bins, 256)
    assert histogram.sum() == grey.size
    cut = contour_cut(modulus, share, bin_width, n_bins)
    projection = grey_projection(histogram, cut)
    low = gradient_bins(modulus, bin_width, n_bins) < cut
    assert projection.sum() == np.count_nonzero(low)
    # Each grey level's count is that of its low-gradient pixels.
    assert np.array_equal(projection, np.bincount(grey[low], minlength=256))
    # The cut keeps at least the requested share of the pixels as smooth.
    assert np.count_nonzero(low) >= np.floor(share * grey.size)


@settings(max_examples=60, deadline=None)
@given(
    grey=cells,
    sigma=st.floats(0.0, 6.0),
    ratio=st.floats(0.0, 1.0),
    mask_seed=st.integers(0, 2**16),
)
def test_segment_labels_cover_the_cell(grey, sigma, ratio, mask_seed):
    modulus = gradient_modulus(grey)
    mask = np.random.default_rng(mask_seed).random(grey.shape) < 0.5
    for counted in (None, mask):
        labels = segment_cell(
            grey, modulus, smooth_share=0.7, bin_width=1.0, n_bins=32, sigma=sigma, valley_ratio=ratio, mask=counted
        )
        assert labels.shape == grey.shape
        # Every pixel, smooth, contour or outside the mask, gets the label of its grey level's mountain.
        order = np.argsort(grey, axis=None, kind="stable")
        assert np.all(np.diff(labels.ravel()[order].astype(int)) >= 0)
        same_grey = grey.ravel()[order]
        assert np.all(np.diff(labels.ravel()[order].astype(int))[np.diff(same_grey.astype(int)) == 0] == 0)


def test_gradient_modulus_reads_a_step_height():
    image = np.zeros((9, 12), np.uint8)
    image[:, 6:] = 80
    modulus = gradient_modulus(image)
    assert modulus.dtype == np.float32
    assert modulus[4, 5] == pytest.approx(80.0) and modulus[4, 6] == pytest.approx(80.0)
    assert modulus[4, 2] == 0.0 and modulus[4, 9] == 0.0


def _two_hills(first: float, second: float) -> np.ndarray:
    levels = np.arange(256)
    return 1000 * np.exp(-0.5 * ((levels - first) / 8) ** 2) + 600 * np.exp(-0.5 * ((levels - second) / 8) ** 2)


def test_two_hills_split_at_their_valley():
    starts = mountains(_two_hills(60, 160), sigma=2.0, valley_ratio=0.5)
    assert len(starts) == 1 and 95 <= starts[0] <= 125


def test_one_hill_is_one_mountain():
    levels = np.arange(256)
    assert len(mountains(1000 * np.exp(-0.5 * ((levels - 120) / 15) ** 2), sigma=3.0, valley_ratio=0.9)) == 0


def test_a_shallow_valley_is_kept_only_by_a_lenient_ratio():
    hills = _two_hills(100, 124)
    assert len(mountains(hills, sigma=0.0, valley_ratio=1.0)) == 1
    assert len(mountains(hills, sigma=0.0, valley_ratio=0.1)) == 0


def test_back_projection_labels_by_interval():
    grey = np.array([[0, 49, 50, 51], [99, 100, 200, 255]], np.uint8)
    assert back_project(grey, np.array([50, 100])).tolist() == [[0, 0, 1, 1], [1, 2, 2, 2]]
    assert back_project(grey, np.array([], dtype=np.int64)).max() == 0


def test_a_two_tone_cell_segments_into_its_two_regions():
    grey = np.full((40, 40), 60, np.uint8)
    grey[:, 22:] = 170
    grey = grey + np.random.default_rng(3).integers(0, 5, grey.shape).astype(np.uint8)
    labels = segment_cell(
        grey, gradient_modulus(grey), smooth_share=0.7, bin_width=1.0, n_bins=64, sigma=2.0, valley_ratio=0.5
    )
    assert len(np.unique(labels[:, :22])) == 1 and len(np.unique(labels[:, 22:])) == 1
    assert labels[0, 0] != labels[0, 39]


def test_bad_histogram_bins_are_refused():
    with pytest.raises(ValueError, match="bin"):
        joint_histogram(np.zeros((3, 3), np.uint8), np.zeros((3, 3), np.float32), 0.0, 4)
