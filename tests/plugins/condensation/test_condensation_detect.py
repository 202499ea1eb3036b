"""Tests of the line scan that proposes candidate cables."""

from __future__ import annotations

import math

import numpy as np
import pytest
from trackbench_condensation.detect import LineScan, propose
from trackbench_condensation.kernel import dog_taps

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
