"""Rendered frames agree with their ground truth, and repeat bit for bit."""

from __future__ import annotations

import math
import pickle

import numpy as np
import pytest

from benchmark.modalities.camera.geometry import cable_borders
from benchmark.modalities.camera.scenes.render import remap_flat
from benchmark.modalities.camera.scenes.scene import CameraScene

SAND, PIPE = 200, 25  # grey levels of the flat scene: 0.8 and 0.1 times the exposure 250


def _border_columns(line, rows: np.ndarray, size=(320, 240)) -> np.ndarray:
    """Pixel column where a model-coordinate line crosses each pixel row."""
    width, height = size
    y = (height - 1) / 2 - rows
    x = line.x0 + (y - line.y0) * line.dx / line.dy
    return x + (width - 1) / 2


@pytest.fixture(scope="module")
def flat_frames(flat_scene_data):
    return list(CameraScene.from_dict(flat_scene_data).frames())


@pytest.mark.parametrize("index", range(6))
def test_silhouette_agrees_with_the_truth_marks(flat_frames, index: int) -> None:
    frame = flat_frames[index]
    image, state = frame.observation, frame.truth.cable
    assert state.w > 10 and abs(state.alpha) < math.radians(40)
    left, right = cable_borders(state)
    rows = np.arange(0, 240, 7)
    u_left, u_right = _border_columns(left, rows), _border_columns(right, rows)
    checked = 0
    for row, a, b in zip(rows, u_left, u_right):
        for column, expected in ((a - 2, SAND), (a + 2, PIPE), (b - 2, PIPE), (b + 2, SAND)):
            col = round(column)
            if 0 <= col < 320:
                assert image[row, col] == expected, (row, column)
                checked += 1
    assert checked > 40


def test_pipe_middle_is_brighter_than_its_flanks(flat_scene) -> None:
    data = flat_scene(n_frames=1)
    data["optics"] = dict(data["optics"], ambient=0.1)
    data["motion"] = {"cy_m": {"mean": 1.0}, "phi_deg": {"mean": 90.0}, "speed_noise_mps": 0.0}
    scene = CameraScene.from_dict(data)
    image = scene.render(0).astype(int)
    state = scene.truth(0).cable
    middle = 159.5 + state.d
    row = image[120]
    assert row[round(middle)] > row[round(middle - 0.4 * state.w)] > row[round(middle - 0.49 * state.w)]


def test_buried_pipe_shows_only_sand(flat_scene) -> None:
    scene = CameraScene.from_dict(flat_scene(n_frames=2, burial=[{"z_m": [-20.0, 20.0], "level": 1.3}]))
    for frame in scene.frames():
        assert frame.truth.visible_fraction == 0.0
        assert frame.observation.min() > 150  # no pipe grey anywhere
        assert frame.truth.cable.w > 0  # the truth still knows where it is


def test_same_seed_gives_identical_frames_and_another_seed_does_not() -> None:
    data = {"name": "camera/textured", "n_frames": 3, "seed": 11, "cable": {"growth_coverage": 0.4},
            "seabed": {"ripples": [{}], "clutter": [{"rocks_per_m2": 5.0}]}, "optics": {"snow_per_frame": 5.0}}
    first = [f.observation.tobytes() for f in CameraScene.from_dict(data).frames()]
    again = [f.observation.tobytes() for f in CameraScene.from_dict(data).frames()]
    other = [f.observation.tobytes() for f in CameraScene.from_dict(dict(data, seed=12)).frames()]
    assert first == again
    assert all(a != b for a, b in zip(first, other))
    assert len(set(first)) == 3


def test_random_access_and_pickling_give_the_streamed_frames() -> None:
    scene = CameraScene.from_dict({"name": "camera/stream", "n_frames": 3, "seed": 2})
    streamed = [f.observation for f in scene.frames()]
    np.testing.assert_array_equal(scene.render(1), streamed[1])
    clone = pickle.loads(pickle.dumps(scene))
    assert len(pickle.dumps(scene)) < 10_000  # the cache of maps is not pickled
    np.testing.assert_array_equal(clone.frame(2).observation, streamed[2])
    assert clone.truth(2) == scene.truth(2)


def test_remap_flat_samples_like_remap_on_a_grid() -> None:
    source = np.arange(64 * 32, dtype=np.float32).reshape(64, 32)
    rng = np.random.default_rng(0)
    col, row = rng.uniform(0, 31, 3000).astype(np.float32), rng.uniform(0, 63, 3000).astype(np.float32)
    # Bilinear interpolation of a linear ramp is the ramp itself; OpenCV may
    # round coordinates to 1/32 texel, i.e. up to 0.5 grey on a slope of 32.
    expected = row * 32 + col
    np.testing.assert_allclose(remap_flat(source, col, row), expected, atol=0.6)
    two = remap_flat(np.stack((source, -source), axis=-1), col, row)
    assert two.shape == (3000, 2)
    np.testing.assert_allclose(two[:, 0], expected, atol=0.6)
    np.testing.assert_allclose(two[:, 1], -expected, atol=0.6)


OVERGROWTH = {
    "x_m": 0.4,
    "mat_cover": 0.25,
    "mat_albedo": 0.5,
    "fronds_per_m": 6.0,
    "frond_albedo": 0.5,
    "side_stones_per_m": 3.0,
    "top_stones_per_m": 1.0,
    "stone_albedo": 0.5,
}
"""Overgrowth of mid-grey albedo, neither the flat scene's sand nor its pipe."""


def test_overgrowth_hides_part_of_the_borders_in_an_untextured_scene(flat_scene) -> None:
    scene = CameraScene.from_dict(flat_scene(overgrowth=[OVERGROWTH]))
    hidden = checked = sand_covered = 0
    for frame in scene.frames():
        left, right = cable_borders(frame.truth.cable)
        rows = np.arange(0, 240, 3)
        for line, inward in ((left, 2), (right, -2)):
            for row, u in zip(rows, _border_columns(line, rows)):
                pipe_side, sand_side = round(u + inward), round(u - inward)
                if 0 <= pipe_side < 320 and 0 <= sand_side < 320:
                    checked += 1
                    hidden += int(frame.observation[row, pipe_side] != PIPE)
                    sand_covered += int(frame.observation[row, sand_side] != SAND)
    assert checked > 500
    # Overgrowth crosses the borders in places, but most of their length stays bare.
    assert 0.05 < hidden / checked < 0.6
    assert sand_covered / checked > 0.05


def test_overgrowth_with_zero_density_renders_exactly_as_none() -> None:
    data = {"name": "camera/plain", "n_frames": 2, "seed": 11, "seabed": {"clutter": [{"rocks_per_m2": 5.0}]}}
    zero = dict(data, overgrowth=[dict(OVERGROWTH, density=[[0.0, 0.0]])])
    plain = [f.observation for f in CameraScene.from_dict(data).frames()]
    for frame, expected in zip(CameraScene.from_dict(zero).frames(), plain):
        np.testing.assert_array_equal(frame.observation, expected)
    dense = CameraScene.from_dict(dict(data, overgrowth=[OVERGROWTH])).render(0)
    assert np.mean(dense != plain[0]) > 0.02


def test_overgrowth_repeats_bit_for_bit_for_a_seed() -> None:
    data = {"name": "camera/overgrown", "n_frames": 2, "seed": 21, "overgrowth": [OVERGROWTH]}
    first = [f.observation.tobytes() for f in CameraScene.from_dict(data).frames()]
    again = [f.observation.tobytes() for f in CameraScene.from_dict(data).frames()]
    other = CameraScene.from_dict(dict(data, seed=22)).render(0).tobytes()
    assert first == again and other != first[0]
