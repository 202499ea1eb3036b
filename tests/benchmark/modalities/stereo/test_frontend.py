"""The image front end: colour tracker, block-matching disparity, upper-half median, eq. (15)."""

from __future__ import annotations

import math

import cv2
import numpy as np
import pydantic
import pytest
from hypothesis import given
from hypothesis import strategies as st

from benchmark.errors import DataError
from benchmark.modalities.stereo.frontend import FrontEndParams, find_marker, measure, upper_half_median
from benchmark.modalities.stereo.model import StereoCalibration
from benchmark.modalities.stereo.scenes.images import StereoImageScene
from benchmark.modalities.stereo.scenes.render import StereoView

CALIBRATION = StereoCalibration(
    focal_px=140.8,
    baseline_m=0.12,
    principal_left_px=159.5,
    principal_right_px=159.5,
    width_px=320,
    range_limit_m=16.0,
    correlation_accuracy_px=0.11,
)
YELLOW = np.array((20.0, 200.0, 235.0))


def textured_pair(disparity: float, column: float = 150.0, seed: int = 0) -> tuple[np.ndarray, np.ndarray]:
    """A grey textured background at zero disparity and a striped yellow square shifted by ``disparity`` px."""
    rng = np.random.default_rng(seed)
    background = cv2.GaussianBlur(rng.uniform(60, 200, (240, 320)).astype(np.float32), (0, 0), 1.5)
    background = np.repeat(background[..., None], 3, axis=2)
    cols = np.arange(320, dtype=np.float32)

    def layer(centre: float) -> tuple[np.ndarray, np.ndarray]:
        # Coverage of a 14 px wide square, exact to a fraction of a pixel, with a dark stripe down its middle.
        cover = np.clip(np.minimum(cols - (centre - 7.0), (centre + 7.0) - cols) + 0.5, 0.0, 1.0)
        stripe = 1.0 - 0.6 * np.clip(1.5 - np.abs(cols - centre), 0.0, 1.0)
        alpha = np.zeros((240, 320), dtype=np.float32)
        alpha[110:126] = cover
        shade = np.ones((240, 320), dtype=np.float32)
        shade[110:126] = stripe
        return alpha[..., None], YELLOW * shade[..., None]

    images = []
    for centre in (column, column - disparity):
        alpha, colour = layer(centre)
        image = background * (1.0 - alpha) + colour * alpha + rng.normal(0.0, 1.0, background.shape)
        images.append(np.clip(image + 0.5, 0, 255).astype(np.uint8))
    return images[0], images[1]


@pytest.mark.parametrize("disparity", [0.8, 1.4, 2.7])
def test_disparity_and_position_of_a_shifted_marker(disparity: float) -> None:
    left, right = textured_pair(disparity)
    measurement = measure(left, right, CALIBRATION)
    assert measurement is not None
    assert measurement.left_px == pytest.approx(150.0, abs=0.3)
    # The upper-half median leans towards the larger disparities by a fraction of their spread.
    assert -0.1 < (measurement.left_px - measurement.right_px) - disparity < 0.25
    x, y = measurement.relative_m
    d = measurement.left_px - measurement.right_px
    assert x == pytest.approx(140.8 * 0.12 / d)
    assert y == pytest.approx(0.12 * (measurement.left_px - 159.5) / d)


def test_nothing_when_the_pair_says_the_marker_is_at_infinity_or_behind() -> None:
    left, right = textured_pair(1.5)
    assert measure(left, left, CALIBRATION) is None
    assert measure(left, left, CALIBRATION, FrontEndParams(min_disparity_px=0.0)) is not None
    # Swapped images: the marker seems to move the wrong way between the cameras.
    assert measure(right, left, CALIBRATION) is None


def test_nothing_without_a_yellow_blob() -> None:
    left, right = textured_pair(1.5)
    grey = cv2.cvtColor(cv2.cvtColor(left, cv2.COLOR_BGR2GRAY), cv2.COLOR_GRAY2BGR)
    assert find_marker(grey, FrontEndParams()) is None
    assert measure(grey, grey, CALIBRATION) is None


def test_the_largest_yellow_component_is_the_marker() -> None:
    left, _ = textured_pair(1.5, column=200.0)
    left[30:33, 40:43] = YELLOW.astype(np.uint8)
    blob = find_marker(left, FrontEndParams())
    assert blob is not None and blob.column_px == pytest.approx(200.0, abs=0.3)
    assert np.count_nonzero(blob.mask) >= 14 * 16


@given(st.lists(st.floats(-3.0, 14.0, allow_nan=False), min_size=1, max_size=60))
def test_upper_half_median_lies_between_the_median_and_the_largest(values: list[float]) -> None:
    result = upper_half_median(np.array(values))
    assert np.median(values) - 1e-9 <= result <= max(values) + 1e-9


def test_upper_half_median_ignores_a_far_minority() -> None:
    assert upper_half_median(np.array([0.1, 0.2, 0.1, 1.5, 1.6, 1.5, 1.4])) == pytest.approx(1.5)
    assert upper_half_median(np.array([2.0])) == 2.0


def test_bad_inputs_and_parameters_are_named() -> None:
    left, right = textured_pair(1.5)
    with pytest.raises(DataError, match="right image"):
        measure(left, right[..., 0], CALIBRATION)
    with pytest.raises(DataError, match="differ in shape"):
        measure(left, right[:200], CALIBRATION)
    with pytest.raises(pydantic.ValidationError, match="block_size"):
        FrontEndParams(block_size=8)
    with pytest.raises(pydantic.ValidationError, match="num_disparities"):
        FrontEndParams(num_disparities=24)
    with pytest.raises(pydantic.ValidationError, match="prefilter"):
        FrontEndParams(prefilter="laplace")


@pytest.mark.parametrize(
    "bad",
    [
        {"hue_min": -1},
        {"hue_max": 180},
        {"hue_min": 50},
        {"saturation_min": 256},
        {"value_min": -1},
        {"min_blob_px": 0},
        {"num_disparities": 0},
        {"block_size": 3},
        {"block_size": 257},
        {"texture_threshold": -1},
        {"prefilter_size": 10},
        {"prefilter_cap": 0},
        {"prefilter_cap": 64},
        {"speckle_window": -5},
        {"min_disparity_px": -0.1},
        {"min_disparity_px": math.inf},
        {"block_size": 9.5},
    ],
)
def test_parameters_outside_their_declared_domains_are_refused(bad) -> None:
    (name,) = bad
    with pytest.raises(pydantic.ValidationError, match=name):
        FrontEndParams(**bad)


def test_parameters_at_the_ends_of_their_domains_are_accepted() -> None:
    edges = FrontEndParams(hue_min=0, hue_max=179, block_size=255, prefilter_size=5, prefilter_cap=1, num_disparities=32)
    assert (edges.hue_min, edges.hue_max, edges.block_size, edges.num_disparities) == (0, 179, 255, 32)
    assert FrontEndParams(hue_min=40, hue_max=40, min_disparity_px=0.0).hue_min == 40


@pytest.fixture(scope="module")
def rendered() -> StereoImageScene:
    return StereoImageScene.from_dict({"name": "stereo-images/frontend", "n_frames": 1, "seed": 5})


def view(ahead: float, starboard: float, aspect_deg: float = 0.0, time_s: float = 0.0) -> StereoView:
    return StereoView((120.0, 310.0), math.radians(200.0), ahead, starboard, math.radians(aspect_deg), time_s)


@pytest.mark.parametrize(
    ("ahead", "starboard", "aspect_deg"),
    [(6.5, 0.5, 0.0), (8.0, -1.0, 15.0), (11.0, 2.0, -20.0), (14.0, 0.0, 5.0), (19.0, -2.0, 0.0)],
)
def test_rendered_marker_gives_the_target_within_a_tolerance_growing_with_range(
    rendered, ahead, starboard, aspect_deg
) -> None:
    left, right = rendered.renderer.render_pair(view(ahead, starboard, aspect_deg, ahead), np.random.default_rng(7))
    measurement = measure(left, right, rendered.info.calibration)
    assert measurement is not None
    x, y = measurement.relative_m
    # 0.5 m plus the depth error of a quarter-pixel disparity error (seeds/002, Table 3).
    tolerance = 0.5 + ahead**2 / (140.8 * 0.12) * 0.25
    assert math.hypot(x - ahead, y - starboard) < tolerance
    assert abs(y - starboard) < 0.3


def test_rendered_marker_near_the_image_border_is_still_measured(rendered) -> None:
    starboard = 8.0 * (4.0 - 159.5) / 140.8
    left, right = rendered.renderer.render_pair(view(8.0, starboard), np.random.default_rng(3))
    measurement = measure(left, right, rendered.info.calibration)
    assert measurement is not None
    assert measurement.left_px < 8.0
    assert measurement.relative_m[0] == pytest.approx(8.0, abs=1.5)


def test_nothing_when_the_rendered_target_is_off_screen(rendered) -> None:
    for ahead, starboard in ((3.0, 10.0), (5.0, -9.0)):
        left, right = rendered.renderer.render_pair(view(ahead, starboard), np.random.default_rng(4))
        assert measure(left, right, rendered.info.calibration) is None
