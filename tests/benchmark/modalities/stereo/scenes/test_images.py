"""Rendered stereo sequences: spec, determinism, pickling and where things appear in the images."""

from __future__ import annotations

import math
import pickle

import numpy as np
import pytest

from benchmark.errors import DataError
from benchmark.modalities.stereo.geometry import project
from benchmark.modalities.stereo.model import StereoTruth
from benchmark.modalities.stereo.scenes.image_spec import StereoImageSceneSpec
from benchmark.modalities.stereo.scenes.images import StereoImageScene
from benchmark.modalities.stereo.scenes.render import StereoView
from benchmark.modalities.stereo.scenes.scene import StereoScene

SPEC = {
    "name": "stereo-images/test",
    "n_frames": 6,
    "seed": 11,
    "target": {"start_m": 8.0, "speed_knots": [[0.0, 3.0]], "path": {"course_deg": 30.0}},
    "chase": {"speed_knots": [[0.0, 2.0]], "path": {"course_deg": 30.0}},
}


@pytest.fixture(scope="module")
def scene() -> StereoImageScene:
    return StereoImageScene.from_dict(SPEC)


def yellowness(image: np.ndarray) -> np.ndarray:
    """How far red and green stand above blue: positive only on the marker, lit or shaded, and its blended edges."""
    b, g, r = (image[..., c].astype(float) for c in range(3))
    return np.clip(np.minimum(r, g) - b - 40.0, 0.0, None)


def yellow_centroid(image: np.ndarray) -> float:
    """Yellowness-weighted mean column."""
    weight = yellowness(image)
    return float((weight * np.arange(image.shape[1])).sum() / weight.sum())


def test_spec_takes_a_render_table_and_names_bad_keys() -> None:
    spec = StereoImageSceneSpec.from_dict({**SPEC, "render": {"height_px": 120, "marker_radius_m": 0.4}})
    assert spec.frame_size == (320, 120)
    assert spec.render.marker_radius_m == 0.4
    with pytest.raises(DataError, match=r"here: render: unknown key 'colour' \(known: height_px, "):
        StereoImageSceneSpec.from_dict({**SPEC, "render": {"colour": 1}}, "here")
    with pytest.raises(DataError, match="marker must fit"):
        StereoImageSceneSpec.from_dict({**SPEC, "render": {"marker_radius_m": 1.0}})


def test_frames_are_bgr_pairs_with_the_truth_and_navigation_of_the_simulated_scene(scene) -> None:
    info = scene.info
    assert (info.modality, info.frame_size, info.n_frames, info.frame_interval_s) == ("stereo", (320, 240), 6, 0.2)
    assert info.calibration == scene.spec.camera.calibration()
    assert info.extra["seed"] == 11
    simulated = StereoScene.from_dict(SPEC)
    frames = list(scene.frames())
    assert [frame.index for frame in frames] == list(range(6))
    for frame in frames[:2]:
        left, right = frame.observation
        assert left.shape == right.shape == (240, 320, 3)
        assert left.dtype == right.dtype == np.uint8
        assert isinstance(frame.truth, StereoTruth)
        assert frame.truth == simulated.truth(frame.index)
        assert frame.navigation == simulated.navigation(frame.index)
        assert frame.time_s == pytest.approx(0.2 * frame.index)


def test_same_spec_same_pixels_any_frame_on_its_own_and_after_pickling(scene) -> None:
    first = scene.pair(3)
    again = StereoImageScene.from_dict(SPEC).pair(3)
    thawed = pickle.loads(pickle.dumps(scene))
    assert len(pickle.dumps(scene)) < 10_000
    for a, b, c in zip(first, again, thawed.pair(3)):
        np.testing.assert_array_equal(a, b)
        np.testing.assert_array_equal(a, c)
    other = StereoImageScene.from_dict({**SPEC, "seed": 12}).pair(3)
    assert not np.array_equal(first[0], other[0])
    # The sensor noise differs from frame to frame and between the two cameras.
    assert not np.array_equal(scene.pair(2)[0], first[0])


@pytest.mark.parametrize(
    ("ahead", "starboard", "aspect_deg"),
    [(6.0, 0.0, 0.0), (9.0, 2.5, 20.0), (15.0, -3.0, -35.0), (23.0, 1.0, 10.0)],
)
def test_the_marker_appears_where_eq_15_projects_the_target(scene, ahead, starboard, aspect_deg) -> None:
    view = StereoView((40.0, -25.0), math.radians(75.0), ahead, starboard, math.radians(aspect_deg), 3.0)
    left, right = scene.renderer.render_pair(view, np.random.default_rng(0))
    y_l, y_r = project(ahead, starboard, scene.info.calibration)
    assert np.count_nonzero(yellowness(left)) >= 6 and np.count_nonzero(yellowness(right)) >= 6
    c_l, c_r = yellow_centroid(left), yellow_centroid(right)
    assert abs(c_l - y_l) < 1.0
    assert abs(c_r - y_r) < 1.0
    # Both images see the drum alike (same shading), so its centroid shifts by the disparity f B / x.
    assert abs((c_l - c_r) - (y_l - y_r)) < 0.15


def test_no_marker_when_the_target_is_out_of_view(scene) -> None:
    view = StereoView((0.0, 0.0), 0.4, 4.0, 12.0, 0.0, 1.0)
    for image in scene.renderer.render_pair(view, np.random.default_rng(1)):
        assert not yellowness(image).any()


def test_the_sea_pattern_has_the_disparity_of_its_distance() -> None:
    quiet = StereoImageScene.from_dict({**SPEC, "render": {"noise_grey": 0.0, "glint": 0.0}})
    renderer = quiet.renderer
    view = StereoView((3.0, 7.0), 1.1, 30.0, 0.0, 0.0, 0.0)
    left, right = renderer.render_pair(view, np.random.default_rng(2))
    row = 160
    distance = 1.0 * 140.8 / (row - 119.5)
    expected = 140.8 * 0.12 / distance
    a = left[row - 1 : row + 2, 40:280, 1].astype(float)
    costs = []
    for shift in range(0, 12):
        b = right[row - 1 : row + 2, 40 - shift : 280 - shift, 1].astype(float)
        costs.append(np.abs(a - b).mean())
    best = int(np.argmin(costs))
    assert abs(best - expected) <= 1.0
    assert costs[best] < 0.5 * costs[0]


def test_frame_index_out_of_range(scene) -> None:
    with pytest.raises(IndexError, match="frame 6 out of range"):
        scene.pair(6)
