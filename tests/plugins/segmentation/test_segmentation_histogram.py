"""Tests of the grey level x gradient histogram segmentation (seeds/000, section 2.3, Fig. 2.4)."""

from __future__ import annotations

import cv2
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays
from trackbench_segmentation.histogram import (
    back_project,
    contour_cut,
    counted_cut,
    frame_gradients,
    gradient_bins,
    gradient_level,
    gradient_modulus,
    grey_projection,
    joint_histogram,
    mountains,
    ranked_bins,
    segment_cell,
)
from trackbench_segmentation.histogram import _select as select_order_statistic

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


def _integer_modulus(image: np.ndarray) -> np.ndarray:
    """The modulus as first written: integer Sobel responses, their squares summed exactly in int32."""
    gx = cv2.Sobel(image, cv2.CV_16S, 1, 0, ksize=3, borderType=cv2.BORDER_REPLICATE).astype(np.int32)
    gy = cv2.Sobel(image, cv2.CV_16S, 0, 1, ksize=3, borderType=cv2.BORDER_REPLICATE).astype(np.int32)
    return np.sqrt((gx * gx + gy * gy).astype(np.float32)) * np.float32(0.25)


@settings(max_examples=60, deadline=None)
@given(
    image=arrays(np.uint8, st.tuples(st.integers(3, 40), st.integers(3, 40)), elements=st.sampled_from([0, 1, 128, 254, 255]))
    | cells,
    transposed=st.booleans(),
)
def test_gradient_modulus_equals_the_integer_sobel_reading_bit_for_bit(image, transposed):
    # The float32 responses and their squares are whole numbers below 2^24, so only the root rounds.
    image = image.T if transposed else image
    expected = _integer_modulus(np.ascontiguousarray(image))
    assert np.array_equal(gradient_modulus(image), expected)


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


def _reference_mountains(projection: np.ndarray, sigma: float, valley_ratio: float) -> np.ndarray:
    """:func:`mountains` written out pixel by pixel, valley by valley."""
    values = np.asarray(projection, dtype=np.float64)
    if sigma > 0:
        radius = int(np.ceil(3.0 * sigma))
        with np.errstate(over="ignore"):
            kernel = np.exp(-0.5 * (np.arange(-radius, radius + 1) / sigma) ** 2)
        values = np.convolve(np.pad(values, radius, mode="edge"), kernel / kernel.sum(), mode="valid")
    signs = np.sign(np.diff(values))
    nonzero = np.flatnonzero(signs)
    cuts = [int(b) + 1 for b, a in zip(nonzero[:-1], nonzero[1:]) if signs[b] < 0 and signs[a] > 0]
    while cuts:
        edges = [0, *cuts, len(values)]
        peaks = [float(values[a:b].max()) for a, b in zip(edges[:-1], edges[1:])]
        worst, worst_ratio = -1, valley_ratio
        for k, cut in enumerate(cuts):
            lower_peak = min(peaks[k], peaks[k + 1])
            ratio = values[cut] / lower_peak if lower_peak > 0 else 1.0
            if ratio > worst_ratio:
                worst, worst_ratio = k, ratio
        if worst < 0:
            break
        del cuts[worst]
    return np.asarray(cuts, dtype=np.int64)


@settings(max_examples=200, deadline=None)
@given(
    projection=arrays(np.int64, 256, elements=st.integers(0, 60)),
    sigma=st.sampled_from([0.0, 0.7, 2.0, 3.0]),
    ratio=st.floats(0.0, 1.0),
)
def test_mountains_equal_the_valley_by_valley_reading(projection, sigma, ratio):
    assert np.array_equal(mountains(projection, sigma, ratio), _reference_mountains(projection, sigma, ratio))


@settings(max_examples=200, deadline=None)
@given(
    values=arrays(np.float32, st.integers(1, 60), elements=st.floats(0, 8, width=32)),
    data=st.data(),
)
def test_two_selected_order_statistics_are_numpys_partition(values, data):
    low = data.draw(st.integers(0, len(values) - 1))
    high = data.draw(st.integers(low, len(values) - 1))
    expected = np.partition(values, [low, high])
    work = values.copy()
    assert select_order_statistic(work, 0, len(work), low) == expected[low]
    assert select_order_statistic(work, low, len(work), high) == expected[high]
    # The values are only moved.
    assert np.array_equal(np.sort(work), np.sort(values))


@settings(max_examples=300, deadline=None)
@given(
    grey=arrays(np.uint8, st.tuples(st.integers(3, 40), st.integers(3, 40)), elements=st.integers(0, 40)),
    share=st.floats(0.05, 1.0),
    bin_width=st.sampled_from([0.25, 0.5, 1.0, 1.5, 2.0, 3.7]),
    n_bins=st.integers(2, 64),
    mask_seed=st.integers(0, 2**16),
)
def test_the_counted_cut_is_the_quantile_cut(grey, share, bin_width, n_bins, mask_seed):
    modulus = gradient_modulus(grey)
    rows = gradient_bins(modulus, bin_width, n_bins)
    mask = np.random.default_rng(mask_seed).random(grey.shape) < 0.6
    mask[0, 0] = True
    for counted in (np.ones(grey.shape, bool), mask):
        totals = np.bincount(rows[counted], minlength=n_bins)
        expected = contour_cut(modulus[counted], share, bin_width, n_bins)
        assert counted_cut(modulus, rows, counted, totals, share, bin_width, n_bins) == expected


@settings(max_examples=60, deadline=None)
@given(grey=cells, sigma=st.floats(0.0, 6.0), ratio=st.floats(0.0, 1.0), mask_seed=st.integers(0, 2**16))
def test_segmentation_equals_the_histogram_quantile_and_mountains(grey, sigma, ratio, mask_seed):
    modulus = gradient_modulus(grey)
    mask = np.random.default_rng(mask_seed).random(grey.shape) < 0.5
    for counted in (None, mask):
        labels = segment_cell(
            grey, modulus, smooth_share=0.5, bin_width=1.0, n_bins=32, sigma=sigma, valley_ratio=ratio, mask=counted
        )
        pixels = np.ones(grey.shape, bool) if counted is None else counted
        if not pixels.any():
            assert not labels.any()
            continue
        histogram = joint_histogram(grey[pixels], modulus[pixels], 1.0, 32)
        cut = contour_cut(modulus[pixels], 0.5, 1.0, 32)
        starts = _reference_mountains(histogram[:cut].sum(axis=0), sigma, ratio)
        assert np.array_equal(labels, back_project(grey, starts))


@settings(max_examples=60, deadline=None)
@given(
    arrays(np.uint8, st.integers(1, 200)),
    st.lists(st.floats(0.0, 1.0), min_size=1, max_size=4),
)
def test_ranked_bins_finds_the_bin_of_each_share_s_order_statistic(values: np.ndarray, shares: list[float]) -> None:
    counts = np.bincount(values, minlength=256)
    expected = [np.sort(values)[int(np.floor(share * (values.size - 1)))] for share in shares]
    assert ranked_bins(counts, shares).tolist() == expected


@settings(max_examples=150, deadline=None)
@given(
    grey=arrays(np.uint8, st.tuples(st.integers(1, 40), st.integers(1, 40))),
    bin_width=st.sampled_from([0.25, 0.5, 1.0, 1.5, 2.0, 3.7, 0.3]),
    n_bins=st.integers(1, 80),
)
def test_the_frame_s_gradients_in_one_pass_are_the_modulus_rows_and_level(grey, bin_width, n_bins):
    modulus, rows, level = frame_gradients(grey, bin_width, n_bins)
    expected = gradient_modulus(grey)
    assert np.array_equal(modulus, expected)
    assert np.array_equal(rows, gradient_bins(expected, bin_width, n_bins))
    assert level == gradient_level(expected)


def test_the_frame_s_gradients_of_the_steepest_steps_and_in_a_strided_view():
    # Black and white checks reach the largest modulus; a view of every other column is read as itself.
    grey = (np.indices((30, 40)).sum(axis=0) % 2 * 255).astype(np.uint8)
    for image in (grey, grey[:, ::2], np.ascontiguousarray(grey.T)):
        modulus, rows, level = frame_gradients(image, 1.0, 64)
        assert np.array_equal(modulus, gradient_modulus(np.ascontiguousarray(image)))
        assert level == gradient_level(modulus)
    with pytest.raises(ValueError, match="bin width"):
        frame_gradients(grey, 0.0, 64)
