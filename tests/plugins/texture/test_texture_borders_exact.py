"""The strip and the RANSAC borders equal those of their straightforward formulations, bit for bit.

:func:`cable_strip` finds the parts of a classified grid on the grid itself
and measures them in pixels, and :func:`ransac_line` counts each line's
support in a compiled loop.  The oracles here are the first formulations:
the parts of the image of pixels, and the residuals of every point from
every line at once.
"""

from __future__ import annotations

import cv2
import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from trackbench_texture.borders import ScanLine, cable_strip, ransac_line


def _first_cable_strip(cable: np.ndarray, min_region_px: int) -> tuple[bool, np.ndarray] | None:
    """``(by_rows, mask)`` of the part that spans the image best, from the labels of the pixels."""
    count, labels, stats, _ = cv2.connectedComponentsWithStats(cable.astype(np.uint8), connectivity=8)
    height, width = cable.shape
    best, best_span = 0, 0.0
    for label in range(1, count):
        if stats[label, cv2.CC_STAT_AREA] < min_region_px:
            continue
        span = max(stats[label, cv2.CC_STAT_HEIGHT] / height, stats[label, cv2.CC_STAT_WIDTH] / width)
        if span > best_span:
            best, best_span = label, span
    if best == 0:
        return None
    region = labels == best
    moments = cv2.moments(region.astype(np.uint8), binaryImage=True)
    by_rows = bool(moments["mu02"] >= moments["mu20"])
    return by_rows, region if by_rows else region.T


def _blocks(draw, count: int) -> np.ndarray:
    """A non-decreasing map of pixels to ``count`` blocks of 1 to 6 pixels each."""
    sizes = draw(st.lists(st.integers(1, 6), min_size=count, max_size=count))
    return np.repeat(np.arange(count), sizes)


@st.composite
def grids(draw) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """A cable mask on a grid (random, or bars that tie in span) and the pixel rows and columns of its blocks."""
    height, width = draw(st.integers(1, 24)), draw(st.integers(1, 24))
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    kind = draw(st.sampled_from(["random", "bars"]))
    if kind == "random":
        cable = rng.random((height, width)) < draw(st.floats(0.1, 0.9))
    else:
        cable = np.zeros((height, width), bool)
        for left in rng.choice(width, size=min(width, int(rng.integers(1, 4))), replace=False):
            cable[:, left] = True
            cable[rng.integers(0, height, 2), left] = False
    return cable, _blocks(draw, height), _blocks(draw, width)


@settings(max_examples=300, deadline=None)
@given(grid=grids(), min_region_px=st.integers(1, 60))
def test_the_strip_of_a_grid_is_the_strip_of_its_pixels(grid, min_region_px):
    cable, rows, cols = grid
    pixels = cable[rows][:, cols]
    expected = _first_cable_strip(pixels, min_region_px)
    for strip in (cable_strip(cable, min_region_px, rows, cols), cable_strip(pixels, min_region_px)):
        if expected is None:
            assert strip is None
        else:
            assert strip.by_rows == expected[0] and np.array_equal(strip.mask, expected[1])


def _first_ransac_line(along, across, inlier_px, trials, rng):
    n = len(along)
    if n < 2:
        return None
    pairs = rng.integers(n, size=(trials, 2))
    d_along = along[pairs[:, 1]] - along[pairs[:, 0]]
    usable = d_along != 0
    if not usable.any():
        return None
    pairs, d_along = pairs[usable], d_along[usable]
    slopes = (across[pairs[:, 1]] - across[pairs[:, 0]]) / d_along
    intercepts = across[pairs[:, 0]] - slopes * along[pairs[:, 0]]
    residual = np.abs(across[None, :] - (slopes[:, None] * along[None, :] + intercepts[:, None]))
    support = (residual <= inlier_px * np.hypot(1.0, slopes)[:, None]).sum(axis=1)
    best = int(np.argmax(support))
    line = ScanLine(float(slopes[best]), float(intercepts[best]))
    for _ in range(2):
        inliers = line.distance(along, across) <= inlier_px
        if inliers.sum() < 2 or np.ptp(along[inliers]) == 0:
            break
        slope, intercept = np.polyfit(along[inliers], across[inliers], 1)
        line = ScanLine(float(slope), float(intercept))
    return line, line.distance(along, across) <= inlier_px


@st.composite
def pixel_points(draw) -> tuple[np.ndarray, np.ndarray]:
    """Pixel coordinates near a few lines plus clutter, as the straight pieces of a strip are."""
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    count = draw(st.integers(0, 400))
    along = rng.integers(0, draw(st.integers(1, 240)), count)
    lines = rng.uniform(-3.0, 3.0, (3, 1)) * along + rng.uniform(0.0, 160.0, (3, 1))
    across = np.rint(lines[rng.integers(0, 3, count), np.arange(count)] + rng.integers(-1, 2, count))
    clutter = rng.random(count) < draw(st.floats(0.0, 0.6))
    across[clutter] = rng.integers(0, 320, int(clutter.sum()))
    return along.astype(np.float64), across.astype(np.float64)


@settings(max_examples=300, deadline=None)
@given(points=pixel_points(), inlier_px=st.sampled_from([0.5, 1.0, 1.5, 2.0]), trials=st.integers(1, 300),
       seed=st.integers(0, 2**32 - 1))
def test_ransac_finds_the_line_and_inliers_of_the_residual_matrix(points, inlier_px, trials, seed):
    along, across = points
    expected = _first_ransac_line(along, across, inlier_px, trials, np.random.default_rng(seed))
    actual = ransac_line(along, across, inlier_px, trials, np.random.default_rng(seed))
    if expected is None:
        assert actual is None
    else:
        assert actual[0] == expected[0] and np.array_equal(actual[1], expected[1])


def test_of_tied_parts_the_first_in_the_labelling_of_the_pixels_wins():
    # OpenCV labels 2 x 2 blocks in raster order: on the grid the left bar's block comes first, in the pixels
    # (two per grid row) the right bar's.
    cable = np.zeros((4, 8), bool)
    cable[1:, 0] = True
    cable[:3, 5] = True
    rows, cols = np.repeat(np.arange(4), 2), np.arange(8)
    pixels = cable[rows][:, cols]
    by_rows, mask = _first_cable_strip(pixels, 1)
    assert mask[0, 5] and not mask[:, 0].any()
    strip = cable_strip(cable, 1, rows, cols)
    assert strip.by_rows == by_rows and np.array_equal(strip.mask, mask)
