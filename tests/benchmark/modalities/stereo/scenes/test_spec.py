"""Stereo scene definitions from plain data, and the errors bad data gets."""

from __future__ import annotations

import pytest

from benchmark.errors import DataError
from benchmark.modalities.stereo.scenes.spec import BoatSpec, PathSpec, StereoSceneSpec

DATA = {
    "name": "stereo/x",
    "n_frames": 50,
    "seed": 3,
    "case": 2,
    "speed": "medium",
    "camera": {"focal_px": 150.0},
    "sensors": {"gps_sigma_m": 0.5, "gps_correlation_s": 4.0},
    "target": {
        "start_m": 7.0,
        "speed_knots": [[0, 3.0], [5, 7.0]],
        "path": {"course_deg": 30.0, "amplitude_m": 4.0, "wavelength_m": 80.0, "onset_m": 10.0, "ramp_m": 40.0},
    },
    "chase": {"speed_knots": [[0, 3.0]], "path": {"course_deg": 30.0}},
}


def test_nested_tables_become_nested_specs() -> None:
    spec = StereoSceneSpec.from_dict(DATA)
    assert spec.target == BoatSpec(
        PathSpec(course_deg=30.0, amplitude_m=4.0, wavelength_m=80.0, onset_m=10.0, ramp_m=40.0),
        start_m=7.0,
        speed_knots=((0.0, 3.0), (5.0, 7.0)),
    )
    assert spec.target.top_speed_mps == 7.0
    assert spec.chase.path.straight and not spec.target.path.straight
    assert (spec.sensors.gps_sigma_m, spec.sensors.heading_sigma_deg) == (0.5, 0.5)
    assert spec.duration_s == pytest.approx(49 * 0.2)


def test_round_trip_through_plain_data() -> None:
    spec = StereoSceneSpec.from_dict(DATA)
    assert StereoSceneSpec.from_dict(spec.to_dict()) == spec


def test_camera_defaults_are_the_bumblebee_of_table_4() -> None:
    camera = StereoSceneSpec.from_dict({"name": "stereo/y", "n_frames": 1}).camera
    calibration = camera.calibration()
    assert (calibration.baseline_m, calibration.width_px, calibration.range_limit_m) == (0.12, 320, 16.0)
    assert calibration.principal_left_px == calibration.principal_right_px == 159.5
    assert calibration.focal_px * calibration.baseline_m == pytest.approx(16.896)
    assert camera.pixel_noise_px**2 == pytest.approx(0.11**2 / 2)  # Q_f, eq. (19)
    shifted = StereoSceneSpec.from_dict({"name": "s", "n_frames": 1, "camera": {"principal_right_px": 150.0}})
    assert shifted.camera.calibration().principal_right_px == 150.0


def _with(path: tuple[str, ...], value) -> dict:
    data = {**DATA, "target": {**DATA["target"], "path": dict(DATA["target"]["path"])}}
    table = data
    for key in path[:-1]:
        table = table[key]
    table[path[-1]] = value
    return data


@pytest.mark.parametrize(
    ("path", "value", "message"),
    [
        (("target", "path", "amplitude"), 1.0, r"here: target\.path: unknown key 'amplitude' \(known: origin_m, course_deg, amplitude_m, "),
        (("target", "speed_knots"), [[1, 3.0]], r"here: target\.speed_knots: must start at time 0, got \[\(1\.0, 3\.0\)\]"),
        (("target", "speed_knots"), [[0, 3.0], [5, 4.0], [5, 6.0]], r"here: target\.speed_knots: .*increase strictly, got \[0\.0, 5\.0, 5\.0\]"),
        (("target", "speed_knots"), [[0, -1.0]], r"here: target\.speed_knots\[0\]\[1\]: must be >= 0, got -1\.0"),
        (("target", "speed_knots"), [[0, 1.0, 2.0]], r"here: target\.speed_knots\[0\]: expected at most 2 values, got 3"),
        (("target", "path", "wavelength_m"), 0.0, r"here: target\.path\.wavelength_m: must be > 0, got 0\.0"),
        (("speed",), "warp", r"here: speed: must be 'slow', 'medium', 'fast' or 'custom', got 'warp'"),
        (("case",), 4, r"here: case: must be 0, 1, 2 or 3, got 4"),
        (("sensors",), {"dropout_rate": 1.0}, r"here: sensors\.dropout_rate: must be < 1, got 1\.0"),
        (("camera",), {"focal_px": "f"}, r"here: camera\.focal_px: expected a number, got 'f'"),
        (("n_frames",), 0, r"here: n_frames: must be >= 1, got 0"),
    ],
)
def test_bad_data_names_where_it_is(path, value, message) -> None:
    with pytest.raises(DataError, match=message):
        StereoSceneSpec.from_dict(_with(path, value), source="here")


def test_missing_required_key_is_a_data_error() -> None:
    with pytest.raises(DataError, match=r"^there: missing required key 'n_frames'$"):
        StereoSceneSpec.from_dict({"name": "stereo/x"}, source="there")

