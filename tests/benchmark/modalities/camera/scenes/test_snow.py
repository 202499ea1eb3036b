"""Marine snow: particles placed once per sequence, splatted in and out of focus."""

from __future__ import annotations

import numpy as np

from benchmark.modalities.camera.scenes.snow import SnowCloud, splat


def test_a_cloud_is_a_poisson_number_of_particles_inside_its_box() -> None:
    box = ((-1.0, 1.0), (0.0, 2.0), (0.0, 5.0))
    cloud = SnowCloud.draw(np.random.default_rng(1), box, per_m3=50.0, size_mm=1.5)
    assert 800 < len(cloud) < 1200
    for axis, (low, high) in enumerate(box):
        assert np.all((cloud.positions[axis] >= low) & (cloud.positions[axis] <= high))
    again = SnowCloud.draw(np.random.default_rng(1), box, per_m3=50.0, size_mm=1.5)
    assert np.array_equal(cloud.positions, again.positions)


def test_a_bright_particle_lights_its_pixels_and_leaves_the_rest() -> None:
    image = np.full((40, 60), 50.0, dtype=np.float32)
    splat(image, np.array([[30.0], [20.0]]), np.array([3.0]), np.array([0.5]), np.array([200.0]))
    assert image[20, 30] > 100.0
    assert np.allclose(image[:5], 50.0) and np.allclose(image[:, :10], 50.0)


def test_a_defocused_particle_spreads_its_light_thinner() -> None:
    sharp = np.zeros((80, 80), dtype=np.float32)
    blurred = np.zeros((80, 80), dtype=np.float32)
    where, size, light = np.array([[40.0], [40.0]]), np.array([2.0]), np.array([100.0])
    splat(sharp, where, size, np.array([0.5]), light)
    splat(blurred, where, size, np.array([8.0]), light)
    assert blurred.max() < 0.2 * sharp.max()
    assert abs(float(blurred.sum()) - float(sharp.sum())) < 0.1 * float(sharp.sum())


def test_no_particles_change_nothing() -> None:
    image = np.full((10, 10), 7.0, dtype=np.float32)
    splat(image, np.zeros((2, 0)), np.zeros(0), np.zeros(0), np.zeros(0))
    assert np.all(image == 7.0)
