"""Tests of the compiled border projection and filter responses."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp
from trackbench_condensation.kernel import dog_taps
from trackbench_condensation.measure import (
    _border,
    _sample_range,
    best_pairs,
    border_line_scores,
    border_scores,
    centre_contrast,
    line_scores,
)

from benchmark.modalities.camera.geometry import cable_borders, pixel_to_model
from benchmark.modalities.camera.model import CableState

SIZE = (320, 240)
TAPS = dog_taps(11)


def border_sample_points(state: np.ndarray, width: int, height: int, radius: int, spacing: float) -> np.ndarray:
    """The sample points of both borders of one state, as :func:`border_scores` visits them.

    Built from the same compiled helpers as :func:`border_scores` (the
    border's foot point and normal, the range of points inside the image).

    Returns
    -------
    numpy.ndarray
        ``(M, 5)`` rows ``(side, u, v, mu, mv)``: side -1 (left) or +1 (right),
        the point in pixels and the unit normal the filter runs along.

    References
    ----------
    seeds/000, section 4.5, Fig. 4.7.
    """
    cu, cv = 0.5 * (width - 1), 0.5 * (height - 1)
    lo, hi_u, hi_v = float(radius), width - 1.0 - radius, height - 1.0 - radius
    nx, ny = math.cos(state[1]), math.sin(state[1])
    cb, sb = math.cos(state[3]), math.sin(state[3])
    rows = []
    for side in (-1, 1):
        u0, v0, du, dv, mu, mv = _border(state[0], state[2], side, nx, ny, cb, sb, cu, cv)
        k0, k1 = _sample_range(u0, v0, du, dv, lo, hi_u, hi_v, spacing)
        for k in range(k0, k1 + 1):
            s = k * spacing
            rows.append((float(side), min(max(u0 + s * du, lo), hi_u), min(max(v0 + s * dv, lo), hi_v), mu, mv))
    return np.array(rows, dtype=float).reshape(-1, 5)


def state_array(d, alpha_deg, w, beta_deg):
    return np.array([d, math.radians(alpha_deg), w, math.radians(beta_deg), 0.0, 0.0])


def distance_to(line, x, y):
    """Distance of a model point from a line."""
    return abs((x - line.x0) * line.dy - (y - line.y0) * line.dx)


table_5_2_states = st.tuples(
    st.floats(-150, 150), st.floats(-45, 45), st.floats(5, 100), st.floats(0, 10)
).map(lambda t: state_array(*t))


@settings(max_examples=60, deadline=None)
@given(state=table_5_2_states, spacing=st.sampled_from([5.0, 20.0]), radius=st.sampled_from([2, 5]))
def test_sample_points_lie_inside_the_image_and_on_their_border(state, spacing, radius):
    points = border_sample_points(state, SIZE[0], SIZE[1], radius, spacing)
    left, right = cable_borders(CableState.from_array(state[:4]))
    for side, u, v, mu, mv in points:
        assert radius - 1e-9 <= u <= SIZE[0] - 1 - radius + 1e-9
        assert radius - 1e-9 <= v <= SIZE[1] - 1 - radius + 1e-9
        line = left if side < 0 else right
        assert distance_to(line, *pixel_to_model(u, v, SIZE)) < 1e-6
        # The filter runs across the border: its normal is perpendicular to it.
        assert math.hypot(mu, mv) == pytest.approx(1.0)
        assert abs(mu * line.dx - mv * line.dy) < 1e-9
    # Consecutive points of a border are one spacing apart.
    for side in (-1.0, 1.0):
        uv = points[points[:, 0] == side][:, 1:3]
        if len(uv) > 1:
            np.testing.assert_allclose(np.hypot(*np.diff(uv, axis=0).T), spacing)


def test_normal_points_from_left_to_right_across_the_cable():
    points = border_sample_points(state_array(0.0, 20.0, 40.0, 3.0), SIZE[0], SIZE[1], 5, 20.0)
    left = points[points[:, 0] < 0]
    right = points[points[:, 0] > 0]
    # From a left point along the normal we get closer to the right border, and vice versa.
    line_r = cable_borders(CableState(0.0, math.radians(20.0), 40.0, math.radians(3.0)))[1]
    for _, u, v, mu, mv in left:
        before = distance_to(line_r, *pixel_to_model(u, v, SIZE))
        after = distance_to(line_r, *pixel_to_model(u + mu, v + mv, SIZE))
        assert after < before
    assert len(right) > 0


def vertical_band(left_x, right_x, inside, outside, size=SIZE):
    """A sharp vertical band between two model x positions."""
    width, height = size
    x = np.arange(width) - (width - 1) / 2.0
    row = np.where((x > left_x) & (x < right_x), inside, outside).astype(np.uint8)
    return np.tile(row, (height, 1))


def test_dark_cable_gives_positive_left_and_negative_right_counts():
    image = vertical_band(-20.5, 19.5, 50, 150)
    scores, counts = border_scores(state_array(-0.5, 0.0, 40.0, 0.0)[None], image, TAPS, 20.0, False)
    # Points every 20 px from the row through the centre, at least 5 px (the
    # filter's half size) inside the image: 114.5 px either way, 11 points.
    assert counts[0, 0] == counts[0, 1] == 11
    # Each sample point sees a 100-level step: the count is 100 per point.
    assert scores[0, 0] == pytest.approx(100.0 * counts[0, 0], rel=0.02)
    assert scores[0, 1] == pytest.approx(-100.0 * counts[0, 1], rel=0.02)


def test_bright_cable_reverses_both_signs():
    image = vertical_band(-20.5, 19.5, 150, 50)
    scores, _ = border_scores(state_array(-0.5, 0.0, 40.0, 0.0)[None], image, TAPS, 20.0, False)
    assert scores[0, 0] < 0 < scores[0, 1]


def test_reversed_normal_describes_the_same_cable():
    # (d, alpha) and (-d, alpha + pi) with the borders swapped are the same
    # pair of lines; the filter then runs right to left and the signs flip.
    image = vertical_band(-30.5, 9.5, 40, 170)
    a, _ = border_scores(state_array(-10.5, 3.0, 40.0, 0.0)[None], image, TAPS, 20.0, False)
    b, _ = border_scores(state_array(10.5, 183.0, 40.0, 0.0)[None], image, TAPS, 20.0, False)
    np.testing.assert_allclose(b[0], -a[0][::-1], rtol=0.05)


def smooth_image(seed=0):
    rng = np.random.default_rng(seed)
    y, x = np.mgrid[0 : SIZE[1], 0 : SIZE[0]].astype(float)
    image = 120 + 60 * np.sin(x / 13.0 + rng.uniform(0, 6)) * np.cos(y / 17.0 + rng.uniform(0, 6)) + 0.2 * x
    return np.clip(image, 0, 255).astype(np.uint8)


def test_nearest_and_bilinear_reads_agree_on_a_smooth_image():
    rng = np.random.default_rng(1)
    states = np.column_stack(
        [rng.uniform(-80, 80, 200), rng.uniform(-0.6, 0.6, 200), rng.uniform(10, 60, 200), rng.uniform(0, 0.1, 200)]
    )
    image = smooth_image()
    nearest, _ = border_scores(states, image, TAPS, 20.0, False)
    bilinear, _ = border_scores(states, image, TAPS, 20.0, True)
    assert np.corrcoef(nearest.ravel(), bilinear.ravel())[0, 1] > 0.99


def test_float_and_uint8_images_give_the_same_scores():
    rng = np.random.default_rng(2)
    states = np.column_stack(
        [rng.uniform(-80, 80, 50), rng.uniform(-0.6, 0.6, 50), rng.uniform(10, 60, 50), np.zeros(50)]
    )
    image = smooth_image(3)
    a, _ = border_scores(states, image, TAPS, 20.0, False)
    b, _ = border_scores(states, image.astype(np.float32), TAPS, 20.0, False)
    np.testing.assert_allclose(a, b, atol=1e-9)


def test_states_outside_the_image_or_not_finite_score_zero():
    states = np.array(
        [state_array(1000.0, 0.0, 30.0, 0.0), [np.nan, 0.0, 30.0, 0.0, 0.0, 0.0], state_array(0, 0, np.inf, 0)]
    )
    scores, counts = border_scores(states, smooth_image(), TAPS, 20.0, False)
    assert np.all(scores == 0) and np.all(counts == 0)


def test_line_scores_equal_the_border_counts_of_the_same_lines():
    image = smooth_image(4)
    alphas = np.radians([-20.0, 0.0, 15.0])
    offsets = np.array([-60.0, -3.0, 41.0])
    lines = line_scores(image, TAPS, 20.0, alphas, offsets)
    for a, alpha in enumerate(alphas):
        for m, offset in enumerate(offsets):
            # A zero-width, zero-skew cable has both borders on the line.
            scores, _ = border_scores(np.array([[offset, alpha, 0.0, 0.0]]), image, TAPS, 20.0, False)
            assert lines[a, m] == pytest.approx(scores[0, 1])


def test_best_pairs_pairs_opposite_extrema_within_the_width_range():
    offsets = np.arange(0.0, 100.0, 2.0)
    responses = np.zeros((1, offsets.size))
    responses[0, 10] = 500.0  # offset 20
    responses[0, 25] = -400.0  # offset 50
    responses[0, 45] = -900.0  # offset 90, too far from the first
    pairs, values = best_pairs(responses, offsets, 5.0, 60.0, 3)
    assert pairs.tolist()[0] == [0, 10, 25]
    assert values[0] == pytest.approx(900.0)
    # Same-sign extrema are never paired.
    assert all(responses[0, i] * responses[0, j] < 0 for _, i, j in pairs)


def test_centre_contrast_rewards_a_brighter_centreline():
    width, height = SIZE
    x = np.arange(width) - (width - 1) / 2.0
    profile = np.where(np.abs(x) < 20, 80 + 40 * np.cos(np.pi * x / 40.0), 150)
    image = np.tile(profile, (height, 1)).astype(np.uint8)
    states = np.array([state_array(0.0, 0.0, 40.0, 0.0), state_array(15.0, 0.0, 40.0, 0.0)])
    contrast = centre_contrast(states, image, 20.0, False)
    assert contrast[0] > 0
    assert contrast[0] > contrast[1]


def reference_best_pairs(scores, offsets, min_width, max_width, keep):
    """best_pairs as first written: every pair of extrema, left to right, the best ``keep`` per angle kept in order."""
    rows, values = [], []
    for a, c in enumerate(scores):
        padded = np.r_[0.0, c, 0.0]
        extrema = [
            m
            for m in range(len(c))
            if (c[m] > 0 and c[m] >= padded[m] and c[m] >= padded[m + 2])
            or (c[m] < 0 and c[m] <= padded[m] and c[m] <= padded[m + 2])
        ]
        best: list[tuple[float, tuple[int, int, int]]] = []
        for i, left in enumerate(extrema):
            for right in extrema[i + 1 :]:
                gap = offsets[right] - offsets[left]
                if gap < min_width:
                    continue
                if gap > max_width:
                    break
                if c[left] * c[right] >= 0:
                    continue
                value = abs(c[left]) + abs(c[right])
                if len(best) == keep and value <= best[-1][0]:
                    continue
                # After every kept pair of at least this value (ties keep the earlier pair first).
                slot = sum(1 for kept, _ in best if kept >= value)
                best.insert(slot, (value, (a, left, right)))
                del best[keep:]
        rows += [row for _, row in best]
        values += [value for value, _ in best]
    return np.array(rows, dtype=np.int64).reshape(-1, 3), np.array(values)


@settings(max_examples=150, deadline=None)
@given(st.data())
def test_best_pairs_keeps_the_pairs_of_the_exhaustive_search(data):
    angles, count = data.draw(st.integers(1, 3)), data.draw(st.integers(1, 40))
    level = st.one_of(st.just(0.0), st.integers(-5, 5).map(float), st.floats(-100, 100))
    scores = data.draw(hnp.arrays(np.float64, (angles, count), elements=level))
    offsets = np.cumsum(data.draw(hnp.arrays(np.float64, count, elements=st.floats(0.5, 3.0))))
    min_width = data.draw(st.floats(0.0, 10.0))
    max_width = min_width + data.draw(st.floats(0.0, 40.0))
    keep = data.draw(st.integers(1, 4))
    rows, values = best_pairs(scores, offsets, min_width, max_width, keep)
    expected_rows, expected_values = reference_best_pairs(scores, offsets, min_width, max_width, keep)
    np.testing.assert_array_equal(rows, expected_rows)
    np.testing.assert_array_equal(values, expected_values)


@settings(max_examples=60, deadline=None)
@given(
    st.tuples(st.floats(-60, 60), st.floats(-60, 60)),
    st.tuples(st.floats(-200, 200), st.floats(-200, 200)),
    st.sampled_from([np.uint8, np.float32]),
    st.integers(0, 2**32 - 1),
)
def test_the_two_border_lines_score_as_two_line_score_calls_bit_for_bit(alphas_deg, lines, dtype, seed):
    image = np.random.default_rng(seed).integers(0, 256, size=(48, 64)).astype(dtype)
    alpha_left, alpha_right = (math.radians(a) for a in alphas_deg)
    left, right = border_line_scores(image, TAPS, 7.0, alpha_left, alpha_right, *lines)
    assert left == line_scores(image, TAPS, 7.0, np.array([alpha_left]), np.array([lines[0]]))[0, 0]
    assert right == line_scores(image, TAPS, 7.0, np.array([alpha_right]), np.array([lines[1]]))[0, 0]
