"""Tests of the LoG edge image (seeds/000, section 2.1)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from trackbench_hough.edges import crossing_steps, edge_image, log_response, zero_crossings


def step_image(height: float, column: int = 40, shape: tuple[int, int] = (60, 80)) -> np.ndarray:
    image = np.full(shape, 100.0, np.float32)
    image[:, column:] += height
    return image


@settings(max_examples=30, deadline=None)
@given(sigma=st.floats(1.5, 5.0), height=st.floats(10.0, 120.0), rising=st.booleans())
def test_threshold_is_the_step_height_in_grey_levels(sigma, height, rising):
    image = step_image(height if rising else -height)
    response = log_response(image, sigma)
    assert zero_crossings(response, sigma, 0.85 * height).any()
    assert not zero_crossings(response, sigma, 1.05 * height).any()


@pytest.mark.parametrize("sigma", [2.0, 3.0, 5.0])
def test_a_step_gives_one_thin_border_at_the_step(sigma):
    edges = edge_image(step_image(60.0).astype(np.uint8), sigma, 20.0)
    columns = np.unique(np.nonzero(edges)[1])
    assert columns.size == 1 and columns[0] in (39, 40)
    assert np.count_nonzero(edges) == edges.shape[0]
    assert edges.dtype == np.uint8 and set(np.unique(edges)) == {0, 255}


def test_a_flat_image_has_no_edges():
    assert not edge_image(np.full((30, 40), 77, np.uint8), 3.0, 1.0).any()


def test_response_sign_follows_the_log_kernel():
    # A bright spot: the LoG of seeds/000 eq. (2.1) is negative at its centre.
    image = np.zeros((41, 41), np.float32)
    image[20, 20] = 255.0
    response = log_response(image, 3.0)
    assert response[20, 20] < 0 and response[20, 20] == response.min()
    assert math.isclose(float(response[20, 20 + 9]), float(response[20 + 9, 20]), rel_tol=1e-4)


def test_sigma_must_be_positive():
    with pytest.raises(ValueError, match="sigma"):
        log_response(np.zeros((5, 5), np.uint8), 0.0)


@settings(max_examples=30, deadline=None)
@given(sigma=st.floats(1.5, 5.0), height=st.floats(10.0, 120.0), stride=st.integers(1, 3))
def test_crossing_steps_measure_what_the_threshold_compares(sigma, height, stride):
    image = step_image(height)
    steps = crossing_steps(log_response(image, sigma), sigma, stride)
    # One crossing of the step's height on each sampled row, none between vertical neighbours;
    # what else changes sign is the LoG's faint far tail.
    strong = steps[steps >= 0.5 * height]
    assert strong.size == len(range(0, image.shape[0], stride))
    assert np.all((strong >= 0.85 * height) & (strong < 1.05 * height))
    assert np.all(steps[steps < 0.5 * height] < 0.05 * height)


@settings(max_examples=20, deadline=None)
@given(gain=st.floats(0.1, 10.0), seed=st.integers(0, 2**16))
def test_crossing_steps_scale_with_the_grey_levels(gain, seed):
    # Float rounding may flip the sign of a response within an ulp of zero, so compare the
    # crossings of real steps and the median the threshold rule uses.
    image = np.random.default_rng(seed).normal(100.0, 20.0, (30, 40)).astype(np.float32)
    steps = crossing_steps(log_response(image, 2.0), 2.0)
    scaled = crossing_steps(log_response(gain * image, 2.0), 2.0)
    assert abs(scaled.size - steps.size) <= 2
    assert np.isclose(np.median(scaled), gain * np.median(steps), rtol=1e-2)
    assert np.isclose(scaled.max(), gain * steps.max(), rtol=1e-3)


def test_crossing_steps_need_a_positive_stride():
    with pytest.raises(ValueError, match="stride"):
        crossing_steps(np.zeros((5, 5), np.float32), 2.0, 0)
