"""A lost target, a decoy in view, and blank, saturated and noisy image pairs."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from benchmark.modalities.stereo.geometry import triangulate
from benchmark.modalities.stereo.hard_observations import decoy, hard_observations
from benchmark.modalities.stereo.modality import STEREO
from benchmark.model import Frame, SequenceInfo


def first(kind: str) -> tuple[Frame, SequenceInfo]:
    scene = STEREO.scene_kinds[kind]({"name": "hard", "n_frames": 1, "seed": 2}, "test")
    return next(iter(scene.frames())), scene.info


def test_measurement_frames_get_a_lost_target_and_a_decoy() -> None:
    frame, info = first("stereo")
    observations = hard_observations(frame, info, np.random.default_rng(0))
    assert list(observations) == ["lost", "decoy"]
    assert observations["lost"] is None


@pytest.mark.parametrize("seed", range(20))
def test_a_decoy_is_in_view_and_triangulates_to_its_position(seed: int) -> None:
    _, info = first("stereo")
    calibration = info.calibration
    measurement = decoy(calibration, np.random.default_rng(seed))
    if measurement is None:
        pytest.skip("this draw fell outside the image")
    assert 0.0 <= measurement.left_px < calibration.width_px and 0.0 <= measurement.right_px < calibration.width_px
    ahead, starboard = triangulate(measurement.left_px, measurement.right_px, calibration)
    assert np.allclose((ahead, starboard), measurement.relative_m, rtol=1e-9, atol=1e-9)
    assert 0.0 < ahead <= calibration.range_limit_m


def test_image_pairs_get_blank_saturated_and_noise_pairs() -> None:
    frame, info = first("stereo-images")
    observations = hard_observations(frame, info, np.random.default_rng(0))
    assert list(observations) == ["lost", "decoy", "blank", "saturated", "noise"]
    left, right = frame.observation
    for kind in ("blank", "saturated", "noise"):
        pair = observations[kind]
        assert [image.shape for image in pair] == [left.shape, right.shape]
        assert all(image.dtype == np.uint8 for image in pair)
    assert not any(image.any() for image in observations["blank"])
    assert all((image == 255).all() for image in observations["saturated"])
    assert all(image.std() > 50 for image in observations["noise"])


def test_without_a_calibration_there_is_no_decoy() -> None:
    frame, info = first("stereo")
    observations = hard_observations(frame, dataclasses.replace(info, calibration=None), np.random.default_rng(0))
    assert list(observations) == ["lost"]
