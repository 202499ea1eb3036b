"""Tests of the grey levels the histograms are built on: smoothing and normalisation to the frame's own range."""

from __future__ import annotations

import cv2
import numpy as np
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from trackbench_segmentation.grey import grey_quantiles, normalised_grey

SIZE = (96, 72)
QUANTILES = (0.01, 0.99)


def textured(seed: int, level: float = 120.0, spread: float = 30.0) -> np.ndarray:
    """A ``float32`` image of smooth relief around ``level`` with standard deviation ``spread``."""
    rng = np.random.default_rng(seed)
    relief = cv2.GaussianBlur(rng.standard_normal(SIZE[::-1]).astype(np.float32), (0, 0), 3.0)
    return np.float32(level) + relief * np.float32(spread / float(relief.std()))


def as_uint8(image: np.ndarray) -> np.ndarray:
    return np.clip(np.rint(image), 0, 255).astype(np.uint8)


def test_without_quantiles_the_frame_is_only_smoothed_as_before():
    image = as_uint8(textured(0))
    assert np.array_equal(normalised_grey(image, 1.0, None), cv2.GaussianBlur(image, (0, 0), 1.0))
    assert normalised_grey(image, 0.0, None) is image


def test_the_quantiles_are_stretched_to_the_full_range():
    out = normalised_grey(as_uint8(textured(1)), 1.0, QUANTILES)
    low, high = np.quantile(out, QUANTILES)
    assert low <= 2 and high >= 253
    assert out.dtype == np.uint8 and out.shape == SIZE[::-1]


@settings(max_examples=20, deadline=None)
@given(seed=st.integers(0, 10_000), gain=st.floats(0.15, 1.0), offset=st.floats(-40.0, 40.0))
def test_a_weaker_contrast_gives_the_same_normalised_levels(seed, gain, offset):
    # The same scene at a fraction of its contrast, shifted: its normalised levels differ only by rounding.
    scene = textured(seed, level=128.0, spread=40.0)
    murky = as_uint8(np.float32(128.0 + offset) + np.float32(gain) * (scene - np.float32(128.0)))
    # A shift that clips as many pixels as a quantile holds moves that quantile onto the clipped level: the frame
    # then lost part of its scene, which is not the weaker contrast this property is about.
    assume(np.mean((murky == 0) | (murky == 255)) < QUANTILES[0] / 2)
    reference = normalised_grey(as_uint8(scene), 1.0, QUANTILES).astype(int)
    weak = normalised_grey(murky, 1.0, QUANTILES).astype(int)
    # Rounding the murky image to integers moves a level by up to half a grey level, i.e. 0.5 / gain of the
    # reference's levels, before the stretch; the quantiles move by as much.
    tolerance = 255.0 / (4.0 * 40.0 * gain) * 3.0 + 2.0
    inside = (reference > 5) & (reference < 250)
    assert np.abs(weak - reference)[inside].mean() < tolerance / 3.0
    assert np.percentile(np.abs(weak - reference)[inside], 99) <= tolerance


def test_a_flat_frame_is_not_stretched():
    flat = np.full(SIZE[::-1], 90, np.uint8)
    assert np.array_equal(normalised_grey(flat, 1.0, QUANTILES), flat)


def test_a_low_contrast_frame_fills_the_levels_without_gaps():
    # Twelve raw grey levels stretched to 256 would leave most levels empty; smoothing in floating point fills them.
    image = as_uint8(textured(2, spread=3.0))
    out = normalised_grey(image, 1.0, QUANTILES)
    used = np.flatnonzero(np.bincount(out.ravel(), minlength=256))
    assert len(np.unique(image)) < 30
    assert np.diff(used[(used > 20) & (used < 235)]).max() <= 2


@given(levels=st.lists(st.integers(0, 255), min_size=1, max_size=300), low=st.floats(0, 1), high=st.floats(0, 1))
def test_quantiles_are_the_levels_of_the_pixels_of_that_rank(levels, low, high):
    image = np.array(levels, np.uint8).reshape(1, -1)
    ordered = np.sort(image.ravel())
    expected = tuple(float(ordered[int(np.floor(q * (len(levels) - 1)))]) for q in (low, high))
    assert grey_quantiles(image, (low, high)) == expected
