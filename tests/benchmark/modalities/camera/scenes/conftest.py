"""Fixtures of the scene tests: plain-data specs of small, easily checked scenes."""

from __future__ import annotations

import copy
from collections.abc import Callable
from typing import Any

import pytest

FLAT_SCENE: dict[str, Any] = {
    "name": "camera/flat",
    "n_frames": 6,
    "seed": 5,
    "seabed": {"albedo": 0.8, "patchiness": 0.0, "detail": 0.0, "grain": 0.0},
    "cable": {"albedo": 0.1, "texture": 0.0, "specular": 0.0},
    "optics": {
        "exposure": 250.0,
        "ambient": 1.0,
        "light_falloff": False,
        "attenuation_per_m": 0.0,
        "vignetting": 0.0,
        "blur_px": 0.0,
        "noise_grey": 0.0,
        "snow_per_frame": 0.0,
        "auto_gain": 0.0,
    },
    "motion": {
        "speed_noise_mps": 0.0,
        "cx_m": {"mean": 0.05, "waves": [{"amplitude": 0.3, "period_frames": 6.0}]},
        "cy_m": {"mean": 2.0, "waves": [{"amplitude": 0.5, "period_frames": 9.0}]},
        "theta_deg": {"waves": [{"amplitude": 8.0, "period_frames": 5.0}]},
        "phi_deg": {"mean": 60.0, "waves": [{"amplitude": 15.0, "period_frames": 7.0, "phase_deg": 30.0}]},
        "xi_deg": {"waves": [{"amplitude": 3.0, "period_frames": 4.0}]},
    },
}
"""Untextured sand (grey 200) and pipe (grey 25), no light effects, no sensor: a pixel
is cable or seabed and nothing else, while the camera swings through varied poses."""


@pytest.fixture
def flat_scene() -> Callable[..., dict[str, Any]]:
    """A factory of flat scene specs; keyword arguments replace top-level keys."""

    def make(**changes: Any) -> dict[str, Any]:
        spec = copy.deepcopy(FLAT_SCENE)
        spec.update(changes)
        return spec

    return make


@pytest.fixture(scope="session")
def flat_scene_data() -> dict[str, Any]:
    """The flat scene spec itself (a copy), for fixtures wider than one test."""
    return copy.deepcopy(FLAT_SCENE)
