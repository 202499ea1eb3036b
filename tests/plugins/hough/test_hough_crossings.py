"""The compiled zero-crossing loops, the median by counting and the edges in rectangles give, bit for bit,
what the array formulations they replace gave."""

from __future__ import annotations

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp
from trackbench_hough.crossings import order_statistics
from trackbench_hough.edges import (
    crossing_steps,
    median_crossing_step,
    step_height_scale,
    zero_crossings,
    zero_crossings_in,
)

# Values near zero of both signs (signed zeros included), repeated values (ties in |a| <= |b|) and large jumps.
values = st.sampled_from([0.0, -0.0, 1e-6, -1e-6, 0.25, -0.25, 0.5, -0.5, 3.0, -3.0, 7.5, -40.0]) | st.floats(
    -50.0, 50.0, width=32
)
responses = hnp.arrays(np.float32, hnp.array_shapes(min_dims=2, max_dims=2, min_side=1, max_side=12), elements=values)


def zero_crossings_by_arrays(response: np.ndarray, sigma: float, min_step: float) -> np.ndarray:
    """The array formulation of trackbench_hough.edges.zero_crossings before it was compiled."""
    min_jump = min_step / step_height_scale(sigma)
    edges = np.zeros(response.shape, dtype=bool)
    magnitude = np.abs(response)
    for axis in (0, 1):
        first = [slice(None), slice(None)]
        second = [slice(None), slice(None)]
        first[axis], second[axis] = slice(None, -1), slice(1, None)
        a, b = response[tuple(first)], response[tuple(second)]
        crossing = (np.signbit(a) != np.signbit(b)) & (np.abs(a - b) >= min_jump)
        first_nearer = magnitude[tuple(first)] <= magnitude[tuple(second)]
        edges[tuple(first)] |= crossing & first_nearer
        edges[tuple(second)] |= crossing & ~first_nearer
    return edges.astype(np.uint8) * 255


def crossing_steps_by_arrays(response: np.ndarray, sigma: float, stride: int) -> np.ndarray:
    """The array formulation of trackbench_hough.edges.crossing_steps before it was compiled."""
    samples = []
    for first, second in (
        (response[::stride, :-1], response[::stride, 1:]),
        (response[:-1, ::stride], response[1:, ::stride]),
    ):
        samples.append(np.abs(first - second)[np.signbit(first) != np.signbit(second)])
    return np.concatenate(samples).astype(np.float64) * step_height_scale(sigma)


@settings(max_examples=150, deadline=None)
@given(response=responses, sigma=st.sampled_from([1.5, 2.0, 3.0]), min_step=st.floats(0.0, 400.0))
def test_zero_crossings_match_the_array_formulation(response, sigma, min_step):
    expected = zero_crossings_by_arrays(response, sigma, min_step)
    found = zero_crossings(response, sigma, min_step)
    assert found.dtype == np.uint8
    np.testing.assert_array_equal(found, expected)
    wide = response.astype(np.float64)
    expected_wide = zero_crossings_by_arrays(wide, sigma, min_step)
    np.testing.assert_array_equal(zero_crossings(wide, sigma, min_step), expected_wide)


@settings(max_examples=150, deadline=None)
@given(response=responses, sigma=st.sampled_from([1.5, 2.0, 3.0]), stride=st.integers(1, 5))
def test_crossing_steps_match_the_array_formulation(response, sigma, stride):
    expected = crossing_steps_by_arrays(response, sigma, stride)
    found = crossing_steps(response, sigma, stride)
    assert found.tobytes() == expected.tobytes()


def test_a_threshold_on_a_float32_boundary_compares_as_the_arrays_did():
    # A jump that equals the threshold only once the threshold is rounded to float32.
    sigma = 2.0
    jump = np.float32(0.1)
    response = np.array([[jump / 2, -jump / 2]], np.float32)
    min_step = float(np.float64(np.float32(jump) - np.float32(jump) * 1e-9) * step_height_scale(sigma))
    np.testing.assert_array_equal(
        zero_crossings(response, sigma, min_step), zero_crossings_by_arrays(response, sigma, min_step)
    )


@settings(max_examples=150, deadline=None)
@given(response=responses, sigma=st.sampled_from([1.5, 2.0, 3.0]), stride=st.integers(1, 5))
def test_median_crossing_step_is_numpys_median_of_the_steps(response, sigma, stride):
    steps = crossing_steps_by_arrays(response, sigma, stride)
    found = median_crossing_step(response, sigma, stride)
    if steps.size == 0:
        assert found is None
    else:
        assert found == float(np.median(steps))


@settings(max_examples=100, deadline=None)
@given(
    values=hnp.arrays(
        np.float32, st.integers(2, 3000), elements=st.floats(0.0, 1e4, width=32) | st.sampled_from([0.0, 1.0, 2.0])
    ),
)
def test_order_statistics_are_those_of_the_sorted_values(values):
    rank = values.size // 2
    expected = np.sort(values)
    assert order_statistics(values, rank) == (expected[rank - 1], expected[rank])


@settings(max_examples=150, deadline=None)
@given(
    response=responses,
    min_step=st.floats(0.0, 400.0),
    corners=st.lists(st.tuples(*[st.integers(0, 12)] * 4), max_size=3),
)
def test_zero_crossings_in_rectangles_are_those_of_the_whole_frame(response, min_step, corners):
    height, width = response.shape
    rectangles = [
        (min(a, b), min(max(a, b) + 1, height), min(c, d), min(max(c, d) + 1, width))
        for a, b, c, d in corners
        if min(a, b) < height and min(c, d) < width
    ]
    expected = np.zeros((height, width), np.uint8)
    whole = zero_crossings_by_arrays(response, 2.0, min_step)
    for row0, row1, col0, col1 in rectangles:
        expected[row0:row1, col0:col1] = whole[row0:row1, col0:col1]
    np.testing.assert_array_equal(zero_crossings_in(response, 2.0, min_step, rectangles), expected)


@settings(max_examples=60, deadline=None)
@given(response=responses, stride=st.integers(1, 3), where=st.integers(0, 143))
def test_a_nan_in_the_response_gives_numpys_median_too(response, stride, where):
    response = response.copy()
    response.flat[where % response.size] = np.nan
    steps = crossing_steps_by_arrays(response, 2.0, stride)
    found = median_crossing_step(response, 2.0, stride)
    if steps.size == 0:
        assert found is None
    else:
        expected = float(np.median(steps))
        assert found == expected or (math.isnan(found) and math.isnan(expected))
