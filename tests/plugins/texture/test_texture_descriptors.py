"""Tests of the five texture descriptors (seeds/000, section 2.2)."""

from __future__ import annotations

import cv2
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from trackbench_texture.descriptors import NAMES, densities, densities_at, pixel_kinds, texture_descriptors
from trackbench_texture.params import DescriptorParams

PARAMS = DescriptorParams()


@st.composite
def images(draw) -> np.ndarray:
    """Blank, noisy, saturated or half-saturated grey images of random sizes, down to 1 x 1."""
    height = draw(st.integers(1, 48))
    width = draw(st.integers(1, 48))
    kind = draw(st.sampled_from(["blank", "noise", "saturated", "split"]))
    seed = draw(st.integers(0, 2**16))
    rng = np.random.default_rng(seed)
    if kind == "blank":
        return np.full((height, width), draw(st.integers(0, 255)), np.uint8)
    if kind == "noise":
        return rng.integers(0, 256, (height, width), dtype=np.uint8)
    if kind == "saturated":
        return np.where(rng.random((height, width)) < 0.5, 0, 255).astype(np.uint8)
    image = np.zeros((height, width), np.uint8)
    image[:, width // 2 :] = 255
    return image


@settings(max_examples=60, deadline=None)
@given(image=images(), window=st.integers(3, 41), sigma=st.sampled_from([0.0, 1.0, 2.5]))
def test_every_descriptor_is_finite_and_a_density_on_any_image(image, window, sigma):
    params = DescriptorParams(smoothing_sigma=sigma, window_px=window)
    values = texture_descriptors(image, params)
    assert values.shape == (*image.shape, len(NAMES))
    assert values.dtype == np.float32
    assert np.isfinite(values).all()
    assert values.min() >= 0.0 and values.max() <= 1.0


def test_a_blank_image_is_all_blur_and_nothing_else():
    values = texture_descriptors(np.full((40, 50), 77, np.uint8), PARAMS)
    assert np.all(values[..., NAMES.index("blurriness")] == 1.0)
    others = [NAMES.index(name) for name in NAMES if name != "blurriness"]
    assert np.all(values[..., others] == 0.0)


def _line_image() -> np.ndarray:
    image = np.full((80, 80), 150, np.uint8)
    cv2.line(image, (20, 5), (30, 75), 60, 3)
    return image


@pytest.mark.parametrize("end", [(30, 75), (75, 30), (60, 70), (21, 75)])
def test_a_straight_line_is_straight_and_has_no_sudden_turns_along_it(end):
    image = np.full((80, 80), 150, np.uint8)
    cv2.line(image, (20, 5), end, 60, 3)
    kinds = pixel_kinds(image, PARAMS)
    on_edges = kinds.edges > 0
    assert on_edges.sum() > 100
    # Apart from its two rounded ends, every edge pixel of a long straight line is straight.
    assert kinds.straight[on_edges].mean() > 0.7
    assert kinds.abrupt[on_edges].mean() < 0.1


def test_a_tangle_of_short_lines_is_abrupt_and_discontinuous_and_not_straight():
    rng = np.random.default_rng(3)
    image = np.full((80, 80), 150, np.uint8)
    for _ in range(60):
        u, v = rng.integers(5, 75, 2)
        du, dv = rng.integers(-4, 5, 2)
        cv2.line(image, (int(u), int(v)), (int(u + du), int(v + dv)), 40, 1)
    tangle = texture_descriptors(image, PARAMS)[20:60, 20:60].mean(axis=(0, 1))
    line = texture_descriptors(_line_image(), PARAMS)[20:60, 15:35].mean(axis=(0, 1))
    index = {name: k for k, name in enumerate(NAMES)}
    assert tangle[index["abruptness"]] > 2 * line[index["abruptness"]]
    assert tangle[index["discontinuity"]] > 2 * line[index["discontinuity"]]
    tangle_kinds, line_kinds = pixel_kinds(image, PARAMS), pixel_kinds(_line_image(), PARAMS)
    straight_share = [kinds.straight.sum() / kinds.edges.sum() for kinds in (tangle_kinds, line_kinds)]
    assert straight_share[0] < 0.5 * straight_share[1]


def test_isolated_specks_are_granular_and_their_neighbourhood_is_not_blurry():
    image = np.full((60, 60), 120, np.uint8)
    image[10:50:4, 10:50:4] = 220
    kinds = pixel_kinds(image, DescriptorParams(smoothing_sigma=0.0))
    assert kinds.specks[10:50:4, 10:50:4].all()
    assert kinds.specks.sum() == 100
    assert kinds.soft[10:50:4, 11:50:4].sum() == 0
    values = texture_descriptors(image, DescriptorParams(smoothing_sigma=0.0))
    assert values[30, 30, NAMES.index("granularity")] > values[2, 2, NAMES.index("granularity")]


def test_blurriness_falls_where_the_intensity_changes_sharply():
    image = np.full((60, 60), 60, np.uint8)
    image[:, 30:] = 200
    values = texture_descriptors(image, DescriptorParams(smoothing_sigma=0.0, window_px=5))
    blur = values[..., NAMES.index("blurriness")]
    assert blur[30, 30] < 0.7
    assert blur[30, 5] == 1.0


@pytest.mark.parametrize(
    "image", [np.zeros((5, 5), np.float32), np.zeros((5, 5, 3), np.uint8), np.zeros((0, 4), np.uint8)]
)
def test_rejects_anything_but_a_grey_uint8_image(image):
    with pytest.raises(ValueError, match="uint8 grey image"):
        texture_descriptors(image, PARAMS)


@settings(max_examples=40, deadline=None)
@given(image=images(), window=st.integers(3, 41), step=st.integers(1, 8))
def test_the_descriptors_of_a_grid_are_those_of_the_whole_image_at_its_pixels(image, window, step):
    kinds = pixel_kinds(image, PARAMS)
    rows = np.arange(min(step // 2, image.shape[0] - 1), image.shape[0], step)
    cols = np.arange(min(step // 2, image.shape[1] - 1), image.shape[1], step)
    expected = densities(kinds, window)[np.ix_(rows, cols)]
    actual = densities_at(kinds, window, rows, cols)
    assert actual.dtype == expected.dtype and actual.tobytes() == expected.tobytes()
