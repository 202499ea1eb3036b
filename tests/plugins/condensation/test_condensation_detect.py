"""Tests of the line scan that proposes candidate cables."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from trackbench_condensation.detect import LineScan, LocalAscent, propose
from trackbench_condensation.kernel import dog_taps
from trackbench_condensation.observation import BorderObservation, ImageScore

from benchmark.modalities.camera.geometry import cable_borders, score_line_pair
from benchmark.modalities.camera.model import CableState
from benchmark.model import Outcome


@pytest.mark.parametrize(
    ("state", "contrast"),
    [
        (CableState(12.0, math.radians(8.0), 34.0, 0.0), -60.0),
        (CableState(-50.0, math.radians(-20.0), 20.0, 0.0), 60.0),
    ],
)
def test_strongest_candidate_is_the_drawn_cable(scene, state, contrast):
    image = scene.draw_cable(state, contrast=contrast, seed=4)
    candidates, scores = LineScan().candidates(image, dog_taps(11), 20.0, 5)
    assert candidates.shape[1] == 4 and len(candidates) == len(scores) <= 5
    assert np.all(np.diff(scores) <= 0)
    best = CableState.from_array(candidates[0])
    assert score_line_pair(cable_borders(best), cable_borders(state), scene.SIZE) is Outcome.CORRECT


def test_angle_window_restricts_the_scan(scene):
    state = CableState(0.0, math.radians(20.0), 30.0, 0.0)
    image = scene.draw_cable(state, seed=2)
    near, _ = LineScan().candidates(image, dog_taps(11), 20.0, 5, around_alpha=math.radians(-30.0), window_deg=6.0)
    assert np.all(np.abs(near[:, 1] - math.radians(-30.0)) <= math.radians(6.0) + 1e-9)
    outside, _ = LineScan().candidates(image, dog_taps(11), 20.0, 5, around_alpha=math.radians(80.0), window_deg=5.0)
    assert outside.shape == (0, 4)


def test_blank_image_has_no_candidates():
    image = np.full((240, 320), 90, np.uint8)
    candidates, scores = LineScan().candidates(image, dog_taps(11), 20.0, 5)
    assert candidates.shape == (0, 4) and scores.shape == (0,)


def test_proposals_scatter_around_the_candidates():
    candidates = np.array([[10.0, 0.1, 30.0, 0.0], [-40.0, -0.2, 20.0, 0.0]])
    spread = np.array([1.0, 0.01, 2.0, 0.02])
    states = propose(candidates, 4000, 6, spread, np.random.default_rng(3))
    assert states.shape == (4000, 6) and np.all(states[:, 4:] == 0)
    nearest = np.argmin(np.abs(states[:, :1] - candidates[:, 0]), axis=1)
    assert 0.45 < nearest.mean() < 0.55
    offsets = states[:, :4] - candidates[nearest]
    np.testing.assert_allclose(offsets.std(axis=0), spread, rtol=0.1)


def test_bad_scan_settings_are_rejected():
    with pytest.raises(ValueError):
        LineScan(angle_step_deg=0.0)


def test_local_ascent_finds_a_skewed_cable_the_parallel_scan_only_approaches(scene):
    state = CableState(10.0, math.radians(6.0), 40.0, math.radians(2.0))
    image = scene.draw_cable(state, seed=3)
    observation = BorderObservation()
    candidates, scan_scores = LineScan().candidates(image, observation.taps, 20.0, 3)

    def score(states: np.ndarray) -> np.ndarray:
        return observation.score(states, image)

    bounds = (np.array([-np.inf, -0.8, 5.0, 0.0]), np.array([np.inf, 0.8, 100.0, math.radians(10.0)]))
    refined, refined_scores = LocalAscent().refine(candidates, score, *bounds)
    assert np.all(refined_scores >= score(candidates))
    np.testing.assert_allclose(refined_scores, score(refined))
    best = CableState.from_array(refined[np.argmax(refined_scores)])
    assert score_line_pair(cable_borders(best), cable_borders(state), scene.SIZE) is Outcome.CORRECT
    assert abs(math.degrees(best.beta - state.beta)) < 0.5
    assert refined_scores.max() > 1.2 * score(candidates).max()


@settings(max_examples=40, deadline=None)
@given(
    offset=st.tuples(st.floats(-6, 6), st.floats(-0.05, 0.05), st.floats(-6, 6), st.floats(-0.05, 0.05)),
    peak=st.tuples(st.floats(-30, 30), st.floats(-0.6, 0.6), st.floats(0, 70), st.floats(-0.1, 0.3)),
)
def test_local_ascent_never_loses_score_and_stays_within_its_bounds(offset, peak):
    low, high = np.array([-20.0, -0.5, 5.0, 0.0]), np.array([20.0, 0.5, 60.0, 0.2])
    centre = np.array(peak)
    scale = np.array([1.0, 100.0, 1.0, 100.0])  # a degree matters about as much as a pixel

    def score(states: np.ndarray) -> np.ndarray:
        return -np.sum(((states - centre) * scale) ** 2, axis=1)

    states = np.array([np.clip(centre, low, high) + np.array(offset), [0.0, 0.0, 10.0, 0.1]])
    refined, values = LocalAscent().refine(states, score, low, high)
    assert np.all((refined >= low) & (refined <= high))
    assert np.all(values >= score(np.clip(states, low, high)))
    np.testing.assert_allclose(values, score(refined))
    # On a concave score a start within a few grid steps ends at the bounded maximum.
    target = np.clip(centre, low, high)
    assert np.all(np.abs(refined[0] - target) <= np.array([0.3, 0.005, 0.3, 0.005]))


@settings(max_examples=30, deadline=None)
@given(
    start=st.tuples(st.floats(-60, 60), st.floats(-0.7, 0.7), st.floats(-10, 120), st.floats(-0.05, 0.25)),
    centre_weight=st.sampled_from([0.0, 1.0]),
    interpolation=st.sampled_from(["nearest", "bilinear"]),
)
def test_the_compiled_ascent_is_the_python_search_bit_for_bit(scene, start, centre_weight, interpolation):
    # ImageScore runs LocalAscent.refine in one compiled call; a plain callable of the same
    # score takes the vectorised Python path.  Both must end on the same states and scores exactly.
    image = scene.draw_cable(CableState(10.0, math.radians(6.0), 40.0, math.radians(2.0)), seed=3)
    observation = BorderObservation(centre_weight=centre_weight, interpolation=interpolation)
    states = np.array([start, [0.0, 0.0, 30.0, 0.0], [12.0, 0.1, 38.0, 0.03]])
    low, high = np.array([-np.inf, -0.8, 5.0, 0.0]), np.array([np.inf, 0.8, 100.0, math.radians(10.0)])
    python = LocalAscent().refine(states, lambda s: observation.score(s, image), low, high)
    compiled = LocalAscent().refine(states, ImageScore(observation, image), low, high)
    np.testing.assert_array_equal(compiled[0], python[0])
    np.testing.assert_array_equal(compiled[1], python[1])
    assert np.any(compiled[1] > observation.score(np.clip(states, low, high), image))
