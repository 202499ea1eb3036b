"""The region of interest's compiled mask equals numpy's broadcast ``float32`` reading bit for bit."""

from __future__ import annotations

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from trackbench_segmentation.band import band_mask


def _broadcast(d: float, alpha: float, half_width: float, width: int, height: int) -> np.ndarray:
    """The first formulation of :func:`trackbench_segmentation.tracking.region_of_interest`'s mask."""
    x = np.arange(width, dtype=np.float32) - np.float32((width - 1) / 2.0)
    y = np.float32((height - 1) / 2.0) - np.arange(height, dtype=np.float32)
    distance = np.abs(x[None, :] * np.float32(math.cos(alpha)) + y[:, None] * np.float32(math.sin(alpha)) - d)
    return distance <= half_width


@settings(max_examples=300, deadline=None)
@given(
    d=st.floats(-400.0, 400.0),
    alpha=st.floats(-math.pi, math.pi),
    half_width=st.floats(0.0, 300.0),
    width=st.integers(1, 90),
    height=st.integers(1, 70),
)
def test_the_band_mask_is_numpy_s(d, alpha, half_width, width, height):
    expected = _broadcast(d, alpha, half_width, width, height)
    assert np.array_equal(band_mask(d, math.cos(alpha), math.sin(alpha), half_width, width, height), expected)


@settings(max_examples=200, deadline=None)
@given(width=st.integers(1, 60), height=st.integers(1, 40), column=st.integers(0, 59), nudge=st.sampled_from([-1, 0, 1]))
def test_a_half_width_landing_on_a_pixel_s_distance_decides_as_numpy_does(width, height, column, nudge):
    # Distances and limits that tie in float32 but not in float64: the limit is taken in float32, as numpy takes it.
    distance = float(abs(np.float32(column % width) - np.float32((width - 1) / 2.0)))
    half_width = float(np.nextafter(distance, distance + nudge)) if nudge else distance
    expected = _broadcast(0.0, 0.0, half_width, width, height)
    assert np.array_equal(band_mask(0.0, 1.0, 0.0, half_width, width, height), expected)
