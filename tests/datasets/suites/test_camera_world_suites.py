"""The camera world's splits: one declared world, disjoint seeds, draws within the declared ranges."""

from __future__ import annotations

import tomllib
from collections.abc import Iterator, Mapping
from importlib import resources
from typing import Any

import pytest
from trackbench_suites.loader import load_suites, parse_suite, shipped_world

from benchmark.errors import DataError

SPLITS = ("camera-train", "camera-dev", "camera-test")
REQUIRED = {"water", "light", "polarity", "seabed", "altitude_m", "frame_size", "jpeg_quality"}
JERLOV = {"I", "IA", "IB", "II", "III", "1C", "3C", "5C", "7C", "9C"}


@pytest.fixture(scope="module")
def suites(kinds):
    return {suite.name: suite for suite in load_suites(kinds)}


@pytest.fixture(scope="module")
def world_sequences(suites):
    return {
        name: [seq for seq in suites[name].sequences if seq.drawn_conditions] for name in SPLITS
    }


def _ranges(draws: Mapping[str, Any]) -> Iterator[tuple[str, Any]]:
    """Every ``(condition, declared entry)`` of a draw table, nested options' draws included."""
    for name, entry in draws.items():
        yield name, entry
        for option in entry.get("options", {}).values():
            yield from _ranges(option.get("draw", {}))


def test_the_splits_have_their_sizes_and_roles(suites, world_sequences) -> None:
    assert len(world_sequences["camera-train"]) == 24
    assert len(suites["camera-train"].sequences) == 31
    assert len(world_sequences["camera-dev"]) == len(suites["camera-dev"].sequences) == 48
    assert len(world_sequences["camera-test"]) == len(suites["camera-test"].sequences) == 48
    assert not suites["camera-train"].scored
    assert suites["camera-dev"].scored and suites["camera-test"].scored
    assert suites["camera-dev"].training == suites["camera-test"].training == "camera-train"


def test_test_seeds_are_disjoint_from_every_other_sequence(suites) -> None:
    test = {seq.spec.seed for seq in suites["camera-test"].sequences}
    others = {seq.spec.seed for name, suite in suites.items() if name != "camera-test" for seq in suite.sequences}
    assert len(test) == 48 and not test & others
    dev = {seq.spec.seed for seq in suites["camera-dev"].sequences}
    train = {seq.spec.seed for seq in suites["camera-train"].sequences}
    assert len(dev) == 48 and not dev & train


def test_every_draw_lies_in_its_declared_range(world_sequences) -> None:
    declared: dict[str, list[Any]] = {}
    for name, entry in _ranges(shipped_world("camera", "test")["draw"]):
        declared.setdefault(name, []).append(entry)
    for sequences in world_sequences.values():
        for seq in sequences:
            conditions = seq.drawn_conditions
            assert REQUIRED <= set(conditions), seq.info.name
            for name, value in conditions.items():
                assert any(_inside(value, entry) for entry in declared[name]), (seq.info.name, name, value)


def _inside(value: Any, entry: Mapping[str, Any]) -> bool:
    for kind in ("uniform", "log_uniform", "integers"):
        if kind in entry:
            low, high = entry[kind]
            return low <= value <= high
    if "options" in entry:
        return value in entry["options"]
    return value in entry["choice"]


def test_the_world_covers_its_conditions_across_the_splits(world_sequences) -> None:
    drawn = [seq.drawn_conditions for sequences in world_sequences.values() for seq in sequences]
    assert {c["frame_size"] for c in drawn} == {"320x240", "640x480"}
    assert {c["light"] for c in drawn} == {"lamp", "daylight", "both"}
    assert {c["polarity"] for c in drawn} == {"dark-on-sand", "bright-on-mud", "concrete", "painted"}
    assert {c["seabed"] for c in drawn} == {"sand", "mud", "gravel-shell"}
    assert {c["water"] for c in drawn} <= JERLOV and len({c["water"] for c in drawn}) >= 8
    assert {"none", "rocks-algae", "overgrowth"} == {c["clutter"] for c in drawn}


def test_a_bright_cable_lies_on_mud_and_ripples_only_on_sand(world_sequences) -> None:
    for sequences in world_sequences.values():
        for seq in sequences:
            conditions = seq.drawn_conditions
            if conditions["polarity"] == "bright-on-mud":
                assert conditions["seabed"] == "mud"
            assert ("ripples" in conditions) == (conditions["seabed"] == "sand")


def test_world_sequences_are_of_a_usual_length_and_the_field_of_view_keeps_with_the_frame_size(world_sequences) -> None:
    for sequences in world_sequences.values():
        for seq in sequences:
            spec = seq.spec
            assert 100 <= spec.n_frames <= 150
            assert spec.focal_px / spec.frame_size[0] == pytest.approx(380.0 / 320.0)
            assert spec.optics.water is not None and spec.optics.water.jerlov == seq.drawn_conditions["water"]


def test_the_thesis_sequences_of_camera_train_are_kept(suites) -> None:
    train = {seq.info.name.split("/")[1]: seq for seq in suites["camera-train"].sequences}
    camera = {seq.info.name.split("/")[1]: seq for seq in suites["camera"].sequences}
    for short in ("S1", "S2", "S3", "S4", "S5", "S6", "S7"):
        assert train[short].spec.optics.water is None
        assert train[short].spec.seed == camera[short].spec.seed + 50000
        assert train[short].spec.motion == camera[short].spec.motion


def test_the_test_file_says_it_is_never_used_to_choose() -> None:
    text = resources.files("trackbench_suites").joinpath("camera_test.toml").read_text(encoding="utf-8")
    assert "NEVER TO CHOOSE" in text
    assert tomllib.loads(text)["suite"]["name"] == "camera-test"


def test_a_sequence_may_start_from_a_world_and_a_missing_world_is_named(kinds) -> None:
    text = """
[suite]
name = "demo"
kind = "camera"
[defaults]
world = "camera"
n_frames = 2
[[sequence]]
name = "A"
seed = 3
"""
    (sequence,) = parse_suite(text, "demo.toml", kinds).sequences
    assert sequence.spec.n_frames == 2 and sequence.drawn_conditions["water"] in JERLOV
    with pytest.raises(DataError, match="demo.toml.*names no world"):
        parse_suite(text.replace('world = "camera"', 'world = "ocean"'), "demo.toml", kinds)
    with pytest.raises(DataError, match="name of a shipped world"):
        parse_suite(text.replace('world = "camera"', 'world = "../camera"'), "demo.toml", kinds)
