"""Tests of one frame's detection process (seeds/000, section 2.3, Fig. 2.5) on drawn cables."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from trackbench_segmentation.detector import cell_pyramid, detect
from trackbench_segmentation.params import SegmentationParams

from benchmark.modalities.camera.geometry import cable_borders, score_line_pair
from benchmark.modalities.camera.model import CableState
from benchmark.model import Outcome

SIZE = (320, 240)
PARAMS = SegmentationParams()


def test_the_pyramid_tiles_the_image_at_each_level():
    cells = cell_pyramid((320, 240), 3)
    assert len(cells) == 1 + 4 + 16
    for level, (first, count) in enumerate([(0, 1), (1, 4), (5, 16)]):
        cover = np.zeros((240, 320), int)
        for rows, cols in cells[first : first + count]:
            cover[rows, cols] += 1
        assert np.all(cover == 1), f"level {level + 1}"


@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(
    d=st.floats(-90.0, 90.0),
    alpha_deg=st.floats(-30.0, 30.0),
    w=st.floats(12.0, 60.0),
    beta_deg=st.floats(0.0, 3.0),
    contrast=st.sampled_from([-60.0, 60.0]),
)
def test_a_cable_on_blank_ground_is_found(scene, d, alpha_deg, w, beta_deg, contrast):
    truth = CableState(d, math.radians(alpha_deg), w, math.radians(beta_deg))
    image = scene.cable(truth, contrast=contrast, texture=0.0, noise=0.0)
    pair = detect(image, PARAMS)
    assert pair is not None
    assert score_line_pair(pair.borders, cable_borders(truth), SIZE) is Outcome.CORRECT


@pytest.mark.parametrize("contrast", [-50.0, 50.0], ids=["dark", "bright"])
def test_a_cable_on_textured_sand_is_found(scene, contrast):
    truth = CableState(-20.0, math.radians(10.0), 30.0, math.radians(2.0))
    pair = detect(scene.cable(truth, contrast=contrast, seed=5), PARAMS)
    assert pair is not None
    assert score_line_pair(pair.borders, cable_borders(truth), SIZE) is Outcome.CORRECT


def test_blank_and_sand_only_images_give_no_pair(scene):
    assert detect(np.full((240, 320), 90, np.uint8), PARAMS) is None
    for seed in range(3):
        image = np.clip(np.rint(scene.ground(SIZE, seed, 130.0, 10.0, 4.0)), 0, 255).astype(np.uint8)
        assert detect(image, PARAMS) is None
