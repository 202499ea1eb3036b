"""Blank, saturated and noise images, shaped like the frame's own."""

from __future__ import annotations

import numpy as np

from benchmark.modalities.camera.hard_observations import hard_observations
from benchmark.model import Frame, SequenceInfo

INFO = SequenceInfo(name="S", modality="camera", n_frames=1, frame_size=(32, 24), frame_interval_s=0.04)


def made(image: np.ndarray, seed: int = 0) -> dict[str, np.ndarray]:
    return hard_observations(Frame(0, image, None), INFO, np.random.default_rng(seed))


def test_kinds_shapes_and_values() -> None:
    image = np.full((24, 32), 90, dtype=np.uint8)
    images = made(image)
    assert list(images) == ["blank", "saturated", "noise"]
    assert all(made.shape == image.shape and made.dtype == np.uint8 for made in images.values())
    assert not images["blank"].any()
    assert (images["saturated"] == 255).all()
    assert images["noise"].std() > 50 and images["noise"].min() < 20 and images["noise"].max() > 235
    assert (image == 90).all()


def test_noise_is_a_function_of_the_generator() -> None:
    image = np.zeros((24, 32), dtype=np.uint8)
    assert np.array_equal(made(image, 3)["noise"], made(image, 3)["noise"])
    assert not np.array_equal(made(image, 3)["noise"], made(image, 4)["noise"])


def test_float_images_saturate_at_one() -> None:
    images = made(np.full((4, 5), 0.5))
    assert (images["saturated"] == 1.0).all()
    assert images["noise"].dtype == float and 0.0 <= images["noise"].min() <= images["noise"].max() <= 1.0
