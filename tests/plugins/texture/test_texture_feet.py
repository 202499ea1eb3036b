"""Tests of moving fitted borders out to the feet of their edges."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from trackbench_texture.feet import border_feet

from benchmark.modalities.camera.geometry import cable_borders
from benchmark.modalities.camera.model import CableState

SIZE = (320, 240)


def _signed_offsets(state: CableState) -> tuple[np.ndarray, np.ndarray]:
    """Per pixel, the distance from the cable's centreline along its normal, and the half width, px."""
    width, height = SIZE
    x, y = np.meshgrid(np.arange(width) - (width - 1) / 2.0, (height - 1) / 2.0 - np.arange(height))
    across = x * math.cos(state.alpha) + y * math.sin(state.alpha) - state.d
    return across, np.full_like(across, state.w / 2.0)


def _cylinder(state: CableState, seabed: float = 60.0, peak: float = 220.0) -> np.ndarray:
    """A lamp-lit cylinder: brightest on its axis, falling to the seabed's grey at its silhouette."""
    across, half = _signed_offsets(state)
    shading = np.sqrt(np.clip(1.0 - (across / half) ** 2, 0.0, 1.0))
    return np.clip(np.rint(seabed + (peak - seabed) * shading), 0, 255).astype(np.uint8)


def _border_errors(estimate: CableState, truth: CableState) -> list[float]:
    """Distance of each estimated border from the true one at the image's middle row, px."""
    def at_middle(line):
        return line.x0 - line.y0 * line.dx / line.dy

    truth_u = sorted(at_middle(line) for line in cable_borders(truth))
    found_u = sorted(at_middle(line) for line in cable_borders(estimate))
    return [abs(a - b) for a, b in zip(found_u, truth_u)]


def test_borders_at_the_steepest_shading_move_out_to_the_silhouette():
    truth = CableState(12.0, math.radians(4.0), 60.0, 0.0)
    image = _cylinder(truth)
    # Edge detectors find a cylinder's borders where its shading is steepest, inside the silhouette.
    inside = CableState(truth.d, truth.alpha, truth.w - 12.0, truth.beta)
    assert max(_border_errors(inside, truth)) > 5.0
    moved = border_feet(image, inside, 4.0, 1.0, 0.5)
    assert max(_border_errors(moved, truth)) < 2.5


@given(offset=st.floats(-2.0, 2.0), alpha_deg=st.floats(-20.0, 20.0), width=st.floats(20.0, 80.0))
def test_a_sharp_border_stays_where_it_is(offset, alpha_deg, width):
    truth = CableState(5.0, math.radians(alpha_deg), width, 0.0)
    across, half = _signed_offsets(truth)
    image = np.where(np.abs(across) <= half, 180, 70).astype(np.uint8)
    fitted = CableState(truth.d + offset, truth.alpha, truth.w, truth.beta)
    moved = border_feet(image, fitted, 3.0, 1.0, 0.5)
    # A step smoothed with sigma 1 px has its slope's half maximum 1.2 px out, plus half a pixel of sampling.
    assert max(_border_errors(moved, truth)) < 2.0


def test_a_blank_image_leaves_the_borders_where_they_were():
    state = CableState(-8.0, math.radians(-6.0), 30.0, math.radians(1.0))
    moved = border_feet(np.full((240, 320), 90, np.uint8), state, 3.0, 1.0, 0.5)
    assert (moved.d, moved.alpha, moved.w, moved.beta) == pytest.approx((state.d, state.alpha, state.w, state.beta))
