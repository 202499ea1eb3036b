"""Tests of the region classes and their classifier (seeds/000, section 2.2)."""

from __future__ import annotations

import numpy as np
import pytest
from trackbench_texture.classes import Region, split_ground, train_regions
from trackbench_texture.descriptors import NAMES

from benchmark.errors import DataError

BLUR = NAMES.index("blurriness")
CUTS = NAMES.index("discontinuity")


def _ground(rng: np.random.Generator, n: int = 200) -> np.ndarray:
    """Half smooth ground (blurry), half cluttered ground (cut lines, little blur)."""
    smooth = np.zeros((n, 5))
    smooth[:, BLUR] = rng.uniform(0.9, 1.0, n)
    cluttered = np.zeros((n, 5))
    cluttered[:, BLUR] = rng.uniform(0.3, 0.5, n)
    cluttered[:, CUTS] = rng.uniform(0.1, 0.2, n)
    return np.vstack([smooth, cluttered])


def test_ground_splits_into_blurry_sand_and_cluttered_stones_and_vegetation():
    labels = split_ground(_ground(np.random.default_rng(0)), np.random.default_rng(1))
    assert np.all(labels[:200] == Region.SAND)
    assert np.all(labels[200:] == Region.STONES_AND_VEGETATION)


def test_uniform_ground_is_all_sand():
    labels = split_ground(np.tile([0.0, 0.0, 0.0, 0.0, 1.0], (50, 1)), np.random.default_rng(0))
    assert np.all(labels == Region.SAND)


def _training(rng: np.random.Generator) -> tuple[np.ndarray, np.ndarray]:
    cable = np.zeros((200, 5))
    cable[:, 0] = rng.uniform(0.2, 0.3, 200)
    cable[:, BLUR] = rng.uniform(0.6, 0.7, 200)
    descriptors = np.vstack([cable, _ground(rng)])
    return descriptors, np.arange(len(descriptors)) < 200


def test_the_classifier_learns_all_classes_and_labels_an_image():
    descriptors, on_cable = _training(np.random.default_rng(0))
    classifier = train_regions(descriptors, on_cable, 20, 0.5, np.random.default_rng(0))
    assert set(classifier.regions) == {Region.CABLE, Region.SAND, Region.STONES_AND_VEGETATION}
    image = np.stack([descriptors[:100], descriptors[200:300], descriptors[400:500]]).astype(np.float32)
    regions = classifier.classify(image)
    assert regions.shape == (3, 100) and regions.dtype == np.uint8
    assert np.all(regions[0] == Region.CABLE)
    assert np.all(regions[1] == Region.SAND)
    assert np.all(regions[2] == Region.STONES_AND_VEGETATION)


def test_pixels_below_the_confidence_are_undefined():
    descriptors, on_cable = _training(np.random.default_rng(0))
    classifier = train_regions(descriptors, on_cable, 20, 1.0, np.random.default_rng(0))
    regions = classifier.classify(descriptors[None, :50].astype(np.float32))
    assert np.all(regions == Region.UNDEFINED)


@pytest.mark.parametrize("missing", ["cable", "ground"])
def test_learning_without_cable_or_without_ground_is_a_data_error(missing):
    descriptors, _ = _training(np.random.default_rng(0))
    on_cable = np.full(len(descriptors), missing == "ground")
    with pytest.raises(DataError, match=f"no {missing} pixel"):
        train_regions(descriptors, on_cable, 5, 0.5, np.random.default_rng(0))
