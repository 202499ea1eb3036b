"""The cable's contrast in grey levels, measured on synthetic images."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from benchmark.modalities.camera.contrast import cable_contrast, measure_contrast
from benchmark.modalities.camera.model import CableState

SIZE = (160, 120)


def painted(state: CableState, cable: float, seabed: float, size: tuple[int, int] = SIZE) -> np.ndarray:
    """An image of grey ``seabed`` with the cable's area between its borders painted ``cable``."""
    width, height = size
    x = np.arange(width)[None, :] - (width - 1) / 2.0
    y = (height - 1) / 2.0 - np.arange(height)[:, None]
    across = x * math.cos(state.alpha) + y * math.sin(state.alpha) - state.d
    return np.where(np.abs(across) <= state.w / 2, cable, seabed).astype(np.float32)


@settings(max_examples=40, deadline=None)
@given(
    d=st.floats(-30.0, 30.0),
    alpha=st.floats(-0.6, 0.6),
    w=st.floats(6.0, 40.0),
    cable=st.floats(0.0, 255.0),
    seabed=st.floats(0.0, 255.0),
)
def test_the_contrast_of_a_painted_cable_is_the_difference_of_its_greys(
    d: float, alpha: float, w: float, cable: float, seabed: float
) -> None:
    state = CableState(d, alpha, w, 0.0)
    measured = measure_contrast(painted(state, cable, seabed), state)
    assert measured is not None
    assert measured.contrast == pytest.approx(abs(cable - seabed), abs=1e-3)
    assert measured.cable_grey == pytest.approx(cable, abs=1e-3)


def test_noise_and_a_few_outliers_do_not_move_the_median() -> None:
    state = CableState(5.0, 0.2, 20.0, 0.0)
    image = painted(state, 60.0, 100.0) + np.random.default_rng(0).normal(0.0, 10.0, (SIZE[1], SIZE[0]))
    image[::17, ::13] = 255.0
    assert cable_contrast(image, state) == pytest.approx(40.0, abs=2.5)


def test_a_skewed_cable_is_measured_between_its_converging_borders() -> None:
    state = CableState(0.0, 0.0, 30.0, 0.05)
    width, height = SIZE
    x = np.arange(width)[None, :] - (width - 1) / 2.0
    y = (height - 1) / 2.0 - np.arange(height)[:, None]
    half = 15.0 - y * math.tan(0.05)
    image = np.where(np.abs(x) <= half, 20.0, 120.0)
    assert cable_contrast(image, state) == pytest.approx(100.0)


def test_a_cable_outside_the_image_cannot_be_measured() -> None:
    state = CableState(500.0, 0.0, 10.0, 0.0)
    assert measure_contrast(np.zeros((SIZE[1], SIZE[0])), state) is None
    assert math.isnan(cable_contrast(np.zeros((SIZE[1], SIZE[0])), state))


def test_bad_inputs_are_refused() -> None:
    with pytest.raises(ValueError, match="grey image"):
        cable_contrast(np.zeros((4, 4, 3)), CableState(0.0, 0.0, 2.0, 0.0))
    with pytest.raises(ValueError, match="known"):
        cable_contrast(np.zeros((4, 4)), CableState(math.nan, 0.0, 2.0, 0.0))
