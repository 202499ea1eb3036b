"""The seabed grid: smooth random fields, roughness that persists between pings, trenches, boulders."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from benchmark.modalities.sonar.scenes.seabed import (
    Boulders,
    across_grid,
    boulder_caps,
    ripple_relief,
    roughness_relief,
    scatter_boulders,
    smoothed_field,
    trench_relief,
)
from benchmark.modalities.sonar.scenes.spec import BoulderField, Ripples, Roughness, TrenchSpec


@given(st.floats(0.3, 40.0), st.sampled_from([0.02, 0.05, 0.1]))
def test_grid_is_symmetric_with_a_column_at_nadir(half_width: float, cell: float) -> None:
    across = across_grid(half_width, cell)
    assert len(across) % 2 == 1 and across[len(across) // 2] == 0.0
    assert across[-1] >= half_width and np.allclose(across, -across[::-1])
    assert np.allclose(np.diff(across), cell)


def test_smoothed_field_has_unit_variance_and_the_correlation_of_its_kernel() -> None:
    field = smoothed_field(np.random.default_rng(1), (400, 300), (3.0, 0.0))
    assert field.shape == (400, 300)
    assert field.std() == pytest.approx(1.0, abs=0.05)
    along = np.mean(field[1:] * field[:-1])
    across = np.mean(field[:, 1:] * field[:, :-1])
    # A Gaussian kernel of s cells gives the correlation exp(-d^2 / (4 s^2)) at a lag of d cells.
    assert along == pytest.approx(np.exp(-1 / 36), abs=0.03)
    assert abs(across) < 0.03


def test_smoothed_field_is_a_pure_function_of_the_generator() -> None:
    a = smoothed_field(np.random.default_rng(7), (20, 30), (2.0, 5.0))
    b = smoothed_field(np.random.default_rng(7), (20, 30), (2.0, 5.0))
    assert np.array_equal(a, b)


def test_roughness_is_correlated_between_pings_not_drawn_anew_for_each() -> None:
    across = across_grid(20.0, 0.05)
    relief = roughness_relief(np.random.default_rng(2), Roughness(0.1, 2.0), 300, 0.3, across)
    assert relief.shape == (300, len(across))
    assert relief.std() == pytest.approx(0.1, rel=0.25)
    neighbours = np.corrcoef(relief[:-1].ravel(), relief[1:].ravel())[0, 1]
    assert neighbours > 0.9
    far = np.corrcoef(relief[:-40].ravel(), relief[40:].ravel())[0, 1]
    assert abs(far) < 0.2
    # smooth across the track too: neighbouring columns nearly equal
    assert np.abs(np.diff(relief, axis=1)).max() < 0.02


def test_ripples_vary_across_the_normal_to_their_crests() -> None:
    along = np.arange(50) * 0.3
    across = across_grid(5.0, 0.05)
    parallel = ripple_relief(Ripples(0.1, 1.0, 0.0), along, across)
    assert np.allclose(parallel, parallel[0]) and np.ptp(parallel[0]) == pytest.approx(0.1, abs=1e-3)
    oblique = ripple_relief(Ripples(0.1, 1.0, 40.0), along, across)
    assert not np.allclose(oblique, oblique[0])
    assert not np.any(ripple_relief(Ripples(), along, across))


def test_trench_has_a_flat_floor_sloping_walls_and_spoil_heaps() -> None:
    across = across_grid(10.0, 0.05)
    spec = TrenchSpec(bottom_width_m=1.0, top_width_m=5.0, offset_m=0.5, berm_ratio=0.4, berm_width_m=1.0)
    relief = trench_relief(spec, np.array([0.8, 0.0, -0.3]), np.array([2.0, 2.0, 2.0]), across)
    centre = np.argmin(np.abs(across - 2.5))
    assert relief[0, centre] == pytest.approx(0.8, abs=1e-3)
    floor = np.abs(across - 2.5) <= 0.5
    assert np.allclose(relief[0, floor], relief[0, centre], atol=0.01)
    heap = np.argmin(np.abs(across - (2.5 + 2.5 + 1.0)))
    assert relief[0, heap] == pytest.approx(-0.4 * 0.8, abs=0.01)
    assert relief[0].min() == pytest.approx(-0.32, abs=0.01)
    assert not np.any(relief[1:])


def test_boulders_keep_off_the_pipes_and_follow_their_density() -> None:
    along = np.arange(400) * 0.5
    across = across_grid(15.0, 0.05)
    pipes = np.array([np.full(400, 1.0), np.full(400, -4.0)])
    widths = np.full((2, 400), 0.3)
    field = BoulderField(per_100m2=3.0, diameter_m=(0.4, 1.0), clearance_m=0.5)
    boulders = scatter_boulders(np.random.default_rng(3), field, along, across, pipes, widths)
    # about 2 x 2.3 m of the 30 m width is kept clear
    expected = 3.0 * 200.0 * (30.0 - 4.6) / 100.0
    assert 0.75 * expected < len(boulders) < 1.25 * expected
    for axis in (1.0, -4.0):
        assert np.all(np.abs(boulders.across_m - axis) > boulders.half_across_m + 0.3 + 0.5)
    assert np.all(boulders.height_m <= 0.6 * 2 * boulders.half_across_m + 1e-12)
    assert np.all((boulders.half_across_m >= 0.2) & (boulders.half_across_m <= 0.5))


def test_boulder_field_covers_only_its_stretch() -> None:
    along = np.arange(200) * 0.5
    across = across_grid(10.0, 0.05)
    field = BoulderField(per_100m2=5.0, start_frame=50.0, stop_frame=80.0)
    boulders = scatter_boulders(np.random.default_rng(4), field, along, across, np.zeros((0, 200)), np.zeros((0, 200)))
    assert len(boulders) > 0
    assert np.all((boulders.along_m >= 25.0) & (boulders.along_m <= 40.0))


def test_boulder_caps_are_half_ellipsoids_on_the_pings_they_cover() -> None:
    along = np.arange(10) * 0.5
    across = across_grid(3.0, 0.05)
    one = Boulders(*(np.array([v]) for v in (2.0, 1.0, 0.6, 0.4, 0.3)))
    caps = np.zeros((10, len(across)))
    boulder_caps(one, along, across, caps)
    top = np.argmin(np.abs(across - 1.0))
    assert caps[4, top] == pytest.approx(0.3)
    assert np.flatnonzero(caps.any(axis=1)).tolist() == [3, 4, 5]
    assert caps[3, top] == pytest.approx(0.3 * np.sqrt(1 - (0.5 / 0.6) ** 2))
    assert np.all(caps[:, np.abs(across - 1.0) >= 0.4] == 0.0)
    lower = Boulders(*(np.array([v]) for v in (2.0, 1.0, 0.6, 0.4, 0.1)))
    boulder_caps(lower, along, across, caps)
    assert caps[4, top] == pytest.approx(0.3)
