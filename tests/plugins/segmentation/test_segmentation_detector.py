"""Tests of one frame's detection process (seeds/000, section 2.3, Fig. 2.5) on drawn cables."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from trackbench_segmentation.detector import cell_pyramid, detect
from trackbench_segmentation.params import PAPER, SegmentationParams

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


@pytest.mark.parametrize("contrast", [-10.0, 12.0], ids=["dark", "bright"])
def test_a_murky_cable_is_found_on_normalised_grey_levels_and_missed_on_raw_ones(scene, contrast):
    # A cable 10-12 grey levels off its ground: in raw grey levels its borders stay below the paper's gradient cut.
    truth = CableState(-15.0, math.radians(5.0), 30.0, math.radians(1.0))
    image = scene.cable(truth, contrast=contrast, seed=3, texture=3.0, noise=2.0)
    pair = detect(image, PARAMS)
    assert pair is not None
    assert score_line_pair(pair.borders, cable_borders(truth), SIZE) is Outcome.CORRECT
    assert detect(image, SegmentationParams(**PAPER)) is None


def test_a_pipe_of_250_px_is_found_in_a_640_px_frame(scene):
    # Half again the paper's largest width at 320 x 240: plausible once widths follow the frame size.
    size = (640, 480)
    truth = CableState(40.0, math.radians(4.0), 250.0, math.radians(2.0))
    image = scene.cable(truth, seed=1, size=size)
    pair = detect(image, PARAMS)
    assert pair is not None
    assert score_line_pair(pair.borders, cable_borders(truth), size) is Outcome.CORRECT
    unscaled = detect(image, SegmentationParams(reference_width_px=None))
    assert unscaled is None or score_line_pair(unscaled.borders, cable_borders(truth), size) is Outcome.FALSE


@pytest.mark.parametrize("texture, noise", [(10.0, 4.0), (3.0, 8.0)])
def test_stretched_sand_gives_no_pair_its_lines_are_not_steeper_than_the_ground(scene, texture, noise):
    # Normalisation stretches bare sand to the full range; the gradient level keeps its lines out.
    image = np.clip(np.rint(scene.ground(SIZE, 7, 130.0, texture, noise)), 0, 255).astype(np.uint8)
    assert detect(image, PARAMS) is None
    assert detect(image, dataclasses.replace(PARAMS, min_gradient_ratio=0.0)) is not None


@settings(max_examples=15, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(gain=st.floats(0.15, 1.0), offset=st.floats(-60.0, 60.0), seed=st.integers(0, 50))
def test_the_detection_does_not_depend_on_the_frame_s_contrast(scene, gain, offset, seed):
    # The same scene seen through murkier water: grey levels pulled towards a veil, noise as before.
    truth = CableState(10.0, math.radians(-6.0), 28.0, math.radians(1.0))
    clear = scene.cable(truth, contrast=-60.0, seed=seed, level=128.0, texture=8.0, noise=0.0).astype(np.float32)
    murky = 128.0 + offset + gain * (clear - 128.0)
    image = np.clip(np.rint(murky + np.random.default_rng(seed).normal(0.0, 1.0, murky.shape)), 0, 255)
    pair = detect(image.astype(np.uint8), PARAMS)
    assert pair is not None
    assert score_line_pair(pair.borders, cable_borders(truth), SIZE) is Outcome.CORRECT
