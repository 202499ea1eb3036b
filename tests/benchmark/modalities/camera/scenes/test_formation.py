"""Frames through the image formation model: determinism, physics, sensor options, conditions."""

from __future__ import annotations

import copy
import math
import pickle
from typing import Any

import numpy as np
import pytest

from benchmark.errors import DataError
from benchmark.identity import _canonical, digest
from benchmark.modalities.camera.contrast import cable_contrast
from benchmark.modalities.camera.scenes.render import jpeg_roundtrip, noise_sigma
from benchmark.modalities.camera.scenes.scene import CameraScene
from benchmark.modalities.camera.scenes.spec import CameraSceneSpec

WATER_SCENE: dict[str, Any] = {
    "name": "camera/water",
    "n_frames": 4,
    "seed": 11,
    "frame_size": [64, 48],
    "focal_px": 76.0,
    "pipe_diameter_m": 0.2,
    "seabed": {"albedo": 0.5, "tint": [1.0, 0.93, 0.8]},
    "cable": {"albedo": 0.08},
    "optics": {
        "blur_px": 0.5,
        "noise_grey": 2.0,
        "vignetting": 0.2,
        "water": {"jerlov": "II", "lamps": [{"offset_m": [0.3, -0.3, 0.0]}], "mean_grey": 100.0},
    },
    "motion": {"cy_m": {"mean": 1.5}, "phi_deg": {"mean": 70.0}},
}


def scene(**changes: Any) -> CameraScene:
    table = copy.deepcopy(WATER_SCENE)
    for path, value in changes.items():
        *heads, last = path.split("__")
        inner = table
        for head in heads:
            inner = inner.setdefault(head, {})
        inner[last] = value
    return CameraScene.from_dict(table)


def test_the_same_spec_gives_the_same_frame_bytes_and_another_seed_does_not() -> None:
    first = scene(optics__water__snow_per_m3=50.0, optics__shot_noise=0.3, optics__jpeg_quality=60)
    again = pickle.loads(pickle.dumps(first))
    assert all(np.array_equal(first.render(k), again.render(k)) for k in range(4))
    other = scene(seed=12, optics__water__snow_per_m3=50.0, optics__shot_noise=0.3, optics__jpeg_quality=60)
    assert not np.array_equal(first.render(0), other.render(0))


def test_the_exposure_brings_the_mean_to_its_target() -> None:
    clean = scene().render_clean(0)
    assert clean.dtype == np.float32
    assert float(clean.mean()) == pytest.approx(100.0, rel=0.05)


def test_turbid_water_takes_contrast_from_the_cable() -> None:
    contrasts = {}
    for jerlov in ("I", "9C"):
        made = scene(optics__water__jerlov=jerlov, optics__blur_px=0.0)
        contrasts[jerlov] = cable_contrast(np.clip(made.render_clean(1), 0, 255), made.truth(1).cable)
    assert contrasts["9C"] < 0.8 * contrasts["I"]


def test_the_lamps_light_fills_the_water_with_backscatter_in_turbid_water() -> None:
    looking_ahead = {"motion__phi_deg": {"mean": 5.0}, "optics__vignetting": 0.0, "optics__blur_px": 0.0}
    top_rows = {}
    for jerlov in ("I", "9C"):
        frame = scene(optics__water__jerlov=jerlov, **looking_ahead).render_clean(0)
        top_rows[jerlov] = float(frame[:8].mean()) / float(frame.mean())
    assert top_rows["9C"] > 2.0 * top_rows["I"]


def test_daylight_alone_lights_the_seabed_and_flickers() -> None:
    sunny = scene(
        optics__water={"jerlov": "1C", "lamps": [], "sun": 50.0, "depth_m": 4.0, "caustics": 1.0},
        optics__blur_px=0.0,
    )
    first, later = sunny.render_clean(0), sunny.render_clean(3)
    assert float(first.std()) > 5.0
    assert not np.allclose(first, later)


def test_shot_noise_grows_with_the_signal_and_jpeg_changes_the_frame() -> None:
    assert float(noise_sigma(200.0, 2.0, 0.5)) > float(noise_sigma(20.0, 2.0, 0.5)) > 2.0
    assert float(noise_sigma(0.0, 2.0, 0.5)) == pytest.approx(2.0)
    frame = np.random.default_rng(0).integers(0, 256, (48, 64), dtype=np.uint8)
    coarse, fine = jpeg_roundtrip(frame, 20), jpeg_roundtrip(frame, 100)
    assert coarse.shape == frame.shape and coarse.dtype == np.uint8
    assert np.abs(coarse.astype(int) - frame).mean() > np.abs(fine.astype(int) - frame).mean()
    plain = scene().render(0)
    compressed = scene(optics__jpeg_quality=30).render(0)
    assert not np.array_equal(plain, compressed)


def test_a_scene_reports_its_contrast_and_noise_as_conditions() -> None:
    made = scene(optics__shot_noise=0.4)
    conditions = made.conditions()
    assert 0.0 < conditions["contrast_grey"] < 255.0
    assert conditions["noise_grey"] > 2.0
    dark = scene(cable__albedo=0.5).conditions()["contrast_grey"]
    assert dark < conditions["contrast_grey"]


def test_fields_left_at_their_defaults_keep_a_specs_identity() -> None:
    table = {"name": "camera/x", "n_frames": 2}
    plain = CameraSceneSpec.from_dict(table)
    canonical = _canonical(plain)
    assert not {"water", "jpeg_quality", "shot_noise"} & set(canonical["optics"])
    assert "tint" not in canonical["cable"] and "tint" not in canonical["seabed"]
    written = CameraSceneSpec.from_dict({**table, "optics": {"jpeg_quality": 0, "shot_noise": 0.0}})
    assert digest(written) == digest(plain)
    assert digest(CameraSceneSpec.from_dict({**table, "optics": {"jpeg_quality": 50}})) != digest(plain)


@pytest.mark.parametrize(
    ("changes", "message"),
    [
        ({"optics__water__jerlov": "12C"}, "jerlov"),
        ({"optics__water__lamps": [], "optics__water__sun": 0.0}, "needs light"),
        ({"optics__jpeg_quality": 101}, "jpeg_quality"),
        ({"optics__water__lamps": [{"cone_deg": 5.0, "edge_deg": 8.0}]}, "cone_deg"),
        ({"cable__tint": [1.0, math.nan, 1.0]}, "tint"),
    ],
)
def test_bad_water_specs_are_refused_naming_the_value(changes: dict[str, Any], message: str) -> None:
    with pytest.raises(DataError, match=message):
        scene(**changes)
