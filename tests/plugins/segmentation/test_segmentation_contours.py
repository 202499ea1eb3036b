"""Tests of the contour chains followed up from the bottom (seeds/000, section 2.3)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays
from trackbench_segmentation.contours import contour_mask, follow_chains, label_changes, snap_to_edges, split_chains
from trackbench_segmentation.histogram import back_project


def test_contour_pixels_mark_horizontal_label_changes():
    labels = np.zeros((5, 8), np.uint8)
    labels[:, 3:] = 1
    mask = contour_mask(labels)
    assert mask.shape == labels.shape
    assert np.array_equal(np.flatnonzero(mask.any(axis=0)), [2])
    assert mask[:, 2].all() and not mask[:, -1].any()


def _line_mask(height: int, width: int, bottom_u: float, du_per_row_up: float) -> np.ndarray:
    mask = np.zeros((height, width), bool)
    for k in range(height):
        mask[height - 1 - k, int(round(bottom_u + k * du_per_row_up))] = True
    return mask


def test_a_slanted_line_is_one_chain_climbing_from_the_bottom():
    alpha = math.radians(20.0)
    mask = _line_mask(60, 80, 40.0, -math.tan(alpha))
    rows, cols, starts = follow_chains(mask, alpha, reach=1, max_gap=0, min_rows=5)
    assert starts.tolist() == [0, 60]
    assert rows.tolist() == list(range(59, -1, -1))
    assert np.all(mask[rows, cols])


def test_the_predicted_direction_chooses_between_two_branches():
    mask = np.zeros((30, 40), bool)
    mask[29, 20] = True
    for k in range(1, 30):
        mask[29 - k, 20 + k // 3] = True
        mask[29 - k, 20 - k // 3] = True
    _, right_cols, _ = follow_chains(mask, -math.atan(1 / 3), reach=1, max_gap=0, min_rows=2)
    _, left_cols, _ = follow_chains(mask, math.atan(1 / 3), reach=1, max_gap=0, min_rows=2)
    assert right_cols[29] == 20 + 29 // 3
    assert left_cols[29] == 20 - 29 // 3


def test_gaps_are_bridged_up_to_the_limit_and_short_chains_dropped():
    mask = np.zeros((40, 10), bool)
    mask[:, 4] = True
    mask[18:21, 4] = False
    _, _, bridged = follow_chains(mask, 0.0, reach=1, max_gap=3, min_rows=5)
    _, _, broken = follow_chains(mask, 0.0, reach=1, max_gap=2, min_rows=5)
    assert np.diff(bridged).tolist() == [37]
    assert np.diff(broken).tolist() == [19, 18]
    _, _, none = follow_chains(mask, 0.0, reach=1, max_gap=2, min_rows=20)
    assert none.tolist() == [0]


def test_the_walk_refuses_a_horizontal_prediction():
    with pytest.raises(ValueError, match="90 deg"):
        follow_chains(np.zeros((4, 4), bool), math.pi / 2, reach=1, max_gap=0, min_rows=2)


def test_a_bent_chain_is_cut_at_its_corner():
    mask = np.zeros((40, 40), bool)
    for k in range(20):
        mask[39 - k, 10] = True
        mask[19 - k, 10 + (k + 1) // 2 + 1] = True
    rows, cols, starts = follow_chains(mask, math.radians(-10.0), reach=1, max_gap=0, min_rows=5)
    assert len(starts) == 2
    pieces = split_chains(rows, cols, starts, 1.0)
    assert len(pieces) == 2
    assert pieces[0, 0] == 0 and pieces[-1, 1] == len(rows)
    assert abs(rows[pieces[1, 0]] - 20) <= 2
    straight = split_chains(rows[:20], cols[:20], np.array([0, 20]), 1.0)
    assert straight.tolist() == [[0, 20]]


def test_contour_points_snap_to_the_gradient_ridge():
    modulus = np.zeros((3, 20), np.float32)
    modulus[:, 11] = 10.0
    modulus[:, 10] = 5.0
    modulus[:, 12] = 5.0
    rows, cols = np.array([0, 1, 2]), np.array([8, 9, 15])
    snapped = snap_to_edges(rows, cols, modulus, 3)
    assert snapped[:2] == pytest.approx([11.0, 11.0])
    assert snapped[2] == pytest.approx(15.5)  # a flat window: the point stays
    assert snap_to_edges(rows, cols, modulus, 0) == pytest.approx(cols + 0.5)


def _reference_snap(rows: np.ndarray, cols: np.ndarray, modulus: np.ndarray, radius: int) -> np.ndarray:
    """:func:`snap_to_edges` on whole arrays: window maxima, parabola vertices, flat windows."""
    width = modulus.shape[1]
    window = np.clip(cols[:, None] + np.arange(-radius + 1, radius + 1)[None, :], 0, width - 1)
    values = modulus[rows[:, None], window]
    peak = window[np.arange(len(cols)), np.argmax(values, axis=1)]
    left = modulus[rows, np.maximum(peak - 1, 0)].astype(np.float64)
    centre = modulus[rows, peak].astype(np.float64)
    right = modulus[rows, np.minimum(peak + 1, width - 1)].astype(np.float64)
    curvature = left - 2.0 * centre + right
    with np.errstate(divide="ignore", invalid="ignore"):
        shift = np.where(curvature < 0, 0.5 * (left - right) / curvature, 0.0)
    flat = values.max(axis=1) == values.min(axis=1)
    return np.where(flat, cols + 0.5, peak + np.clip(shift, -0.5, 0.5))


@settings(max_examples=200, deadline=None)
@given(
    modulus=arrays(
        np.float32,
        st.tuples(st.integers(1, 12), st.integers(1, 30)),
        elements=st.sampled_from([0.0, 0.25, 0.9886953, 1.9773906, 2.966086, 7.5, 80.0]),
    ),
    radius=st.integers(1, 8),
    seed=st.integers(0, 2**16),
)
def test_snapping_equals_the_whole_array_reading(modulus, radius, seed):
    rng = np.random.default_rng(seed)
    height, width = modulus.shape
    rows, cols = rng.integers(0, height, 25), rng.integers(0, width, 25)
    assert np.array_equal(snap_to_edges(rows, cols, modulus, radius), _reference_snap(rows, cols, modulus, radius))


@settings(max_examples=100, deadline=None)
@given(
    grey=arrays(np.uint8, st.tuples(st.integers(1, 20), st.integers(1, 20))),
    starts=st.lists(st.integers(1, 255), max_size=6, unique=True).map(sorted),
    seed=st.integers(0, 2**16),
)
def test_label_changes_are_the_contours_of_the_back_projection(grey, starts, seed):
    mask = np.random.default_rng(seed).random(grey.shape) < 0.7
    levels = np.asarray(starts, dtype=np.int64)
    assert np.array_equal(label_changes(grey, levels, mask), contour_mask(back_project(grey, levels)) & mask)
    # Cells cut out of a larger image give the same contours.
    assert np.array_equal(label_changes(grey[:, 1:], levels, mask[:, 1:]), label_changes(grey, levels, mask)[:, 1:])
