"""Sequences drawn from declared ranges: one stream per seed, values in place, conditions recorded, errors named."""

from __future__ import annotations

import math

import pytest
from hypothesis import given
from hypothesis import strategies as st

from benchmark.errors import DataError
from benchmark.modalities.camera.scenes.scene import CameraScene
from benchmark.scenes.draws import condition_label, resolve_draws

WORLD = {
    "name": "world/T01",
    "n_frames": 2,
    "draw": {
        "water": {"choice": ["I", "III", "9C"], "into": "optics.water"},
        "altitude_m": {"uniform": [0.8, 3.5], "into": "motion.cy_m.mean"},
        "blur_px": {"log_uniform": [0.5, 4.0], "into": "optics.blur_px"},
        "jpeg": {"integers": [20, 95], "into": "sensor.jpeg_quality"},
        "polarity": {
            "options": {
                "dark-on-sand": {"cable": {"albedo": 0.1}, "seabed": {"albedo": 0.55}},
                "bright-on-mud": {"cable": {"albedo": 0.6}, "seabed": {"albedo": 0.15}},
            }
        },
    },
}


@given(seed=st.integers(0, 2**32))
def test_every_draw_lands_inside_its_range_and_is_recorded(seed: int) -> None:
    table, conditions = resolve_draws({**WORLD, "seed": seed})
    assert "draw" not in table
    assert table["optics"]["water"] == conditions["water"] in ("I", "III", "9C")
    assert 0.8 <= table["motion"]["cy_m"]["mean"] == conditions["altitude_m"] <= 3.5
    assert 0.5 <= table["optics"]["blur_px"] <= 4.0
    assert 20 <= table["sensor"]["jpeg_quality"] <= 95 and isinstance(table["sensor"]["jpeg_quality"], int)
    albedos = {"dark-on-sand": (0.1, 0.55), "bright-on-mud": (0.6, 0.15)}[conditions["polarity"]]
    assert (table["cable"]["albedo"], table["seabed"]["albedo"]) == albedos
    assert list(conditions) == ["water", "altitude_m", "blur_px", "jpeg", "polarity"]


def test_the_same_seed_draws_the_same_sequence_and_others_differ() -> None:
    first = resolve_draws({**WORLD, "seed": 7})
    assert resolve_draws({**WORLD, "seed": 7}) == first
    others = {repr(resolve_draws({**WORLD, "seed": seed})[1]) for seed in range(8, 20)}
    assert len(others) > 6


def test_a_table_without_draws_is_returned_as_is() -> None:
    table = {"name": "camera/S1", "n_frames": 3, "optics": {"blur_px": 1.0}}
    assert resolve_draws(table) == (table, {})


def test_drawn_values_merge_into_tables_already_written() -> None:
    table = {"seed": 3, "optics": {"noise_grey": 2.0}, "draw": {"blur": {"uniform": [1.0, 1.0], "into": "optics.blur_px"}}}
    concrete, _ = resolve_draws(table)
    assert concrete["optics"] == {"noise_grey": 2.0, "blur_px": 1.0}


def test_an_option_may_draw_its_own_values_after_it_is_chosen() -> None:
    table = {
        "seed": 1,
        "draw": {
            "light": {"options": {"lamp": {"draw": {"cone_deg": {"uniform": [30.0, 60.0], "into": "lamp.cone_deg"}}}}},
            "after": {"choice": [1], "into": "x"},
        },
    }
    concrete, conditions = resolve_draws(table)
    assert list(conditions) == ["light", "cone_deg", "after"]
    assert 30.0 <= concrete["lamp"]["cone_deg"] <= 60.0 and "draw" not in concrete


def test_weights_favour_their_values() -> None:
    draw = {"kind": {"choice": ["rare", "common"], "weights": [1, 99], "into": "k"}}
    drawn = [resolve_draws({"seed": seed, "draw": draw})[1]["kind"] for seed in range(200)]
    assert 0 < drawn.count("rare") < 20


@pytest.mark.parametrize(
    ("draw", "message"),
    [
        ({"x": 3}, "expected a table"),
        ({"x": {"into": "a"}}, "needs exactly one of"),
        ({"x": {"uniform": [0, 1], "choice": [1], "into": "a"}}, "needs exactly one of"),
        ({"x": {"uniform": [2, 1], "into": "a"}}, "low <= high"),
        ({"x": {"uniform": [0, math.inf], "into": "a"}}, "uniform"),
        ({"x": {"log_uniform": [0, 1], "into": "a"}}, "log_uniform"),
        ({"x": {"uniform": [0, 1]}}, "needs into"),
        ({"x": {"choice": [], "into": "a"}}, "at least one value"),
        ({"x": {"choice": [1, 2], "weights": [1], "into": "a"}}, "one value per choice entry"),
        ({"x": {"choice": [1], "weights": [-1], "into": "a"}}, "weights"),
        ({"x": {"uniform": [0, 1], "into": "a", "spread": 2}}, "spread"),
        ({"x": {"choice": [1], "into": "name.first"}}, "not a table"),
    ],
)
def test_a_bad_draw_is_a_data_error_naming_the_entry(draw: dict, message: str) -> None:
    with pytest.raises(DataError, match=message) as caught:
        resolve_draws({"name": "n", "seed": 0, "draw": draw}, "world.toml [sequence T01]")
    assert "world.toml [sequence T01].draw.x" in str(caught.value)


def test_draws_need_a_valid_seed() -> None:
    with pytest.raises(DataError, match="seed"):
        resolve_draws({"seed": -1, "draw": {"x": {"choice": [1], "into": "a"}}}, "here")


def test_a_drawn_scene_keeps_its_conditions_through_pickling_and_shows_them() -> None:
    import pickle

    table = {
        "name": "world/T01",
        "n_frames": 1,
        "seed": 5,
        "draw": {"altitude_m": {"uniform": [1.5, 2.5], "into": "motion.cy_m.mean"}},
    }
    scene = CameraScene.from_dict(table)
    altitude = scene.drawn_conditions["altitude_m"]
    assert scene.spec.motion.cy_m.mean == altitude
    assert scene.info.extra["conditions"] == {"altitude_m": altitude}
    conditions = pickle.loads(pickle.dumps(scene)).conditions()
    assert conditions["altitude_m"] == altitude
    assert set(conditions) == {"altitude_m", "contrast_grey", "noise_grey"}
    assert CameraScene.from_dict(table).identity == scene.identity


@pytest.mark.parametrize(
    ("value", "label"), [([640, 480], "640x480"), (2.34567, "2.35"), ("9C", "9C"), (40, "40")]
)
def test_condition_labels(value: object, label: str) -> None:
    assert condition_label(value) == label


def test_a_draw_may_step_into_a_list_already_written() -> None:
    table = {
        "seed": 2,
        "motion": {"phi_deg": {"waves": [{"amplitude": 0.0, "period_frames": 40.0}, {"amplitude": 1.0}]}},
        "draw": {"pitch": {"uniform": [2.0, 3.0], "into": "motion.phi_deg.waves.0.amplitude"}},
    }
    concrete, conditions = resolve_draws(table)
    waves = concrete["motion"]["phi_deg"]["waves"]
    assert waves[0] == {"amplitude": conditions["pitch"], "period_frames": 40.0}
    assert waves[1] == {"amplitude": 1.0} and 2.0 <= conditions["pitch"] <= 3.0
    assert table["motion"]["phi_deg"]["waves"][0]["amplitude"] == 0.0
    with pytest.raises(DataError, match="not an index of a list of 2"):
        resolve_draws({**table, "draw": {"p": {"uniform": [0, 1], "into": "motion.phi_deg.waves.2.amplitude"}}})


@pytest.mark.parametrize("seed", range(12))
def test_options_given_an_earlier_condition_draw_only_among_those_allowed(seed: int) -> None:
    draw = {
        "polarity": {"options": {"dark": {}, "bright": {}}},
        "seabed": {
            "given": "polarity",
            "allowed": {"dark": ["sand", "gravel"], "bright": ["mud"]},
            "options": {"sand": {"s": 1}, "mud": {"s": 2}, "gravel": {"s": 3}},
        },
    }
    concrete, conditions = resolve_draws({"seed": seed, "draw": draw})
    allowed = {"dark": {"sand", "gravel"}, "bright": {"mud"}}
    assert conditions["seabed"] in allowed[conditions["polarity"]]
    assert concrete["s"] == {"sand": 1, "mud": 2, "gravel": 3}[conditions["seabed"]]


@pytest.mark.parametrize(
    ("entry", "message"),
    [
        ({"given": "polarity", "options": {"a": {}}}, "go together"),
        ({"given": "polarity", "allowed": {"dark": ["b"]}, "options": {"a": {}}}, "must name some of the options"),
        ({"given": "colour", "allowed": {"dark": ["a"]}, "options": {"a": {}}}, "not a condition drawn before"),
        ({"given": "polarity", "allowed": {"light": ["a"]}, "options": {"a": {}}}, "says nothing for polarity"),
    ],
)
def test_a_dependent_draw_that_cannot_be_followed_is_named(entry: dict, message: str) -> None:
    draw = {"polarity": {"choice": ["dark"], "into": "p"}, "seabed": entry}
    with pytest.raises(DataError, match=message):
        resolve_draws({"seed": 1, "draw": draw})
