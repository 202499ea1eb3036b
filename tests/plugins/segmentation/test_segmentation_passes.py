"""The compiled passes over a frame's cells equal the one-cell, one-step form bit for bit.

:func:`trackbench_segmentation.passes.pyramid_lines` finds every cell's long
lines in two compiled passes; the oracle is
:func:`trackbench_segmentation.detector.cell_long_lines`, one cell at a time
with the numpy and Python steps of the method.  Its pieces have oracles of
their own: ``numpy.add.reduceat`` for :func:`piece_sums`, and the grouping as first
written, every round scanning every segment (:func:`full_scan_group`), for
:func:`trackbench_segmentation.lines._group`.
"""

from __future__ import annotations

import dataclasses
import math

import numba
import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from trackbench_segmentation.detector import (
    Prediction,
    cell_lines,
    cell_long_lines,
    cell_pyramid,
    detect_pairs,
    edge_gradient,
    pair_rules,
    pyramid_table,
)
from trackbench_segmentation.grey import normalised_grey
from trackbench_segmentation.histogram import gradient_bins, gradient_modulus
from trackbench_segmentation.lines import _NAMES, Segments, _fit, _group, _lines_and_angles
from trackbench_segmentation.pairing import fuse
from trackbench_segmentation.params import PAPER, SegmentationParams
from trackbench_segmentation.contours import _snap
from trackbench_segmentation.passes import cell_table, piece_sums, pyramid_lines, row_extents
from trackbench_segmentation.scaling import frame_params

from benchmark.modalities.camera.model import CableState

SIZE = (96, 72)
PARAMS = {
    "default": SegmentationParams(),
    "paper": SegmentationParams(**PAPER),
    "uneven bins": SegmentationParams(gradient_bin=1.5, projection_sigma=0.0),
    "three levels": SegmentationParams(pyramid_levels=3, snap_px=0, valley_ratio=0.8),
}


def _same(first: Segments, second: Segments) -> bool:
    return len(first) == len(second) and all(np.array_equal(getattr(first, n), getattr(second, n)) for n in _NAMES)


def _band(size: tuple[int, int], centre: float, half_width: float, alpha: float) -> np.ndarray:
    width, height = size
    u = np.arange(width)[None, :] - (width - 1) / 2.0
    v = (height - 1) / 2.0 - np.arange(height)[:, None]
    return np.abs(u * math.cos(alpha) + v * math.sin(alpha) - centre) <= half_width


def _frame(scene, d: float, alpha_deg: float, w: float, contrast: float, seed: int, noise: float) -> np.ndarray:
    truth = CableState(d, math.radians(alpha_deg), w, math.radians(1.0))
    return scene.cable(truth, contrast=contrast, seed=seed, texture=6.0, noise=noise, size=SIZE)


@settings(max_examples=30, deadline=None, suppress_health_check=[HealthCheck.too_slow, HealthCheck.function_scoped_fixture])
@given(
    d=st.floats(-30.0, 30.0),
    alpha_deg=st.floats(-25.0, 25.0),
    w=st.floats(6.0, 30.0),
    contrast=st.sampled_from([-50.0, 40.0]),
    seed=st.integers(0, 1000),
    noise=st.sampled_from([0.0, 3.0, 8.0]),
    variant=st.sampled_from(sorted(PARAMS)),
    searched=st.sampled_from(["whole", "band", "scattered"]),
)
def test_the_pyramid_s_lines_are_the_cells_long_lines(scene, d, alpha_deg, w, contrast, seed, noise, variant, searched):
    image = _frame(scene, d, alpha_deg, w, contrast, seed, noise)
    p = frame_params(PARAMS[variant], SIZE)
    grey = normalised_grey(image, p.smoothing_sigma, p.grey_quantiles)
    modulus = gradient_modulus(grey)
    rows = gradient_bins(modulus, p.gradient_bin, p.gradient_bins)
    min_gradient = edge_gradient(modulus, p)
    prediction = None
    if searched == "band":
        prediction = Prediction(_band(SIZE, d, w, math.radians(alpha_deg)), math.radians(alpha_deg), w)
    elif searched == "scattered":
        prediction = Prediction(np.random.default_rng(seed).random(image.shape) < 0.7, 0.1, w)
    mask, alpha = (None, 0.0) if prediction is None else (prediction.roi, prediction.alpha)
    table = pyramid_table(SIZE, p.pyramid_levels)
    lines, offsets = pyramid_lines(grey, modulus, rows, table, p, mask, alpha, min_gradient)
    for k, cell in enumerate(cell_pyramid(SIZE, p.pyramid_levels)):
        expected = cell_long_lines(grey, modulus, rows, cell, p, prediction, min_gradient)
        assert _same(Segments(*lines[:, offsets[k] : offsets[k + 1]]), expected), f"cell {k}"


@settings(max_examples=15, deadline=None, suppress_health_check=[HealthCheck.too_slow, HealthCheck.function_scoped_fixture])
@given(
    d=st.floats(-30.0, 30.0),
    alpha_deg=st.floats(-20.0, 20.0),
    w=st.floats(8.0, 30.0),
    seed=st.integers(0, 1000),
    variant=st.sampled_from(sorted(PARAMS)),
    tracking=st.booleans(),
)
def test_the_frame_s_pairs_are_those_of_the_one_cell_form(scene, d, alpha_deg, w, seed, variant, tracking):
    # The whole detection, pairs, states, scores and the types of their numbers, against cell_lines and fuse.
    image = _frame(scene, d, alpha_deg, w, -50.0, seed, 3.0)
    params = PARAMS[variant]
    prediction = Prediction(_band(SIZE, d, 2 * w, 0.0), 0.0, w * 1.1) if tracking else None
    p = frame_params(params, SIZE)
    grey = normalised_grey(image, p.smoothing_sigma, p.grey_quantiles)
    modulus = gradient_modulus(grey)
    rows = gradient_bins(modulus, p.gradient_bin, p.gradient_bins)
    min_gradient = edge_gradient(modulus, p)
    cells = cell_pyramid(SIZE, p.pyramid_levels)
    found = [cell_lines(grey, modulus, rows, cell, p, prediction, min_gradient) for cell in cells]
    expected = fuse(
        found, SIZE, pair_rules(p), strip_px=p.strip_px, max_angle=math.radians(p.group_angle_deg),
        min_rows=p.long_share * SIZE[1], min_gradient=min_gradient, max_rms=p.max_rms_px, max_lines=p.max_lines,
        expected_width=None if prediction is None else prediction.width,
    )

    def described(pairs):
        return [(x.first, x.second, x.borders, x.state, x.score, type(x.score), type(x.state.w)) for x in pairs]

    assert described(detect_pairs(image, params, prediction)) == described(expected)


@settings(max_examples=200, deadline=None)
@given(
    values=st.lists(st.floats(-1e6, 1e6), min_size=1, max_size=400),
    cuts=st.lists(st.integers(1, 399), max_size=6, unique=True),
)
def test_piece_sums_are_numpy_s_reduceat(values, cuts):
    values = np.asarray(values)
    firsts = np.array([0] + sorted(c for c in cuts if c < len(values)), dtype=np.int64)
    pieces = np.stack([firsts, np.append(firsts[1:], len(values))], axis=1)
    assert np.array_equal(piece_sums(values, pieces), np.add.reduceat(values, firsts))


@numba.njit(cache=True, nogil=True)
def full_scan_group(n, sv, su, svv, suv, suu, v_low, v_high, order, strip, max_angle):  # pragma: no cover - compiled
    """The grouping as first written: every round scans every segment, in index order (the reference form)."""
    count = n.shape[0]
    a, b, angle = _lines_and_angles(n, sv, su, svv, suv)
    labels = np.full(count, -1, dtype=np.int64)
    groups = 0
    for seed in order:
        if labels[seed] >= 0:
            continue
        labels[seed] = groups
        g = np.array([n[seed], sv[seed], su[seed], svv[seed], suv[seed]])
        joined = True
        while joined:
            joined = False
            ga, gb = _fit(g[0], g[1], g[2], g[3], g[4])
            scale = np.sqrt(1.0 + gb * gb)
            group_angle = np.arctan(gb)
            for j in range(count):
                if labels[j] >= 0 or abs(angle[j] - group_angle) > max_angle:
                    continue
                top = abs(a[j] + b[j] * v_low[j] - ga - gb * v_low[j]) / scale
                bottom = abs(a[j] + b[j] * v_high[j] - ga - gb * v_high[j]) / scale
                if top <= strip and bottom <= strip:
                    labels[j] = groups
                    g[0] += n[j]
                    g[1] += sv[j]
                    g[2] += su[j]
                    g[3] += svv[j]
                    g[4] += suv[j]
                    joined = True
        groups += 1
    return labels


@settings(max_examples=150, deadline=None)
@given(
    count=st.integers(1, 40),
    seed=st.integers(0, 2**16),
    strip=st.floats(0.5, 6.0),
    max_angle_deg=st.floats(0.0, 10.0),
)
def test_groups_grown_over_the_free_segments_are_the_same(scene, count, seed, strip, max_angle_deg):
    rng = np.random.default_rng(seed)
    parts = []
    for _ in range(count):
        top = int(rng.integers(0, 80))
        parts.append(scene.segment(float(rng.uniform(20, 60)), float(rng.normal(0, 0.05)), top,
                                   top + int(rng.integers(2, 60)), wobble=float(rng.uniform(0, 1.5))))
    s = Segments.concatenate(parts)
    order = np.argsort(-s.n, kind="stable")
    args = (s.n, s.sv, s.su, s.svv, s.suv, s.suu, s.v_low, s.v_high, order, strip, math.radians(max_angle_deg))
    assert np.array_equal(_group(*args), full_scan_group(*args))


@settings(max_examples=150, deadline=None)
@given(
    lines=st.lists(
        st.tuples(
            st.sampled_from([-40.0, 0.0, 25.0, math.nan]),  # u at v = 0: few, so that lines coincide
            st.sampled_from([-0.1, -0.05, 0.0, 0.05, 0.1, math.inf, math.nan]),  # du / dv
            st.integers(0, 60),
            st.integers(1, 40),
        ),
        min_size=1,
        max_size=30,
    ),
    strip=st.sampled_from([0.5, 2.0, 1e9]),
    max_angle_deg=st.sampled_from([0.0, 2.0, 3.0, 45.0]),
)
def test_groups_of_lines_with_nan_and_infinite_slopes_are_the_same(lines, strip, max_angle_deg):
    """Coinciding, parallel, NaN and infinite lines: the rounds' angle test lets NaN angles through, as the full scan's."""
    sums = []
    with np.errstate(all="ignore"):  # inf * 0 at row 0: a NaN sum, which the test wants
        for a, b, top, length in lines:
            v = np.arange(top, top + length, dtype=np.float64)
            u = a + b * v if math.isfinite(b) else np.full(length, b)
            sums.append((float(length), v.sum(), u.sum(), (v * v).sum(), (u * v).sum(), (u * u).sum(), v[0], v[-1]))
    n, sv, su, svv, suv, suu, v_low, v_high = (np.array(column) for column in zip(*sums))
    order = np.argsort(-n, kind="stable")
    args = (n, sv, su, svv, suv, suu, v_low, v_high, order, strip, math.radians(max_angle_deg))
    assert np.array_equal(_group(*args), full_scan_group(*args))


@settings(max_examples=100, deadline=None)
@given(shape=st.tuples(st.integers(1, 20), st.integers(1, 20)), seed=st.integers(0, 2**16), share=st.floats(0, 1))
def test_row_extents_span_each_row_s_pixels(shape, seed, share):
    mask = np.random.default_rng(seed).random(shape) < share
    first, stop = row_extents(mask)
    for r in range(shape[0]):
        columns = np.flatnonzero(mask[r])
        assert (first[r], stop[r]) == ((columns[0], columns[-1] + 1) if len(columns) else (0, 0))


@pytest.mark.parametrize("levels", [1, 2, 3, 4])
def test_each_cell_is_the_union_of_the_finest_cells_it_is_counted_from(levels):
    size = (53, 37)
    bounds, parts = pyramid_table(size, levels)
    finest = bounds[len(bounds) - parts.shape[1] :]
    for k, (top, bottom, left, right) in enumerate(bounds):
        cover = np.zeros(size[::-1], int)
        for j in np.flatnonzero(parts[k]):
            t, b, lft, r = finest[j]
            cover[t:b, lft:r] += 1
        expected = np.zeros(size[::-1], int)
        expected[top:bottom, left:right] = 1
        assert np.array_equal(cover, expected)


def test_cells_that_the_finest_do_not_tile_are_counted_on_their_own():
    cells = ((slice(0, 10), slice(0, 10)), (slice(0, 6), slice(0, 4)), (slice(0, 6), slice(4, 10)))
    _, parts = cell_table(cells, 2, (10, 10))
    assert np.array_equal(parts, np.eye(3, dtype=np.int64))


def test_a_walk_that_cannot_climb_is_refused(scene):
    grey = np.zeros((8, 8), np.uint8)
    modulus = np.zeros((8, 8), np.float32)
    with pytest.raises(ValueError, match="alpha"):
        pyramid_lines(grey, modulus, modulus.astype(np.int64), pyramid_table((8, 8), 1),
                      dataclasses.replace(PARAMS["default"], reference_width_px=None), None, math.pi / 2, 4.0)


def _clamped_snap(rows: np.ndarray, cols: np.ndarray, modulus: np.ndarray, radius: int) -> np.ndarray:
    """The snapping's first form: every column of the window clamped to the row."""
    width = modulus.shape[1]
    snapped = np.empty(cols.shape[0], dtype=np.float64)
    for k in range(cols.shape[0]):
        row, col = rows[k], cols[k]
        peak = min(max(col - radius + 1, 0), width - 1)
        largest = smallest = modulus[row, peak]
        for u in range(col - radius + 2, col + radius + 1):
            value = modulus[row, min(max(u, 0), width - 1)]
            if value > largest:
                peak, largest = min(max(u, 0), width - 1), value
            smallest = min(smallest, value)
        if largest == smallest:
            snapped[k] = col + 0.5
            continue
        left = np.float64(modulus[row, max(peak - 1, 0)])
        centre = np.float64(modulus[row, peak])
        right = np.float64(modulus[row, min(peak + 1, width - 1)])
        curvature = left - 2.0 * centre + right
        shift = 0.5 * (left - right) / curvature if curvature < 0 else 0.0
        snapped[k] = peak + min(max(shift, -0.5), 0.5)
    return snapped


@settings(max_examples=300, deadline=None)
@given(
    shape=st.tuples(st.integers(1, 12), st.integers(1, 30)),
    seed=st.integers(0, 2**16),
    radius=st.integers(1, 6),
    levels=st.sampled_from([2, 5, 1000]),
    view=st.booleans(),
)
def test_snapping_without_clamps_inside_the_row_moves_the_points_alike(shape, seed, radius, levels, view):
    # Few levels make flat windows and ties; a strided view of a wider array is read as itself.
    rng = np.random.default_rng(seed)
    wide = (rng.integers(0, levels, (shape[0], 2 * shape[1])) / 4).astype(np.float32)
    modulus = wide[:, ::2] if view else np.ascontiguousarray(wide[:, : shape[1]])
    count = int(rng.integers(0, 40))
    rows = rng.integers(0, shape[0], count).astype(np.int64)
    cols = rng.integers(0, shape[1], count).astype(np.int64)
    assert np.array_equal(_snap(rows, cols, modulus, radius), _clamped_snap(rows, cols, modulus, radius))
