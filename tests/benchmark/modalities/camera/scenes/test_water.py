"""The revised image formation model and Jerlov's water types (Akkaynak and Treibitz 2018)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from benchmark.modalities.camera.scenes.water import (
    GREY_WEIGHTS,
    JERLOV_KD,
    PURE_WATER_ABSORPTION,
    backscatter,
    channel_responses,
    daylight_at_depth,
    formed_image,
    spectral_iops,
    to_grey,
    transmission,
    water_optics,
)

TYPES = list(JERLOV_KD)
coefficients = st.lists(st.floats(0.0, 5.0), min_size=3, max_size=3).map(np.array)
ranges = st.floats(0.0, 50.0)


@given(beta=coefficients, z=ranges)
def test_transmission_lies_in_0_1_and_is_1_at_the_camera(beta: np.ndarray, z: float) -> None:
    share = transmission(beta, np.array([z]))
    assert np.all(share > 0.0) or np.any(beta * z > 700)
    assert np.all(share <= 1.0)
    assert np.allclose(transmission(beta, np.array([0.0])), 1.0)


@given(veil=st.lists(st.floats(0.01, 2.0), min_size=3, max_size=3).map(np.array), beta=coefficients)
def test_backscatter_rises_with_range_and_saturates_at_the_veiling_light(veil: np.ndarray, beta: np.ndarray) -> None:
    z = np.array([0.0, 0.5, 1.0, 2.0, 5.0, 1e4])
    values = backscatter(veil, beta, z)
    assert np.allclose(values[:, 0], 0.0)
    assert np.all(np.diff(values, axis=1) >= -1e-12)
    assert np.all(values <= veil[:, None] + 1e-12)
    saturated = beta > 1e-2
    assert np.allclose(values[saturated, -1], veil[saturated])


@pytest.mark.parametrize("jerlov", TYPES)
def test_far_away_an_object_takes_the_colour_of_the_water(jerlov: str) -> None:
    optics = water_optics(jerlov, depth_m=10.0)
    veil = optics.reflectance * daylight_at_depth(jerlov, 10.0)
    signal = np.array([0.9, 0.5, 0.1])
    far = formed_image(signal, veil, optics, np.array([1e4]))[:, 0]
    near = formed_image(signal, veil, optics, np.array([0.0]))[:, 0]
    assert np.allclose(far, veil)
    assert np.allclose(near, signal)


def test_red_is_lost_first_in_oceanic_water_and_blue_in_turbid_coastal_water() -> None:
    oceanic = water_optics("I").beta_d
    coastal = water_optics("9C").beta_d
    assert oceanic[0] > oceanic[1] > oceanic[2]
    assert coastal[2] > coastal[1] > coastal[0]


def test_attenuation_grows_from_clear_oceanic_to_turbid_coastal_water_in_every_channel() -> None:
    betas = np.array([water_optics(jerlov).beta_d for jerlov in TYPES])
    assert np.all(np.diff(betas[:, 1]) > 0)
    assert np.all(betas[-1] > betas[0])
    backscatters = np.array([water_optics(jerlov).backscatter for jerlov in TYPES])
    assert np.all(backscatters[-1] > 10 * backscatters[0])


def test_direct_and_backscatter_coefficients_differ_as_the_revised_model_says() -> None:
    for jerlov in ("I", "III", "5C"):
        optics = water_optics(jerlov, depth_m=10.0)
        assert not np.allclose(optics.beta_d, optics.beta_b, rtol=0.02)


def test_the_wideband_coefficient_depends_weakly_on_range() -> None:
    near, far = water_optics("I", range_m=0.5).beta_d, water_optics("I", range_m=10.0).beta_d
    assert np.all(far <= near + 1e-12)
    assert np.all(far > 0.5 * near)


@given(jerlov=st.sampled_from(TYPES), depth=st.floats(0.0, 100.0), deeper=st.floats(0.1, 50.0))
def test_daylight_fades_with_depth(jerlov: str, depth: float, deeper: float) -> None:
    here, below = daylight_at_depth(jerlov, depth), daylight_at_depth(jerlov, depth + deeper)
    assert np.all(here <= 1.0 + 1e-12)
    assert np.all(below < here)


@pytest.mark.parametrize("jerlov", TYPES)
def test_inherent_optical_properties_are_physical(jerlov: str) -> None:
    beta, absorption, back = spectral_iops(jerlov)
    assert np.all(absorption >= PURE_WATER_ABSORPTION - 1e-12)
    assert np.all(back > 0)
    assert np.all(beta >= absorption)


def test_channel_responses_and_grey_weights_are_normalised() -> None:
    assert np.allclose(channel_responses().sum(axis=1), 1.0)
    assert math.isclose(float(GREY_WEIGHTS.sum()), 1.0)
    assert np.allclose(to_grey(np.ones((3, 4))), 1.0)


def test_an_unknown_water_type_or_range_is_refused() -> None:
    with pytest.raises(ValueError, match="Jerlov"):
        water_optics("12C")
    with pytest.raises(ValueError, match="range_m"):
        water_optics("I", range_m=0.0)
