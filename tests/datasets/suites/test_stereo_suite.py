"""The stereo suite as specified: nine sequences of seeds/002, section 3, registered by the plugin."""

from __future__ import annotations

import math
import pickle

import numpy as np
import pytest
from trackbench_suites.loader import load_suites

from benchmark.modalities.stereo.geometry import project
from benchmark.modalities.stereo.model import StereoTruth
from benchmark.modalities.stereo.scenes.scene import StereoScene
from benchmark.modalities.stereo.scenes.sensors import Loss
from benchmark.plugins import load_registry

TOP_SPEED = {"slow": 3.6, "medium": 7.0, "fast": 9.0}
NAMES = [f"stereo/case{case}-{speed}" for case in (1, 2, 3) for speed in TOP_SPEED]


@pytest.fixture(scope="module")
def stereo(kinds) -> dict[str, StereoScene]:
    return {seq.info.name: seq for seq in {suite.name: suite.sequences for suite in load_suites(kinds)}["stereo"]}


def test_plugin_registers_nine_stereo_sequences_next_to_camera() -> None:
    registry = load_registry()
    assert {"camera", "stereo"} <= set(registry.suites)
    suite = registry.suites["stereo"]
    assert suite.origin.plugin == "suites"
    assert [seq.info.name for seq in suite.sequences] == NAMES
    for seq in suite.sequences:
        info = seq.info
        case, speed = info.name.removeprefix("stereo/case").split("-")
        assert isinstance(seq, StereoScene)
        assert (info.modality, info.frame_interval_s) == ("stereo", 0.2)
        assert 500 <= info.n_frames <= 750
        assert (info.extra["case"], info.extra["speed"]) == (int(case), speed)
        assert info.extra["description"]
        assert len(pickle.dumps(seq)) < 10_000


def test_the_camera_is_the_bumblebee_of_tables_3_and_4(stereo) -> None:
    for seq in stereo.values():
        calibration = seq.info.calibration
        assert (calibration.baseline_m, calibration.width_px, calibration.range_limit_m) == (0.12, 320, 16.0)
        assert calibration.correlation_accuracy_px == 0.11
        y_l, y_r = project(16.9, 0.0, calibration)
        assert float(y_l - y_r) == pytest.approx(1.0, abs=1e-3)


def test_range_crosses_the_16_m_limit_out_and_back_in_every_sequence(stereo) -> None:
    for name, seq in stereo.items():
        ranges = seq.relative_geometry().range_m
        beyond = ranges > 16.0
        assert ranges.min() < 8.0 and 20.0 < ranges.max() < 30.0, name
        assert np.count_nonzero(np.diff(beyond.astype(int))) >= 4, name
        assert 0.15 < beyond.mean() < 0.6, name


def test_target_top_speed_follows_the_speed_class(stereo) -> None:
    for name, seq in stereo.items():
        _, target = seq.tracks()
        top = TOP_SPEED[seq.info.extra["speed"]]
        assert target.speed_mps.max() == pytest.approx(top, abs=0.02), name
        assert target.speed_mps.min() < 0.8 * top, name
        acceleration = np.diff(target.speed_mps) / 0.2
        assert np.abs(acceleration).max() < 1.0, name


def _heading_spread_deg(heading: np.ndarray) -> float:
    unwrapped = np.unwrap(heading)
    return float(np.degrees(unwrapped.max() - unwrapped.min()))


def test_paths_are_straight_or_sinusoidal_as_the_case_says(stereo) -> None:
    for name, seq in stereo.items():
        chase, target = seq.tracks()
        case = seq.info.extra["case"]
        assert (_heading_spread_deg(chase.heading) > 10.0) == (case == 3), name
        assert (_heading_spread_deg(target.heading) > 10.0) == (case in (2, 3)), name


def test_headings_change_smoothly_without_artificial_jumps(stereo) -> None:
    for name, seq in stereo.items():
        for track in seq.tracks():
            turn = np.diff(np.unwrap(track.heading))
            assert np.degrees(np.abs(turn)).max() < 4.0, name
            assert np.degrees(np.abs(np.diff(turn))).max() < 1.0, name


def test_frames_measure_the_target_most_of_the_time_and_lose_it_sometimes(stereo) -> None:
    missing = []
    for name, seq in stereo.items():
        frames = list(seq)
        assert all(isinstance(f.truth, StereoTruth) for f in frames), name
        none = np.array([f.observation is None for f in frames])
        assert np.array_equal(none, seq.losses() != Loss.KEPT), name
        assert none.mean() < 0.1, name
        missing.append(none.mean())
        gps = np.array([np.subtract(f.navigation.position_m, f.truth.chase_position_m) for f in frames])
        assert 0.2 < gps.std() < 0.4, name
    assert 0.005 < np.mean(missing) < 0.05


def test_raw_measurements_degrade_beyond_the_operational_range(stereo) -> None:
    near, far = [], []
    for seq in stereo.values():
        for frame in seq:
            if frame.observation is None:
                continue
            truth = frame.truth
            dx, dy = np.subtract(truth.target.position_m, truth.chase_position_m)
            psi = truth.chase_heading
            ahead = math.cos(psi) * dx + math.sin(psi) * dy
            error = frame.observation.relative_m[0] - ahead
            (near if truth.range_m < 10.0 else far if truth.range_m > 18.0 else []).append(error)
    assert np.std(far) > 4 * np.std(near)
