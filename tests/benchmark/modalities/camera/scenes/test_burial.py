"""Sand over the pipe: the burial profile and the visible fraction."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from benchmark.modalities.camera.geometry import Line
from benchmark.modalities.camera.model import CameraPose
from benchmark.modalities.camera.scenes.burial import image_chord, sand_level, slice_visibility, visible_fraction
from benchmark.modalities.camera.scenes.spec import Burial

SIZE = (320, 240)
FOCAL = 380.0
RADIUS = 0.1
Z = np.arange(-5.0, 20.0, 0.01)
DOWN = CameraPose(0.0, 2.0, 0.0, 0.0, math.radians(70), 0.0)


def test_no_burial_leaves_the_sand_at_the_seabed() -> None:
    level = sand_level((), RADIUS, Z, np.random.default_rng(0))
    assert np.all(level == np.float32(-RADIUS))


def test_sand_reaches_its_level_inside_the_stretch_and_ramps_outside() -> None:
    burial = Burial(z_m=(2.0, 3.0), level=0.5, ramp_m=0.4, roughness=0.0)
    level = sand_level((burial,), RADIUS, Z, np.random.default_rng(0))
    inside = (Z >= 2.0) & (Z <= 3.0)
    np.testing.assert_allclose(level[inside], 0.0, atol=1e-6)  # half the diameter: the axis
    assert np.all(level[(Z < 1.6) | (Z > 3.4)] == np.float32(-RADIUS))
    ramp = (Z > 1.6) & (Z < 2.0)
    assert np.all(np.diff(level[ramp]) >= 0)


def test_slice_visibility() -> None:
    levels = np.array([-RADIUS, 0.0, RADIUS / 2, RADIUS, 2 * RADIUS])
    np.testing.assert_allclose(slice_visibility(levels, RADIUS), [1.0, 1.0, math.sqrt(3) / 2, 0.0, 0.0])


@settings(max_examples=40, deadline=None)
@given(rho=st.floats(-250, 250), phi=st.floats(0, math.pi))
def test_image_chord_ends_on_the_image_border(rho: float, phi: float) -> None:
    line = Line.from_normal(rho, phi)
    chord = image_chord(line, SIZE)
    half_w, half_h = (SIZE[0] - 1) / 2, (SIZE[1] - 1) / 2
    if chord is None:
        assert abs(rho) > min(half_w, half_h) - 1e-9
        return
    for x, y in chord:
        assert abs(x) <= half_w + 1e-6 and abs(y) <= half_h + 1e-6
        assert max(abs(x) - half_w, abs(y) - half_h) == pytest.approx(0.0, abs=1e-6)


def test_visible_fraction_without_and_under_sand() -> None:
    clear = sand_level((), RADIUS, Z, np.random.default_rng(0))
    buried = sand_level((Burial(z_m=(-5.0, 20.0), level=1.2, roughness=0.0),), RADIUS, Z, np.random.default_rng(0))
    assert visible_fraction(DOWN, RADIUS, FOCAL, SIZE, Z, clear) == 1.0
    assert visible_fraction(DOWN, RADIUS, FOCAL, SIZE, Z, buried) == 0.0


def test_visible_fraction_counts_the_uncovered_share() -> None:
    # Sand covers the pipe from Z = 1 on: the far part of the image.
    far = Burial(z_m=(1.0, 20.0), level=1.2, ramp_m=0.0, roughness=0.0)
    level = sand_level((far,), RADIUS, Z, np.random.default_rng(0))
    partly = visible_fraction(DOWN, RADIUS, FOCAL, SIZE, Z, level)
    assert 0.0 < partly < 1.0
    # Moving ahead brings more of the buried stretch into view.
    ahead = CameraPose(DOWN.cx, DOWN.cy, 0.4, DOWN.theta, DOWN.phi, DOWN.xi)
    assert visible_fraction(ahead, RADIUS, FOCAL, SIZE, Z, level) < partly


def test_cable_outside_the_image_is_not_visible() -> None:
    aside = CameraPose(6.0, 2.0, 0.0, 0.0, math.radians(89), 0.0)
    clear = sand_level((), RADIUS, Z, np.random.default_rng(0))
    assert visible_fraction(aside, RADIUS, FOCAL, SIZE, Z, clear) == 0.0
