"""Tests of fitting the cable's borders to the cable region."""

from __future__ import annotations

import math

import cv2
import numpy as np
import pytest
from trackbench_texture.borders import cable_strip, fit_borders, ransac_line

from benchmark.modalities.camera.geometry import cable_borders, score_line_pair
from benchmark.modalities.camera.model import CableState
from benchmark.model import Outcome

SIZE = (160, 120)
LIMITS = dict(
    inlier_px=1.0, trials=200, min_length_share=0.5, min_inlier_share=0.3, min_width_px=5.0, max_width_px=120.0,
    max_skew=math.radians(10.0),
)


def _outline(state: CableState, spill: float = 12.0) -> tuple[np.ndarray, np.ndarray]:
    """The border pixels of a cable and a strip reaching ``spill`` px beyond them, both ``(H, W)``."""
    width, height = SIZE
    u = np.arange(width) - (width - 1) / 2.0
    v = (height - 1) / 2.0 - np.arange(height)
    x, y = np.meshgrid(u, v)
    distances = []
    for line in cable_borders(state):
        distances.append((x - line.x0) * line.dy - (y - line.y0) * line.dx)
    left, right = distances
    inside = np.sign(left) != np.sign(right)
    near = np.minimum(np.abs(left), np.abs(right))
    edges = (near <= 0.5).astype(np.float32)
    return edges, inside | (near < spill)


def _outcome(estimate: CableState | None, truth: CableState) -> Outcome:
    return score_line_pair(None if estimate is None else cable_borders(estimate), cable_borders(truth), SIZE)


def test_ransac_finds_a_line_among_outliers():
    rng = np.random.default_rng(0)
    along = np.arange(100.0)
    across = 0.2 * along + 30.0
    across[::3] = rng.uniform(0.0, 100.0, 34)
    line, inliers = ransac_line(along, across, 1.0, 100, np.random.default_rng(1))
    assert line.slope == pytest.approx(0.2, abs=0.01) and line.intercept == pytest.approx(30.0, abs=0.5)
    assert inliers.sum() >= 66


def test_ransac_needs_two_points_on_two_scan_lines():
    rng = np.random.default_rng(0)
    assert ransac_line(np.array([3.0]), np.array([4.0]), 1.0, 10, rng) is None
    assert ransac_line(np.array([3.0, 3.0]), np.array([4.0, 9.0]), 1.0, 10, rng) is None


def test_the_strip_is_the_part_that_spans_the_image():
    mask = np.zeros((120, 160), bool)
    mask[10:110, 70:90] = True
    mask[5:45, 5:60] = True
    strip = cable_strip(mask, 100)
    assert strip is not None and strip.by_rows
    assert strip.mask.sum() == 100 * 20
    assert cable_strip(mask, 5000) is None


def test_a_lying_strip_is_scanned_by_columns():
    mask = np.zeros((120, 160), bool)
    mask[50:70, 5:155] = True
    strip = cable_strip(mask, 100)
    assert not strip.by_rows
    assert strip.mask.shape == (160, 120)


def test_borders_are_fitted_along_the_strip():
    for truth in (
        CableState(10.0, math.radians(12.0), 24.0, math.radians(1.0)),
        CableState(-20.0, math.radians(-8.0), 30.0, 0.0),
        CableState(5.0, math.radians(80.0), 20.0, math.radians(0.5)),
    ):
        edges, region = _outline(truth)
        strip = cable_strip(region, 400)
        estimate = fit_borders(strip, edges, np.random.default_rng(0), **LIMITS)
        assert _outcome(estimate, truth) is Outcome.CORRECT, truth


def test_clutter_in_the_strip_does_not_move_the_borders():
    truth = CableState(0.0, math.radians(5.0), 26.0, math.radians(0.5))
    edges, region = _outline(truth)
    rng = np.random.default_rng(5)
    for _ in range(25):
        u, v = rng.integers(0, 160), rng.integers(0, 120)
        cv2.line(edges, (int(u), int(v)), (int(u + rng.integers(-6, 7)), int(v + rng.integers(-6, 7))), 1.0, 1)
    estimate = fit_borders(cable_strip(region, 400), edges, np.random.default_rng(0), **LIMITS)
    assert _outcome(estimate, truth) is Outcome.CORRECT


def test_a_region_that_is_not_cable_shaped_gives_no_detection():
    rng = np.random.default_rng(0)
    blob = np.zeros((120, 160), bool)
    cv2.circle(blob.view(np.uint8), (80, 60), 35, 1, -1)
    noise = (rng.random((120, 160)) < 0.2).astype(np.float32)
    assert fit_borders(cable_strip(blob, 400), noise, rng, **LIMITS) is None
    short = np.zeros((120, 160), bool)
    short[70:118, 60:100] = True
    edges, _ = _outline(CableState(0.0, 0.0, 30.0, 0.0))
    assert fit_borders(cable_strip(short, 400), edges, rng, **LIMITS) is None


def test_implausible_widths_and_skews_give_no_detection():
    for truth, limit in (
        (CableState(0.0, 0.0, 26.0, 0.0), {"max_width_px": 20.0}),
        (CableState(0.0, 0.0, 26.0, 0.0), {"min_width_px": 30.0}),
        (CableState(0.0, 0.0, 40.0, math.radians(6.0)), {"max_skew": math.radians(3.0)}),
    ):
        edges, region = _outline(truth)
        assert fit_borders(cable_strip(region, 400), edges, np.random.default_rng(0), **{**LIMITS, **limit}) is None
        assert fit_borders(cable_strip(region, 400), edges, np.random.default_rng(0), **LIMITS) is not None


def test_parallel_pairing_finds_a_wide_cable_whose_region_holds_two_strips():
    # A cable wider than the texture neighbourhood: the cable class marks a
    # band along each border, not its inside.  The strip is one band; the
    # side-by-side reading needs both borders in it, the parallel pair does not.
    truth = CableState(4.0, math.radians(6.0), 70.0, math.radians(0.5))
    edges, _ = _outline(truth, spill=0.0)
    width, height = SIZE
    x, y = np.meshgrid(np.arange(width) - (width - 1) / 2.0, (height - 1) / 2.0 - np.arange(height))
    bands = np.zeros((height, width), bool)
    for line in cable_borders(truth):
        bands |= np.abs((x - line.x0) * line.dy - (y - line.y0) * line.dx) < 8.0
    strip = cable_strip(bands, 400)
    assert strip is not None and strip.mask.sum() < bands.sum()
    rng = np.random.default_rng(0)
    assert _outcome(fit_borders(strip, edges, rng, **LIMITS), truth) is not Outcome.CORRECT
    for seed in range(5):
        found = fit_borders(strip, edges, np.random.default_rng(seed), None, bands, "parallel", **LIMITS)
        assert _outcome(found, truth) is Outcome.CORRECT, seed


def test_parallel_pairing_keeps_to_the_width_limits():
    truth = CableState(0.0, math.radians(-4.0), 40.0, 0.0)
    edges, region = _outline(truth)
    strip = cable_strip(region, 400)
    found = fit_borders(strip, edges, np.random.default_rng(0), None, region, "parallel", **LIMITS)
    assert _outcome(found, truth) is Outcome.CORRECT
    narrow = {**LIMITS, "max_width_px": 30.0}
    assert fit_borders(strip, edges, np.random.default_rng(0), None, region, "parallel", **narrow) is None
