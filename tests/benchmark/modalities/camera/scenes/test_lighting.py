"""Lamps, their backscatter and the sun flicker."""

from __future__ import annotations

import math

import numpy as np
from hypothesis import given
from hypothesis import strategies as st

from benchmark.modalities.camera.scenes.lighting import (
    CausticWaves,
    backscatter_knots,
    beam_profile,
    lamp_axis,
    lamp_backscatter_table,
    lookup_backscatter,
)
from benchmark.modalities.camera.scenes.spec import Lamp
from benchmark.modalities.camera.scenes.water import water_optics

EVEN = Lamp(cone_deg=30.0, edge_deg=5.0, hotspot=0.0)


def test_the_beam_is_full_inside_the_cone_and_dark_outside() -> None:
    inside, outside = math.cos(math.radians(20.0)), math.cos(math.radians(40.0))
    assert np.allclose(beam_profile(np.array([1.0, inside]), EVEN), 1.0)
    assert np.allclose(beam_profile(np.array([outside, 0.0, -1.0]), EVEN), 0.0)


@given(a=st.floats(0.0, 89.0), b=st.floats(0.0, 89.0), hotspot=st.floats(0.0, 2.0))
def test_the_beam_weakens_away_from_its_axis(a: float, b: float, hotspot: float) -> None:
    lamp = Lamp(cone_deg=30.0, edge_deg=8.0, hotspot=hotspot)
    near, far = sorted((a, b))
    values = beam_profile(np.cos(np.radians([near, far])), lamp)
    assert values[0] >= values[1] - 1e-6
    assert 0.0 <= values[1] and values[0] <= 1.0 + hotspot + 1e-6


def test_a_lamp_is_aimed_at_the_point_the_camera_looks_at() -> None:
    axis = lamp_axis(Lamp(offset_m=(0.5, 0.0, 0.0)), aim_m=2.0)
    point = np.array((0.5, 0.0, 0.0)) + axis * math.hypot(0.5, 2.0)
    assert np.allclose(point, (0.0, 0.0, 2.0))


def _table(jerlov: str, lamps: tuple[Lamp, ...] = (Lamp(offset_m=(0.3, -0.3, 0.0)),)) -> np.ndarray:
    rays = np.array([[0.0, 0.3, -0.2], [0.0, 0.1, 0.25], [1.0, 1.0, 1.0]])
    return lamp_backscatter_table(lamps, water_optics(jerlov), rays, aim_m=2.0, max_range_m=20.0)


def test_the_lamps_backscatter_grows_with_range_and_with_turbidity() -> None:
    clear, turbid = _table("I"), _table("9C")
    assert np.all(np.diff(clear, axis=0) >= 0) and np.all(np.diff(turbid, axis=0) >= 0)
    assert np.all(turbid[-1] > 2 * clear[-1])
    assert np.all(_table("9C", ()) == 0.0)


def test_the_lamps_backscatter_saturates_in_turbid_water() -> None:
    table = _table("9C")
    knots = backscatter_knots(20.0)
    assert table[-1, 0] - table[np.searchsorted(knots, 5.0), 0] < 0.05 * table[-1, 0]


def test_backscatter_lookup_interpolates_between_knots() -> None:
    table = _table("3C")
    knots = backscatter_knots(20.0)
    at_knots = lookup_backscatter(table, 20.0, np.array([knots[5], knots[6], knots[7]], dtype=np.float32))
    assert np.allclose(at_knots, table[[5, 6, 7], [0, 1, 2]], rtol=1e-4)
    middle = lookup_backscatter(table, 20.0, np.full(3, math.sqrt(knots[5] * knots[6]), dtype=np.float32))
    assert np.all((middle >= table[5] - 1e-7) & (middle <= table[6] + 1e-7))


def test_sun_flicker_averages_one_moves_with_time_and_fades_with_depth() -> None:
    rng = np.random.default_rng(3)
    waves = CausticWaves.draw(rng, scale_m=0.3, speed_mps=0.3, surface_amplitude=1.0, depth_m=0.0)
    x, z = (a.astype(np.float32) for a in np.meshgrid(np.linspace(0, 20, 400), np.linspace(0, 20, 400)))
    now, later = waves.factor(x, z, 0.0), waves.factor(x, z, 0.5)
    assert abs(float(now.mean()) - 1.0) < 0.05
    assert np.all(now >= 0) and float(now.max()) > 3.0
    assert not np.allclose(now, later)
    deep = CausticWaves.draw(np.random.default_rng(3), 0.3, 0.3, 1.0, depth_m=30.0)
    assert float(deep.factor(x, z, 0.0).std()) < 0.05 * float(now.std())
