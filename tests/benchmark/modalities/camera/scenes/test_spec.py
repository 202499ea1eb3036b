"""Scene definitions from plain data, and the errors bad data gets."""

from __future__ import annotations

import math

import pytest

from benchmark.errors import DataError
from benchmark.modalities.camera.scenes.spec import CameraSceneSpec, Overgrowth, Ripples


def test_nested_tables_become_nested_specs(flat_scene) -> None:
    data = flat_scene(seabed={"ripples": [{"amplitude": 0.3, "z_m": [1, 2]}]}, burial=[{"z_m": [3, 4]}])
    spec = CameraSceneSpec.from_dict(data)
    assert spec.seabed.ripples == (Ripples(amplitude=0.3, z_m=(1.0, 2.0)),)
    assert spec.burial[0].z_m == (3.0, 4.0)
    assert spec.motion.phi_deg.mean == 60.0
    assert spec.nominal_tilt == pytest.approx(math.radians(60.0))
    assert spec.radius == pytest.approx(0.1)


def test_round_trip_through_plain_data(flat_scene) -> None:
    spec = CameraSceneSpec.from_dict(flat_scene(burial=[{"z_m": [3, 4], "level": 0.5}]))
    assert CameraSceneSpec.from_dict(spec.to_dict()) == spec


def test_overgrowth_and_density_profiles_from_plain_data(flat_scene) -> None:
    data = flat_scene(
        overgrowth=[{"density": [[1, 1.0], [2, 0.25]], "fronds_per_m": 4, "parallel_share": 0.5}],
        seabed={"clutter": [{"rocks_per_m2": 2.0, "density": [[0.0, 2.0]]}]},
    )
    spec = CameraSceneSpec.from_dict(data)
    assert spec.overgrowth == (
        Overgrowth(density=((1.0, 1.0), (2.0, 0.25)), fronds_per_m=4.0, parallel_share=0.5),
    )
    assert spec.seabed.clutter[0].density == ((0.0, 2.0),)
    assert CameraSceneSpec.from_dict(spec.to_dict()) == spec
    assert CameraSceneSpec.from_dict(flat_scene()).overgrowth == ()


@pytest.mark.parametrize(
    ("change", "message"),
    [
        ({"seabed": {"ripples": [{"amplitud": 0.3}]}}, r"here: seabed\.ripples\[0\]: unknown key 'amplitud' \(known: amplitude, wavelength_m, "),
        ({"n_frames": "ten"}, r"here: n_frames: expected an integer, got 'ten'"),
        ({"focal_px": True}, r"here: focal_px: expected a number, got True"),
        ({"frame_size": [320]}, r"here: frame_size: expected 2 values, got 1"),
        ({"n_frames": 0}, r"here: n_frames: must be >= 1, got 0"),
        ({"motion": {"phi_deg": {"waves": [{"amplitude": 1.0, "period_frames": 0.0}]}}}, r"here: motion\.phi_deg\.waves\[0\]\.period_frames: must be > 0, got 0\.0"),
        ({"burial": [{"z_m": [1.0, "inf"]}]}, r"here: burial\[0\]\.z_m\[1\]: expected a number, got 'inf'"),
        ({"motion": {"cx_m": 0.1}}, r"here: motion\.cx_m: expected a table for Signal, got 0\.1"),
        ({"overgrowth": [{"density": [[2.0, 1.0], [1.0, 0.5]]}]}, r"here: overgrowth\[0\]\.density: .*increase strictly, got \[2\.0, 1\.0\]"),
        ({"overgrowth": [{"density": [[1.0, -0.5]]}]}, r"here: overgrowth\[0\]\.density\[0\]\[1\]: must be >= 0, got -0\.5"),
        ({"overgrowth": [{"density": [[1.0]]}]}, r"here: overgrowth\[0\]\.density\[0\]: expected 2 values, got 1"),
        ({"overgrowth": [{"mat_cover": 1.0}]}, r"here: overgrowth\[0\]\.mat_cover: must be < 1, got 1\.0"),
        ({"seabed": {"clutter": [{"density": [[0.0, "a"]]}]}}, r"here: seabed\.clutter\[0\]\.density\[0\]\[1\]: expected a number, got 'a'"),
    ],
)
def test_bad_data_names_where_it_is(flat_scene, change, message) -> None:
    with pytest.raises(DataError, match=message):
        CameraSceneSpec.from_dict(flat_scene(**change), source="here")


def test_missing_required_key_is_a_data_error() -> None:
    with pytest.raises(DataError, match=r"^there: missing required key 'n_frames'$"):
        CameraSceneSpec.from_dict({"name": "camera/x"}, source="there")
