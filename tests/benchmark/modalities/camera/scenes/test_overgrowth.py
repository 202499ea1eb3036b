"""The overgrowth layer: algae and stones over the pipe and against its sides."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from benchmark.modalities.camera.scenes.overgrowth import CoverLayer, drape_height, overgrowth_layer
from benchmark.modalities.camera.scenes.spec import Overgrowth
from benchmark.modalities.camera.scenes.texture import TextureGrid

GRID = TextureGrid(x0=-1.28, z0=0.0, cell=0.01, nx=256, nz=400)
RADIUS = 0.1
DENSE = Overgrowth(
    x_m=0.4, mat_cover=0.3, fronds_per_m=10.0, side_stones_per_m=4.0, top_stones_per_m=1.0
)


def _layer(*specs: Overgrowth, seed: int = 3) -> CoverLayer | None:
    return overgrowth_layer(specs, GRID, RADIUS, np.random.default_rng(seed))


def _columns(layer: CoverLayer, lo: float, hi: float) -> slice:
    """Columns of the layer with ``lo <= X < hi``."""
    x = layer.x0 + GRID.cell * np.arange(layer.alpha.shape[1])
    inside = np.flatnonzero((x >= lo) & (x < hi))
    return slice(int(inside[0]), int(inside[-1]) + 1)


@settings(max_examples=50, deadline=None)
@given(st.floats(-0.3, 0.3), st.floats(0.02, 0.5))
def test_drape_follows_the_top_of_the_pipe_and_the_seabed_beside_it(x: float, radius: float) -> None:
    height = float(drape_height(np.array([x]), radius)[0])
    if abs(x) >= radius:
        assert height == 0.0
    else:
        # The point (x, height - r) lies on the pipe's circle, on its upper half.
        assert (height - radius) ** 2 + x * x == pytest.approx(radius * radius, rel=1e-9, abs=1e-12)
        assert radius <= height <= 2 * radius


def test_nothing_to_draw_gives_no_layer() -> None:
    assert _layer() is None
    assert _layer(Overgrowth()) is None  # every density is zero by default
    assert _layer(dataclasses.replace(DENSE, density=((0.0, 0.0),))) is None
    assert _layer(dataclasses.replace(DENSE, z_m=(50.0, 60.0))) is None  # beyond the grid


def test_same_generator_gives_the_same_layer_and_another_does_not() -> None:
    first, again, other = _layer(DENSE, seed=4), _layer(DENSE, seed=4), _layer(DENSE, seed=5)
    for name in ("alpha", "paint", "height"):
        np.testing.assert_array_equal(getattr(first, name), getattr(again, name))
    assert not np.array_equal(first.alpha, other.alpha)


@pytest.mark.parametrize("cover", [1e-17, 3.8e-60, 5e-324])
def test_a_cover_too_small_to_count_draws_no_mat(cover: float) -> None:
    bare = dataclasses.replace(DENSE, mat_cover=0.0, fronds_per_m=0.0, side_stones_per_m=0.0, top_stones_per_m=0.0)
    layer = _layer(dataclasses.replace(bare, mat_cover=cover, fronds_per_m=1.0))
    reference = _layer(dataclasses.replace(bare, fronds_per_m=1.0))
    assert layer is not None and reference is not None
    np.testing.assert_array_equal(layer.alpha, reference.alpha)


def test_layer_values_are_in_range() -> None:
    layer = _layer(DENSE)
    assert layer.alpha.dtype == np.float32 and layer.alpha.shape[0] == GRID.nz
    assert layer.alpha.min() >= 0.0 and layer.alpha.max() <= 1.0 + 1e-6
    # Premultiplied: the albedo under the paint never exceeds 1.
    assert np.all(layer.paint <= layer.alpha + 1e-6) and layer.paint.min() >= 0.0
    assert layer.height.min() >= 0.0


def test_mats_and_fronds_lie_over_the_pipe_and_beside_it() -> None:
    layer = _layer(dataclasses.replace(DENSE, side_stones_per_m=0.0, top_stones_per_m=0.0))
    over = layer.alpha[:, _columns(layer, -RADIUS, RADIUS)]
    beside = layer.alpha[:, _columns(layer, RADIUS + 0.05, 0.35)]
    assert over.mean() > 0.1 and beside.mean() > 0.1
    # Draped over the pipe, their top is above its surface.
    cols = _columns(layer, -0.5 * RADIUS, 0.5 * RADIUS)
    covered = layer.alpha[:, cols] > 0.5
    assert np.all(layer.height[:, cols][covered] > RADIUS * 1.8)


def test_stones_beside_the_pipe_hide_only_the_flank_below_their_top() -> None:
    stones = Overgrowth(side_stones_per_m=6.0, stone_size_m=0.12, stone_height=0.5)
    layer = _layer(stones)
    flank = _columns(layer, RADIUS - 0.03, RADIUS)
    covered = layer.alpha[:, flank] > 0.5
    assert covered.any()  # some stones reach into the pipe's outline
    x = layer.x0 + GRID.cell * np.arange(layer.alpha.shape[1])[flank]
    pipe_top = np.broadcast_to(drape_height(x, RADIUS), covered.shape)
    heights = layer.height[:, flank][covered]
    # Domes on the seabed: mostly lower than the pipe's top there, so the pipe shows above them.
    assert np.mean(heights < pipe_top[covered]) > 0.5
    assert heights.max() < 0.5 * 0.12 * 2.5  # at most the height ratio times a large stone
    on_top = _layer(Overgrowth(top_stones_per_m=6.0, stone_size_m=0.12))
    middle = _columns(on_top, -0.02, 0.02)
    top_covered = on_top.alpha[:, middle] > 0.5
    assert top_covered.any() and np.all(on_top.height[:, middle][top_covered] > 2 * RADIUS)


def test_density_profile_sets_where_the_overgrowth_is() -> None:
    # Dense for Z < 1.5, none beyond 2.0; fronds may reach about a metre past their roots.
    profile = dataclasses.replace(DENSE, density=((1.5, 1.0), (2.0, 0.0)))
    layer = _layer(profile)
    z = GRID.z_coords()
    assert layer.alpha[z < 1.5].mean() > 0.2
    assert np.all(layer.alpha[z > 3.0] == 0.0)
    light = _layer(dataclasses.replace(DENSE, density=((0.0, 0.2),)))
    assert light.alpha.mean() < 0.6 * _layer(DENSE).alpha.mean()


def test_fronds_along_the_pipe_make_long_edges_along_z() -> None:
    along = Overgrowth(fronds_per_m=10.0, parallel_share=1.0, frond_length_m=0.3)
    across = dataclasses.replace(along, parallel_share=0.0)
    # Edges of fronds along Z are steps across X (differences along columns), and vice versa.
    def ratio(layer: CoverLayer) -> float:
        a = layer.alpha
        return float(np.abs(np.diff(a, axis=1)).sum() / np.abs(np.diff(a, axis=0)).sum())

    assert ratio(_layer(along)) > 2.0 * ratio(_layer(across))


def test_composite_changes_the_seabed_only_where_there_is_overgrowth() -> None:
    layer = _layer(DENSE)
    seabed = np.full(GRID.shape, 0.6, dtype=np.float32)
    out = layer.composite(seabed)
    assert seabed.min() == 0.6  # the input is not modified
    band = np.zeros(GRID.shape, dtype=np.float32)
    band[:, layer.col0 : layer.col0 + layer.alpha.shape[1]] = layer.alpha
    np.testing.assert_array_equal(out[band == 0], seabed[band == 0])
    assert np.all(out[band > 0.99] < 0.6)  # mats, fronds and stones are darker than this sand


def test_pipe_band_spans_the_pipe() -> None:
    layer = _layer(DENSE)
    stack, x0 = layer.pipe_band(RADIUS)
    assert stack.shape[0] == GRID.nz and stack.shape[2] == 3 and stack.dtype == np.float32
    x_last = x0 + GRID.cell * (stack.shape[1] - 1)
    assert x0 < -RADIUS and x_last > RADIUS
    first = round((x0 - layer.x0) / GRID.cell)
    np.testing.assert_array_equal(stack[..., 0], layer.alpha[:, first : first + stack.shape[1]])
    np.testing.assert_array_equal(stack[..., 2], layer.height[:, first : first + stack.shape[1]])
