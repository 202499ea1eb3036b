"""The splits of the wide sonar world: sonar-train, sonar-dev and sonar-test, drawn from one world file."""

from __future__ import annotations

import math
import tomllib
from importlib import resources

import pytest
from trackbench_suites.loader import load_suites, shipped_world

from benchmark.modalities.sonar.model import Swath
from benchmark.modalities.sonar.scenes.scene import SonarScene

SPLITS = ("sonar-train", "sonar-dev", "sonar-test")
CONDITIONS = {"beams", "swath_deg", "beam_width_deg", "altitude_m", "pipe_diameter_m", "seabed", "drift_mps"}


@pytest.fixture(scope="module")
def splits(kinds):
    return {suite.name: suite for suite in load_suites(kinds) if suite.name in SPLITS}


def test_three_splits_train_unscored_dev_and_test_scored_and_trained_on_train(splits):
    assert set(splits) == set(SPLITS)
    assert not splits["sonar-train"].scored
    assert splits["sonar-dev"].scored and splits["sonar-test"].scored
    assert splits["sonar-dev"].training == splits["sonar-test"].training == "sonar-train"
    assert len(splits["sonar-test"].sequences) >= 24
    assert all(300 <= seq.info.n_frames <= 500 for suite in splits.values() for seq in suite.sequences)


def test_the_splits_share_the_world_and_differ_only_in_their_seeds(splits):
    folder = resources.files("trackbench_suites")
    for name in SPLITS:
        document = tomllib.loads((folder / f"{name.replace('-', '_')}.toml").read_text(encoding="utf-8"))
        assert document["defaults"] == {"world": "sonar-wide"}
        assert all(set(entry) == {"name", "seed"} for entry in document["sequence"])
    seeds = [seq.spec.seed for suite in splits.values() for seq in suite.sequences]
    assert len(seeds) == len(set(seeds))


def test_every_sequence_reports_the_world_s_conditions_within_their_ranges(splits):
    draw = shipped_world("sonar-wide", "test")["draw"]
    low, high = draw["beams"]["integers"]
    for suite in splits.values():
        for seq in suite.sequences:
            assert isinstance(seq, SonarScene)
            conditions = seq.conditions()
            assert CONDITIONS | {"footprint_ratio", "pipe_speed_mps"} <= set(conditions)
            assert low <= conditions["beams"] <= high == 400 and 90.0 <= conditions["swath_deg"] <= 150.0
            assert 5.0 <= conditions["altitude_m"] <= 30.0 and 0.3 <= conditions["pipe_diameter_m"] <= 1.5
            assert conditions["seabed"] in {"bare-rough", "trench", "sand-waves"}
            assert conditions["footprint_ratio"] == pytest.approx(
                2.0 * seq.spec.vehicle.altitude_m.mean * math.tan(math.radians(conditions["beam_width_deg"]) / 2.0)
                / conditions["pipe_diameter_m"],
                rel=0.05,
            )


def test_the_test_split_covers_wide_beams_every_seabed_and_fast_drift(splits):
    conditions = [seq.conditions() for seq in splits["sonar-test"].sequences]
    assert sum(c["footprint_ratio"] >= 0.5 for c in conditions) >= 6
    assert {c["seabed"] for c in conditions} == {"bare-rough", "trench", "sand-waves"}
    assert sum(c["drift_mps"] > 0.4 for c in conditions) >= 6


def test_training_sequences_render(splits):
    for seq in splits["sonar-train"].sequences:
        frame = seq.frame(0)
        assert isinstance(frame.observation, Swath) and frame.observation.valid.mean() > 0.5
        assert math.isfinite(frame.truth.across_m)
