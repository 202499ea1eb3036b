"""Sonar scene definitions from plain data, and the errors bad data gets."""

from __future__ import annotations

import copy
import math

import numpy as np
import pytest

from benchmark.errors import DataError
from benchmark.modalities.sonar.scenes.spec import (
    BoulderField,
    Drift,
    Ripples,
    Roughness,
    SecondPipeSpec,
    SonarSceneSpec,
    TrenchSpec,
)
from benchmark.scenes.signal import Event, Signal

DATA = {
    "name": "sonar/x",
    "n_frames": 40,
    "seed": 4,
    "frame_interval_s": 0.4,
    "sonar": {"model": "EM2000-like", "n_beams": 111, "swath_deg": 120.0, "beam_width_deg": 1.5},
    "vehicle": {"speed_mps": 1.8, "altitude_m": {"mean": 12.0, "noise_std": 0.3}},
    "seabed": {
        "roughness": [{"std_m": 0.2, "length_m": 8.0}, {"std_m": 0.05, "length_m": 1.0}],
        "boulders": [{"per_100m2": 2.0, "diameter_m": [0.3, 1.2], "start_frame": 10.0}],
    },
    "pipe": {
        "diameter_m": 0.9,
        "burial": {"events": [{"frame": 20.0, "amplitude": 1.0}]},
        "trench": {"depth_m": {"mean": 0.5}, "berm_ratio": 0.3},
    },
    "second_pipe": {"diameter_m": 0.5, "offset_m": {"mean": -4.0}},
}


def test_nested_tables_become_nested_specs() -> None:
    spec = SonarSceneSpec.from_dict(DATA)
    assert spec.seabed.roughness == (Roughness(0.2, 8.0), Roughness(0.05, 1.0))
    assert spec.seabed.boulders[0] == BoulderField(per_100m2=2.0, diameter_m=(0.3, 1.2), start_frame=10.0)
    assert spec.pipe.burial == Signal(events=(Event(frame=20.0, amplitude=1.0),))
    assert spec.pipe.trench == TrenchSpec(depth_m=Signal(mean=0.5), berm_ratio=0.3)
    assert spec.second_pipe == SecondPipeSpec(diameter_m=0.5, offset_m=Signal(mean=-4.0))
    assert spec.ping_spacing_m == pytest.approx(1.8 * 0.4)
    assert spec.sonar.half_swath == pytest.approx(math.radians(60.0))


def test_calibration_is_the_sonar_and_the_first_pipe() -> None:
    calibration = SonarSceneSpec.from_dict(DATA).calibration()
    assert (calibration.n_beams, calibration.pipe_diameter_m) == (111, 0.9)
    assert calibration.beam_spacing == pytest.approx(math.radians(120.0) / 110)
    assert calibration.beam_width == pytest.approx(math.radians(1.5))


def test_sand_waves_spans_and_drift_are_optional_and_off_by_default() -> None:
    plain = SonarSceneSpec.from_dict(DATA)
    assert plain.seabed.sand_waves == Ripples() and plain.pipe.bend_radius_m == 0.0 and plain.pipe.drift == Drift()
    wide = SonarSceneSpec.from_dict(
        _with(("seabed", "sand_waves"), {"height_m": 1.5, "wavelength_m": 30.0, "crest_deg": 80.0})
        | {"pipe": {"diameter_m": 0.9, "bend_radius_m": 300.0, "drift": {"amplitude_m": 2.0, "speed_mps": 1.0}}}
    )
    assert wide.seabed.sand_waves == Ripples(1.5, 30.0, 80.0)
    assert wide.pipe.bend_radius_m == 300.0 and wide.pipe.drift == Drift(2.0, 1.0)


def test_a_drift_reaches_its_speed_and_its_amplitude() -> None:
    drift = Drift(amplitude_m=2.5, speed_mps=0.8, phase_deg=30.0)
    offsets = drift.offsets(4000, 0.05)
    assert np.max(np.abs(offsets)) == pytest.approx(2.5, rel=1e-4)
    assert np.max(np.abs(np.diff(offsets))) / 0.05 == pytest.approx(0.8, rel=1e-3)
    assert offsets[0] == pytest.approx(2.5 * math.sin(math.radians(30.0)))
    assert np.all(Drift(0.0, 1.0).offsets(5, 0.3) == 0.0) and np.all(Drift(2.0, 0.0).offsets(5, 0.3) == 0.0)


def test_round_trip_through_plain_data() -> None:
    spec = SonarSceneSpec.from_dict(DATA)
    assert SonarSceneSpec.from_dict(spec.to_dict()) == spec
    alone = SonarSceneSpec.from_dict({"name": "sonar/y", "n_frames": 1})
    assert alone.second_pipe is None
    assert SonarSceneSpec.from_dict(alone.to_dict()) == alone


def _with(path: tuple[str | int, ...], value) -> dict:
    data = copy.deepcopy(DATA)
    table = data
    for key in path[:-1]:
        table = table[key]
    table[path[-1]] = value
    return data


@pytest.mark.parametrize(
    ("path", "value", "message"),
    [
        (("sonar", "beams"), 3, r"here: sonar: unknown key 'beams' \(known: model, n_beams, "),
        (("sonar", "n_beams"), 2, r"here: sonar\.n_beams: must be >= 3, got 2"),
        (("sonar", "swath_deg"), 180.0, r"here: sonar\.swath_deg: must be < 175, got 180\.0"),
        (("sonar", "missing_outer"), 1.0, r"here: sonar\.missing_outer: must be < 1, got 1\.0"),
        (("sonar", "outer_sigma_factor"), 0.5, r"here: sonar\.outer_sigma_factor: must be >= 1, got 0\.5"),
        (("sonar", "range_resolution_m"), 1e-310, r"here: sonar\.range_resolution_m: must be 0 \(no rounding\) or at least 1e-06 m, got 1e-310"),
        (("sonar", "n_beams"), 111.0, r"here: sonar\.n_beams: expected an integer, got 111\.0"),
        (("vehicle", "speed_mps"), 0.0, r"here: vehicle\.speed_mps: must be > 0, got 0\.0"),
        (("vehicle", "altitude_m", "noise_std"), -1.0, r"here: vehicle\.altitude_m\.noise_std: must be >= 0, got -1\.0"),
        (("seabed", "roughness", 1, "length_m"), 0.0, r"here: seabed\.roughness\[1\]\.length_m: must be > 0, got 0\.0"),
        (("seabed", "boulders", 0, "diameter_m"), [1.0, 0.5], r"here: seabed\.boulders\[0\]\.diameter_m: needs low <= high, got \[1\.0, 0\.5\]"),
        (("seabed", "cell_m"), 2.0, r"here: seabed\.cell_m: must be <= 0\.5, got 2\.0"),
        (("pipe", "diameter_m"), "big", r"here: pipe\.diameter_m: expected a number, got 'big'"),
        (("pipe", "trench", "top_width_m"), 0.5, r"here: pipe\.trench: bottom_width_m must be below top_width_m, got 1\.0 >= 0\.5"),
        (("second_pipe", "offset"), 3.0, r"here: second_pipe: unknown key 'offset' \(known: diameter_m, offset_m, burial, trench\)"),
        (("pipe", "bend_radius_m"), -1.0, r"here: pipe\.bend_radius_m: must be >= 0, got -1\.0"),
        (("pipe", "drift"), {"amplitude_m": -1.0}, r"here: pipe\.drift\.amplitude_m: must be >= 0, got -1\.0"),
        (("pipe", "drift"), {"speed_mps": -0.5}, r"here: pipe\.drift\.speed_mps: must be >= 0, got -0\.5"),
        (("seabed", "sand_waves"), {"wavelength_m": 0.0}, r"here: seabed\.sand_waves\.wavelength_m: must be > 0, got 0\.0"),
        (("n_frames",), 0, r"here: n_frames: must be >= 1, got 0"),
    ],
)
def test_bad_data_names_where_it_is(path, value, message) -> None:
    with pytest.raises(DataError, match=message):
        SonarSceneSpec.from_dict(_with(path, value), source="here")


def test_missing_required_key_is_a_data_error() -> None:
    with pytest.raises(DataError, match=r"^there: missing required key 'n_frames'$"):
        SonarSceneSpec.from_dict({"name": "sonar/x"}, source="there")
