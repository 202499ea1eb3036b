"""Beams cast on seabed and pipes, the beam pattern, and the sonar's errors."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from benchmark.modalities.sonar.scenes.seabed import across_grid
from benchmark.modalities.sonar.scenes.spec import SonarSpec
from benchmark.modalities.sonar.scenes.swath import (
    Ellipse,
    beam_angles,
    beam_ranges,
    degrade_ranges,
    ellipse_ranges,
    first_ranges,
    seabed_ranges,
    swath_from_ranges,
)

ACROSS = across_grid(40.0, 0.05)
ANGLES = beam_angles(241, math.radians(120.0))


def test_beams_are_equiangular_from_port_to_starboard() -> None:
    angles = beam_angles(111, math.radians(120.0))
    assert angles[0] == pytest.approx(-math.radians(60.0)) and angles[-1] == pytest.approx(math.radians(60.0))
    assert np.allclose(np.diff(angles), math.radians(120.0) / 110)


@given(st.floats(2.0, 30.0), st.floats(-0.3, 0.3))
def test_rays_meet_a_plane_where_geometry_says(depth: float, slope: float) -> None:
    ranges, cos_incidence = seabed_ranges(ACROSS, depth + slope * ACROSS, ANGLES)
    expected = depth / (1.0 - slope * np.tan(ANGLES)) / np.cos(ANGLES)
    inside = np.abs(expected * np.sin(ANGLES)) < ACROSS[-1]
    assert np.allclose(ranges[inside], expected[inside], rtol=1e-9)
    tilt = math.atan(slope)
    assert np.allclose(cos_incidence[inside], np.abs(np.cos(ANGLES[inside] + tilt)), atol=1e-9)
    assert np.all(np.isnan(ranges[~inside]))


@settings(max_examples=40, deadline=None)
@given(st.integers(0, 2**32 - 1), st.floats(0.05, 1.5))
def test_each_ray_stops_at_the_first_point_of_a_rough_profile(seed: int, relief: float) -> None:
    rng = np.random.default_rng(seed)
    across = across_grid(20.0, 0.1)
    depth = 8.0 + np.cumsum(rng.normal(0.0, relief * 0.1, len(across)))
    depth -= depth[len(across) // 2] - 8.0
    depth = np.maximum(depth, 2.0)
    ranges, _ = seabed_ranges(across, depth, ANGLES)
    hit = np.isfinite(ranges)
    assert hit[len(ANGLES) // 2]
    x, z = ranges * np.sin(ANGLES), ranges * np.cos(ANGLES)
    assert np.allclose(z[hit], np.interp(x[hit], across, depth), atol=1e-9)
    for theta, xs, zs in zip(ANGLES[hit], x[hit], z[hit]):
        before = (np.abs(across) < abs(xs) - 1e-9) & (np.sign(across) == np.sign(xs))
        ray_depth = np.abs(across[before]) / math.tan(abs(theta)) if theta != 0 else np.inf
        assert np.all(ray_depth < depth[before] + 1e-9)


def test_a_vertical_ray_meets_an_ellipse_at_its_top_head_on() -> None:
    ellipse = Ellipse(0.0, 10.0, 0.6, 0.4)
    ranges, cos_incidence = ellipse_ranges(np.array([0.0, 0.5]), ellipse)
    assert ranges[0] == pytest.approx(9.6) and cos_incidence[0] == pytest.approx(1.0)
    assert ranges[1] == np.inf and np.isnan(cos_incidence[1])
    side = ellipse_ranges(np.array([math.atan2(0.59, 10.0)]), ellipse)[1][0]
    assert side < 0.5


def test_a_proud_pipe_hides_the_seabed_behind_it() -> None:
    pipe = Ellipse(3.0, 9.5, 0.5, 0.5)
    angles = np.linspace(0.0, 0.6, 2000)
    ranges, _ = first_ranges(ACROSS, np.full(len(ACROSS), 10.0), angles, [pipe])
    x, z = ranges * np.sin(angles), ranges * np.cos(angles)
    on_pipe = np.abs(np.hypot(x - 3.0, z - 9.5) - 0.5) < 1e-9
    on_seabed = np.abs(z - 10.0) < 1e-9
    assert on_pipe.sum() > 20 and np.all(on_pipe | on_seabed)
    facing = (x - 3.0) * x + (z - 9.5) * z  # < 0 where the surface faces the transducer
    assert np.all(facing[on_pipe] <= 1e-9)
    # A seabed return in the shadow would mean its ray passed through the pipe.
    seabed_x = x[on_seabed]
    t = np.linspace(0.0, 1.0, 400)[:, None]
    distances = np.hypot(t * seabed_x - 3.0, t * 10.0 - 9.5)
    assert np.all(distances.min(axis=0) >= 0.5 - 1e-6)
    assert seabed_x[seabed_x > 3.0].min() > 3.0 + 0.5 * 10.0 / 9.5  # the shadow is wider than the pipe


def test_a_beam_with_a_width_mixes_its_rays_and_without_is_its_axis() -> None:
    depth = np.full(len(ACROSS), 10.0)
    pipe = Ellipse(2.0, 9.6, 0.4, 0.4)
    axes = beam_angles(241, math.radians(120.0))
    narrow, incidence = beam_ranges(ACROSS, depth, axes, [pipe], 0.0, 100.0)
    rays, cos_incidence = first_ranges(ACROSS, depth, axes, [pipe])
    assert np.allclose(narrow, rays, rtol=1e-12) and np.allclose(np.cos(incidence), cos_incidence)
    wide, _ = beam_ranges(ACROSS, depth, axes, [pipe], math.radians(2.0), 100.0)
    flat = np.abs(axes - 0.5) < 0.2
    assert np.allclose(wide[flat], narrow[flat], rtol=1e-3)
    edge = np.argmax(np.abs(wide - narrow))
    lo, hi = sorted((narrow[edge - 2 : edge + 3].min(), narrow[edge - 2 : edge + 3].max()))
    assert lo <= wide[edge] <= hi
    gated, _ = beam_ranges(ACROSS, depth, axes, [pipe], 0.0, 12.0)
    assert np.array_equal(np.isnan(gated), narrow > 12.0)


def _sonar(**changes) -> SonarSpec:
    return SonarSpec(**{"range_sigma_m": 0.0, **changes})


def _degrade(ranges, incidence, sonar, seed=0):
    rngs = [np.random.default_rng([seed, i]) for i in range(3)]
    return degrade_ranges(ranges, incidence, sonar, *rngs)


def test_without_errors_the_ranges_are_kept() -> None:
    ranges = np.linspace(10.0, 20.0, 240)
    assert np.array_equal(_degrade(ranges, np.zeros(240), _sonar()), ranges)


def test_range_noise_grows_with_the_incidence_angle() -> None:
    sonar = _sonar(range_sigma_m=0.02, outer_sigma_factor=3.0, swath_deg=120.0)
    ranges = np.full(20000, 10.0)
    nadir = _degrade(ranges, np.zeros(20000), sonar) - 10.0
    outer = _degrade(ranges, np.full(20000, math.radians(60.0)), sonar) - 10.0
    assert nadir.std() == pytest.approx(0.02, rel=0.05)
    assert outer.std() == pytest.approx(0.06, rel=0.05)


def test_missing_beams_are_more_at_the_outer_beams_and_nan_in_both_arrays() -> None:
    sonar = _sonar(missing_nadir=0.01, missing_outer=0.3)
    axes = beam_angles(240, math.radians(120.0))
    ranges = np.tile(10.0 / np.cos(axes), 100)
    incidence = np.tile(np.abs(axes), 100)
    reported = _degrade(ranges, incidence, sonar).reshape(100, 240)
    lost = np.isnan(reported).mean(axis=0)
    expected = 0.01 + 0.29 * (np.abs(axes) / math.radians(60.0)) ** 4
    assert lost[:20].mean() == pytest.approx(expected[:20].mean(), abs=0.03)
    assert lost[-20:].mean() == pytest.approx(expected[-20:].mean(), abs=0.03)
    assert lost[110:130].mean() == pytest.approx(0.01, abs=0.01)
    swath = swath_from_ranges(reported[0], axes)
    assert np.array_equal(np.isnan(swath.across_m), np.isnan(swath.depth_m))
    assert np.array_equal(~swath.valid, np.isnan(reported[0]))


def test_spikes_quantisation_and_generators() -> None:
    sonar = _sonar(outlier_rate=0.1, outlier_scale_m=2.0, range_resolution_m=0.01)
    ranges = np.full(5000, 10.0)
    reported = _degrade(ranges, np.zeros(5000), sonar)
    off = np.abs(reported - 10.0) > 0.005
    assert off.mean() == pytest.approx(0.1 * np.exp(-0.005 / 2.0), abs=0.02)
    assert np.allclose(reported / 0.01, np.round(reported / 0.01))
    assert np.array_equal(_degrade(ranges, np.zeros(5000), sonar, seed=0), reported)
    assert not np.array_equal(_degrade(ranges, np.zeros(5000), sonar, seed=1), reported)
