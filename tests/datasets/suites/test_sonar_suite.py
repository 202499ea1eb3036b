"""The sonar suite as specified: four sequences modelled on seeds/003, section 4, registered by the plugin."""

from __future__ import annotations

import math
import pickle

import numpy as np
import pytest
from trackbench_suites.loader import load_suites

from benchmark.modalities.sonar.model import SonarTruth, Swath
from benchmark.modalities.sonar.scenes.scene import SonarScene
from benchmark.plugins import load_registry

NAMES = ["sonar/autotracker", "sonar/as-laid", "sonar/concrete", "sonar/second-pipe"]


@pytest.fixture(scope="module")
def sonar(kinds) -> dict[str, SonarScene]:
    return {seq.info.name: seq for seq in {suite.name: suite.sequences for suite in load_suites(kinds)}["sonar"]}


def test_plugin_registers_the_four_sonar_sequences() -> None:
    suite = load_registry().suites["sonar"]
    assert suite.origin.plugin == "suites"
    assert [seq.info.name for seq in suite.sequences] == NAMES
    for seq in suite.sequences:
        info = seq.info
        assert isinstance(seq, SonarScene) and info.modality == "sonar" and info.frame_size is None
        assert 300 <= info.n_frames <= 500 and 0.2 <= info.frame_interval_s <= 0.5
        assert info.extra["description"] and info.extra["sonar"]
        assert len(pickle.dumps(seq)) < 10_000


def test_sonars_are_the_em2000_and_the_reson_8125(sonar) -> None:
    for name, seq in sonar.items():
        calibration = seq.info.calibration
        if name == "sonar/autotracker":
            assert calibration.n_beams == 111 and math.degrees(calibration.beam_spacing) == pytest.approx(120 / 110)
            assert 0.02 <= calibration.range_sigma_m <= 0.1
        else:
            assert calibration.n_beams == 240 and math.degrees(calibration.swath_angle) == pytest.approx(120.0)
            assert calibration.range_sigma_m <= 0.02
    diameters = {name: seq.info.calibration.pipe_diameter_m for name, seq in sonar.items()}
    assert diameters["sonar/autotracker"] == 0.9
    assert 0.5 <= diameters["sonar/as-laid"] <= 0.6 and 1.0 <= diameters["sonar/concrete"] <= 1.2


def test_every_sequence_yields_valid_frames_with_the_pipe_in_the_swath(sonar) -> None:
    for name, seq in sonar.items():
        n, beams = seq.info.n_frames, seq.info.calibration.n_beams
        half = seq.info.calibration.swath_angle / 2
        for k in (0, n // 3, n - 1):
            frame = seq.frame(k)
            assert isinstance(frame.observation, Swath) and frame.observation.across_m.shape == (beams,)
            assert 0.6 < frame.observation.valid.mean() <= 1.0, (name, k)
            assert isinstance(frame.truth, SonarTruth)
        track = seq.pipes()[0]
        angle = np.arctan2(np.abs(track.across_m), track.axis_depth_m)
        assert np.all(angle < half - math.radians(10.0)), name
        assert np.ptp(track.across_m) > 1.5, name  # the pipe meanders


def test_altitudes_follow_the_paper_s_vehicles(sonar) -> None:
    for name, seq in sonar.items():
        altitude = seq.altitudes()
        low, high = (10.0, 15.0) if name == "sonar/autotracker" else (7.5, 10.5)
        assert low <= altitude.min() and altitude.max() <= high, name
        assert np.ptp(altitude) > 0.5, name


def test_burial_stretches_and_the_trench_are_where_the_descriptions_say(sonar) -> None:
    burial = {name: seq.pipes()[0].burial for name, seq in sonar.items()}
    auto = burial["sonar/autotracker"]
    assert 0.02 < np.mean(auto >= 1.0) < 0.1 and np.all(auto[313:328] >= 1.0)
    assert np.all((auto[160:210] > 0.3) & (auto[160:210] < 0.7)) and np.mean(auto == 0.0) > 0.6
    assert np.all(burial["sonar/concrete"] < 0.2) and np.all(burial["sonar/as-laid"] < 0.6)
    laid = sonar["sonar/as-laid"]
    across, depth = laid.seabed()
    pipe = laid.pipes()[0]
    rows = range(len(depth))
    floor = np.array([np.interp(pipe.across_m[k], across, depth[k]) for k in rows])
    shoulders = np.array([np.interp(pipe.across_m[k] + [-3.0, 3.0], across, depth[k]).mean() for k in rows])
    assert np.all(floor[220:280] - shoulders[220:280] > 0.8)
    assert np.median(np.abs(floor[:150] - shoulders[:150])) < 0.15


def test_only_the_second_pipe_sequence_has_a_second_pipe_converging_and_diverging(sonar) -> None:
    for name, seq in sonar.items():
        assert (len(seq.pipes()) == 2) == (name == "sonar/second-pipe")
    first, second = sonar["sonar/second-pipe"].pipes()
    separation = second.across_m - first.across_m
    assert 2.0 < separation.min() < 3.0 and separation[0] > 5.0 and separation[-1] > 5.0
    assert np.any(np.abs(second.across_m) < np.abs(first.across_m) - 1.0)  # nearer nadir at times
    assert np.all(second.burial == 0.0)
