"""Tests of the outline: from the steepest edges of eq. (4.11) out to the cable's silhouette."""

from __future__ import annotations

import math

import cv2
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from trackbench_condensation.kernel import dog_taps
from trackbench_condensation.measure import border_scores
from trackbench_condensation.silhouette import Silhouette

from benchmark.modalities.camera.model import CableState

SIZE = (320, 240)
TAPS = dog_taps(11)
SPACING = 20.0
OUTLINE = Silhouette(TAPS, SPACING, fraction=0.5, rim_ratio=0.35, rim_reach_px=4.0)


def lit_cylinder(
    d: float, radius: float, lamp_deg: float, background: float = 60.0, seed: int = 0, size: tuple[int, int] = SIZE
) -> np.ndarray:
    """A vertical pipe lit by one lamp, ``float32`` grey levels.

    Across the pipe the grey level is ``30 + 200 max(0, N . L)``: Lambert's
    law with the surface normal ``N`` of the cylinder and a lamp ``lamp_deg``
    to the right of the viewing direction; the seabed around it is
    ``background``.  Eight samples a pixel, a Gaussian blur of 1.2 px and
    pixel noise of 2 grey levels.
    """
    width, height = size
    x = (np.arange(8 * width) + 0.5) / 8 - 0.5 - (width - 1) / 2.0
    u = (x - d) / radius
    inside = np.abs(u) < 1
    lamp = math.radians(lamp_deg)
    facing = u * math.sin(lamp) + np.sqrt(np.clip(1 - u * u, 0, 1)) * math.cos(lamp)
    row = np.where(inside, 30.0 + 200.0 * np.maximum(facing, 0.0), background).reshape(width, 8).mean(axis=1)
    image = cv2.GaussianBlur(np.tile(row, (height, 1)).astype(np.float32), (0, 0), 1.2)
    return image + np.random.default_rng(seed).normal(0.0, 2.0, image.shape).astype(np.float32)


def steepest_edges(image: np.ndarray, d: float, radius: float) -> np.ndarray:
    """The state whose two vertical borders sit on the strongest bright-cable edges inside the outline."""
    insets = np.arange(0.0, radius - 2.0, 0.5)
    left = np.array([[d + o / 2, 0.0, 2 * radius - o, 0.0] for o in insets])
    right = np.array([[d - o / 2, 0.0, 2 * radius - o, 0.0] for o in insets])
    left_counts, _ = border_scores(left, image, TAPS, SPACING, False)
    right_counts, _ = border_scores(right, image, TAPS, SPACING, False)
    inset_left, inset_right = insets[np.argmax(-left_counts[:, 0])], insets[np.argmax(right_counts[:, 1])]
    return np.array([d + (inset_left - inset_right) / 2, 0.0, 2 * radius - inset_left - inset_right, 0.0])


def borders(state: np.ndarray) -> tuple[float, float]:
    return state[0] - state[2] / 2, state[0] + state[2] / 2


@pytest.mark.parametrize(("radius", "lamp_deg"), [(30.0, 0.0), (60.0, 0.0), (60.0, 20.0), (30.0, 20.0)])
def test_a_lit_pipe_is_reported_at_its_outline_not_at_its_steepest_edges(radius, lamp_deg):
    d = 10.0
    image = lit_cylinder(d, radius, lamp_deg)
    edges = steepest_edges(image, d, radius)
    outline = OUTLINE.outline(edges, image)
    truth = (d - radius, d + radius)
    # The shading puts the steepest edge of the unlit (or both) flanks inside the outline ...
    assert max(abs(e - t) for e, t in zip(borders(edges), truth, strict=True)) >= 2.0
    # ... and the outline finds the silhouette within a pixel and a half.
    assert all(abs(o - t) <= 1.5 for o, t in zip(borders(outline), truth, strict=True))
    assert outline[1] == edges[1] and outline[3] == edges[3]


def test_a_shadowed_rim_is_crossed_only_when_the_rim_rule_is_on():
    d, radius = -20.0, 60.0
    image = lit_cylinder(d, radius, lamp_deg=20.0)
    edges = steepest_edges(image, d, radius)
    with_rim = OUTLINE.outline(edges, image)
    without = Silhouette(TAPS, SPACING, rim_ratio=0.0).outline(edges, image)
    assert abs(borders(with_rim)[0] - (d - radius)) <= 1.5
    assert borders(without)[0] - (d - radius) >= 3.0


def test_a_cable_darker_than_the_seabed_is_left_where_it_is():
    d, radius = 10.0, 40.0
    image = lit_cylinder(d, radius, lamp_deg=20.0)
    state = steepest_edges(image, d, radius) + np.array([0.0, 0.01, 0.0, 0.005])
    assert np.any(OUTLINE.outline(state, image) != state)
    np.testing.assert_array_equal(OUTLINE.outline(state, np.float32(255.0) - image), state)


@pytest.mark.parametrize("contrast", [-60.0, 45.0])
def test_a_flat_band_keeps_its_borders(scene, contrast):
    state = CableState(-18.0, math.radians(6.0), 34.0, math.radians(1.0))
    image = scene.draw_cable(state, contrast=contrast)
    outline = OUTLINE.outline(state.as_array(), image)
    assert all(abs(o - t) <= 1.5 for o, t in zip(borders(outline), borders(state.as_array()), strict=True))


@settings(max_examples=25, deadline=None)
@given(st.floats(0.2, 5.0), st.floats(-100.0, 100.0), st.floats(-8.0, 8.0), st.floats(-8.0, 8.0))
def test_the_outline_is_free_of_the_grey_level_scale_and_offset(gain, offset, shift_d, shift_w):
    image = lit_cylinder(5.0, 35.0, lamp_deg=15.0)
    state = np.array([5.0 + shift_d, 0.02, 60.0 + shift_w, 0.01])
    np.testing.assert_allclose(
        OUTLINE.outline(state, np.float32(gain) * image + np.float32(offset)), OUTLINE.outline(state, image), atol=1e-6
    )


@settings(max_examples=40, deadline=None)
@given(
    st.floats(-120.0, 120.0),
    st.floats(-0.6, 0.6),
    st.floats(-50.0, 200.0),
    st.floats(0.0, 0.15),
    st.integers(0, 3),
)
def test_only_d_and_w_move_and_the_width_stays_positive(d, alpha, w, beta, seed):
    image = np.random.default_rng(seed).normal(100.0, 30.0, (SIZE[1], SIZE[0])).astype(np.float32)
    state = np.array([d, alpha, w, beta])
    outline = OUTLINE.outline(state, image)
    assert np.all(np.isfinite(outline))
    assert outline[1] == alpha and outline[3] == beta
    # Either a border moved and the width is at least a pixel, or nothing moved.
    assert outline[2] >= 1.0 or np.array_equal(outline, state)
    if w <= 0:
        np.testing.assert_array_equal(outline, state)


def test_mirroring_the_image_mirrors_the_outline():
    image = lit_cylinder(12.0, 40.0, lamp_deg=25.0)
    # Off the half-pixel grid, so that no read rounds a tie one way in the image and the other in its mirror.
    state = steepest_edges(image, 12.0, 40.0) + np.array([0.23, 0.0, 0.31, 0.0])
    mirrored = OUTLINE.outline(np.array([-state[0], 0.0, state[2], 0.0]), np.ascontiguousarray(image[:, ::-1]))
    outline = OUTLINE.outline(state, image)
    np.testing.assert_allclose([-mirrored[0], mirrored[2]], [outline[0], outline[2]], atol=1e-9)


@pytest.mark.parametrize(
    ("fraction", "rim_ratio", "reach"), [(0.0, 0.3, 4.0), (1.0, 0.3, 4.0), (0.5, -0.1, 4.0), (0.5, 0.3, -1.0)]
)
def test_bad_settings_are_rejected(fraction, rim_ratio, reach):
    with pytest.raises(ValueError, match="silhouette fraction|rim ratio|rim reach"):
        Silhouette(TAPS, SPACING, fraction, rim_ratio, reach)
