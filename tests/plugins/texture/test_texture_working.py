"""Tests of the working image: resampling to a working height and grey-level normalisation."""

from __future__ import annotations

import cv2
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from trackbench_texture.working import NORMALISERS, REFERENCE_GREY, working_image

from benchmark.modalities.camera.geometry import pixel_to_model


def _textured(height: int = 120, width: int = 160, seed: int = 0) -> np.ndarray:
    """A ``float32`` image of blurred relief around grey 0 with a spread of about 1."""
    rng = np.random.default_rng(seed)
    relief = cv2.GaussianBlur(rng.standard_normal((height, width)).astype(np.float32), (0, 0), 2.0)
    return relief / float(relief.std())


def test_the_working_image_has_the_working_height_and_the_frames_aspect():
    image = np.zeros((480, 640), np.uint8)
    work = working_image(image, 240, "none", 40.0, 0.1)
    assert work.size == (320, 240) and work.frame_size == (640, 480) and work.resampled
    kept = working_image(image, 0, "none", 40.0, 0.1)
    assert kept.size == (640, 480) and not kept.resampled


def test_a_frame_at_the_working_height_is_left_as_it_is():
    image = np.random.default_rng(0).integers(0, 256, (240, 320), dtype=np.uint8)
    assert np.array_equal(working_image(image, 240, "none", 40.0, 0.1).image, image)


def test_working_pixels_map_to_the_frame_pixels_they_average():
    work = working_image(np.zeros((480, 640), np.uint8), 240, "none", 40.0, 0.1)
    # Working pixel (u, v) averages frame pixels 2u..2u+1, 2v..2v+1: its centre is their mean.
    assert work.to_frame(0.0, 0.0) == (0.5, 0.5)
    assert work.to_frame(10.0, 7.0) == (20.5, 14.5)
    line = work.frame_line((0.0, 0.0), (0.0, 239.0))
    assert (line.x0, line.y0) == pytest.approx(pixel_to_model(0.5, 0.5, (640, 480)))
    assert abs(line.dx) == pytest.approx(0.0) and abs(line.dy) == pytest.approx(1.0)


def test_a_frame_mask_is_resampled_to_the_working_size():
    work = working_image(np.zeros((480, 640), np.uint8), 240, "none", 40.0, 0.1)
    mask = np.zeros((480, 640), bool)
    mask[:, 100:200] = True
    small = work.frame_mask(mask)
    assert small.shape == (240, 320) and small.dtype == bool
    assert small[:, 51:99].all() and not small[:, :49].any() and not small[:, 101:].any()


def test_the_global_normaliser_gives_the_reference_mean_and_spread():
    image = np.clip(100.0 + 12.0 * _textured(), 0, 255).astype(np.uint8)
    out = NORMALISERS["global"](image, 40.0, 12.0)
    assert out.dtype == np.uint8 and out.shape == image.shape
    assert float(out.mean()) == pytest.approx(REFERENCE_GREY, abs=1.0)
    assert float(out.std()) == pytest.approx(40.0, rel=0.05)


def test_a_blank_image_stays_blank_under_every_normaliser():
    blank = np.full((60, 80), 37, np.uint8)
    for name, normalise in NORMALISERS.items():
        out = normalise(blank, 40.0, 6.0)
        assert np.ptp(out) == 0, name


@given(gain=st.floats(0.5, 2.0), offset=st.floats(-20.0, 20.0), name=st.sampled_from(["global", "local"]))
def test_normalised_images_do_not_depend_on_exposure_or_contrast(gain, offset, name):
    # The invariant the normalisers exist for: the same scene at another gain
    # and offset of its grey levels gives the same working image.
    relief = _textured(seed=3)
    reference = np.clip(np.rint(120.0 + 20.0 * relief), 0, 255)
    changed = np.clip(np.rint(120.0 + offset + gain * 20.0 * relief), 0, 255)
    a = NORMALISERS[name](reference.astype(np.uint8), 40.0, 12.0).astype(int)
    b = NORMALISERS[name](changed.astype(np.uint8), 40.0, 12.0).astype(int)
    # Rounding the frames to whole grey levels moves a normalised pixel by a few levels at low gain.
    assert np.percentile(np.abs(a - b), 99) <= 5


def test_a_bad_frame_is_named():
    with pytest.raises(ValueError, match="uint8 grey image"):
        working_image(np.zeros((4, 4, 3), np.float32), 240, "none", 40.0, 0.1)


def _global_pixel_by_pixel(image: np.ndarray, spread: float) -> np.ndarray:
    """The global normaliser's first formulation: every pixel shifted, scaled and rounded in ``float32``."""
    values = image.astype(np.float32)
    mean, sd = cv2.meanStdDev(values)
    gain = spread / max(float(sd[0, 0]), 1.0)
    centred = (values - np.float32(mean[0, 0])) * np.float32(gain)
    return np.clip(np.rint(centred + np.float32(REFERENCE_GREY)), 0, 255).astype(np.uint8)


@settings(max_examples=150, deadline=None)
@given(
    shape=st.tuples(st.integers(1, 40), st.integers(1, 40)),
    seed=st.integers(0, 2**32 - 1),
    low=st.integers(0, 255),
    levels=st.integers(1, 256),
    spread=st.floats(0.5, 400.0),
)
def test_the_global_normalisers_table_of_grey_levels_equals_normalising_each_pixel(shape, seed, low, levels, spread):
    image = np.random.default_rng(seed).integers(low, min(low + levels, 256), shape, endpoint=False).astype(np.uint8)
    out = NORMALISERS["global"](image, spread, 1.0)
    assert out.dtype == np.uint8 and out.tobytes() == _global_pixel_by_pixel(image, spread).tobytes()
