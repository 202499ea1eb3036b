"""Albedo maps of the seabed and of the pipe."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st

from benchmark.modalities.camera.scenes.spec import CableLook, Clutter, Ripples, SeabedSpec
from benchmark.modalities.camera.scenes.texture import (
    PSI_CELLS,
    TextureGrid,
    cable_map,
    lowpass_noise,
    profile_factor,
    profile_peak,
    seabed_map,
    zone_weight,
)

GRID = TextureGrid(x0=-1.28, z0=0.0, cell=0.01, nx=256, nz=400)


def _rng(seed: int = 3) -> np.random.Generator:
    return np.random.default_rng(seed)


def test_lowpass_noise_has_unit_variance_and_wraps_smoothly() -> None:
    field = lowpass_noise(_rng(), (256, 512), (6.0, 6.0))
    assert field.dtype == np.float32
    assert float(field.std()) == pytest.approx(1.0, abs=1e-4)
    inner = np.abs(np.diff(field, axis=0)).mean()
    seam = np.abs(field[0] - field[-1]).mean()
    assert seam < 2 * inner  # periodic: the last row is a neighbour of the first
    white_steps = np.abs(np.diff(lowpass_noise(_rng(), (256, 512), (0.0, 0.0)), axis=0)).mean()
    assert inner < 0.5 * white_steps


def test_zone_weight_is_one_inside_zero_outside() -> None:
    z = np.linspace(0.0, 4.0, 401)
    weight = zone_weight(z, (1.0, 3.0), 0.4)
    assert np.all(weight[(z >= 1.2) & (z <= 2.8)] == 1.0)
    assert np.all(weight[(z <= 0.8) | (z >= 3.2)] == 0.0)
    assert np.all((weight >= 0) & (weight <= 1))


def test_seabed_map_is_reproducible_and_in_range() -> None:
    spec = SeabedSpec(ripples=(Ripples(),), clutter=(Clutter(rocks_per_m2=5.0, algae_per_m2=3.0),))
    first, second = seabed_map(spec, GRID, _rng(4)), seabed_map(spec, GRID, _rng(4))
    np.testing.assert_array_equal(first, second)
    assert first.shape == GRID.shape and first.dtype == np.float32
    assert first.min() >= 0.01 and first.max() <= 1.0
    assert not np.array_equal(first, seabed_map(spec, GRID, _rng(5)))


def test_ripples_stay_in_their_stretch() -> None:
    plain = seabed_map(SeabedSpec(), GRID, _rng())
    rippled = seabed_map(SeabedSpec(ripples=(Ripples(z_m=(1.5, 2.5), fade_m=0.2),)), GRID, _rng())
    z = GRID.z_coords()
    outside, inside = (z < 1.35) | (z > 2.65), (z > 1.65) & (z < 2.35)
    np.testing.assert_array_equal(plain[outside], rippled[outside])
    assert np.abs(rippled[inside] / plain[inside] - 1.0).mean() > 0.04  # amplitude 0.2 times the profile


def test_ripple_crests_run_at_their_angle() -> None:
    spec = SeabedSpec(patchiness=0.0, detail=0.0, grain=0.0, ripples=(Ripples(angle_deg=20.0, waviness_m=0.0),))
    albedo = seabed_map(spec, GRID, _rng())
    # Along a crest the albedo is constant: shifting by the crest direction changes nothing.
    step_z = 50
    step_x = round(step_z * math.tan(math.radians(20.0)))
    shifted = np.abs(albedo[step_z:, step_x:] - albedo[:-step_z, :-step_x]).mean()
    across = np.abs(albedo[:, 3:] - albedo[:, :-3]).mean()
    assert shifted < 0.3 * across


def test_rocks_change_only_their_stretch() -> None:
    plain = seabed_map(SeabedSpec(), GRID, _rng())
    rocky = seabed_map(
        SeabedSpec(clutter=(Clutter(z_m=(1.0, 2.0), rocks_per_m2=30.0, rock_albedo=0.1),)), GRID, _rng()
    )
    z = GRID.z_coords()
    np.testing.assert_array_equal(plain[z < 0.8], rocky[z < 0.8])
    np.testing.assert_array_equal(plain[z > 2.2], rocky[z > 2.2])
    zone = (z > 1.0) & (z < 2.0)
    assert rocky[zone].mean() < plain[zone].mean() - 0.02


def test_marine_growth_covers_the_flanks_not_the_top() -> None:
    bare = cable_map(CableLook(albedo=0.2, texture=0.0), 300, 0.01, 0.1, _rng())
    grown = cable_map(
        CableLook(albedo=0.2, texture=0.0, growth_coverage=0.6, growth_albedo=0.6), 300, 0.01, 0.1, _rng()
    )
    assert bare.shape == (300, PSI_CELLS)
    psi = np.degrees(np.linspace(-math.pi, math.pi, PSI_CELLS, endpoint=False))
    top, flanks = np.abs(psi) < 20, (np.abs(psi) > 65) & (np.abs(psi) < 95)
    change = np.abs(grown - bare)
    assert change[:, flanks].mean() > 10 * change[:, top].mean()
    assert change[:, flanks].mean() > 0.05


profiles = st.lists(
    st.tuples(st.floats(-10, 10), st.floats(0, 5)), min_size=1, max_size=6, unique_by=lambda p: p[0]
).map(lambda points: tuple(sorted(points)))


@settings(max_examples=60, deadline=None)
@given(profiles, st.floats(-20, 20), st.floats(0, 10))
@example(profile=((-2.225073858507e-311, 3.0), (1.1125369292536007e-308, 0.0)), lo=0.0, length=0.0)
def test_profile_factor_interpolates_its_points_and_the_peak_bounds_it(profile, lo, length) -> None:
    factors = [f for _, f in profile]
    z = np.linspace(lo, lo + length, 97)
    values = profile_factor(z, profile)
    assert np.all(values >= min(factors) - 1e-12) and np.all(values <= max(factors) + 1e-12)
    for point, factor in profile:
        assert profile_factor(point, profile) == pytest.approx(factor)
    assert profile_peak(profile, lo, lo + length) >= values.max() - 1e-12
    np.testing.assert_array_equal(profile_factor(z, ()), np.ones_like(z))


def test_clutter_with_a_zero_density_profile_is_no_clutter() -> None:
    plain = seabed_map(SeabedSpec(), GRID, _rng())
    none = Clutter(rocks_per_m2=30.0, algae_per_m2=10.0, density=((0.0, 0.0),))
    np.testing.assert_array_equal(seabed_map(SeabedSpec(clutter=(none,)), GRID, _rng()), plain)


def test_clutter_density_profile_confines_rocks_and_algae() -> None:
    plain = seabed_map(SeabedSpec(), GRID, _rng())
    profile = ((1.0, 1.0), (1.5, 0.0))
    rocky = seabed_map(
        SeabedSpec(clutter=(Clutter(rocks_per_m2=30.0, algae_per_m2=5.0, algae_size_m=0.1, density=profile),)),
        GRID,
        _rng(),
    )
    z = GRID.z_coords()
    np.testing.assert_array_equal(plain[z > 2.0], rocky[z > 2.0])
    assert np.abs(rocky[z < 1.0] - plain[z < 1.0]).mean() > 0.02
