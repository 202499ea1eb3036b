"""Tests of benchmark.parameters: validation when made, command-line text by type, the cache key."""

import dataclasses
import math
import re
from typing import Annotated

import annotated_types
import pydantic
import pytest

from benchmark.errors import ParameterError
from benchmark.parameters import NonNegative, Positive, Share, make_params, params_key


@dataclasses.dataclass(frozen=True)
class Knobs:
    sigma: float = 3.0
    count: int = 5
    enabled: bool = False
    label: str = "x"


def test_string_overrides_are_converted_to_the_type_of_the_default():
    params = make_params(Knobs, "knobbed", {"sigma": "1.5", "count": "7", "enabled": "yes", "label": "abc"})
    assert params == Knobs(1.5, 7, True, "abc")


def test_unknown_parameter_names_tracker_and_parameter():
    with pytest.raises(ParameterError, match=r"'knobbed'.*'sigmaa'.*known: sigma, count"):
        make_params(Knobs, "knobbed", {"sigmaa": 1})


@pytest.mark.parametrize("key, value", [("count", "many"), ("enabled", "perhaps"), ("sigma", "1,5")])
def test_unconvertible_value_names_the_parameter(key, value):
    with pytest.raises(ParameterError, match=repr(key)):
        make_params(Knobs, "knobbed", {key: value})


def test_cache_key_changes_with_parameters_and_version():
    base = params_key("knobbed", "1.0", Knobs())
    assert base == params_key("knobbed", "1.0", Knobs())
    assert base != params_key("knobbed", "1.0", Knobs(sigma=2.0))
    assert base != params_key("knobbed", "1.1", Knobs())
    assert base != params_key("other", "1.0", Knobs())


@dataclasses.dataclass(frozen=True)
class Typed:
    n: int = 1
    x: float | None = 0.5
    r: tuple[float, float] = (0.0, 1.0)
    flag: bool = False
    name: str = "a"
    k: Annotated[int, annotated_types.Ge(1)] = 1


@pytest.mark.parametrize(
    ("key", "text", "value"),
    [
        ("n", "5", 5),
        ("x", "None", None),
        ("x", "none", None),
        ("x", "2.5", 2.5),
        ("r", "(1, 2)", (1.0, 2.0)),
        ("r", "[1, 2]", (1.0, 2.0)),
        ("flag", "yes", True),
        ("flag", "false", False),
        ("name", "123", "123"),
        ("name", "None", "None"),
        ("k", "3", 3),
    ],
)
def test_command_line_text_is_converted_by_the_field_s_type(key, text, value):
    params = make_params(Typed, "typing", {key: text})
    assert getattr(params, key) == value and type(getattr(params, key)) is type(value)
    assert dataclasses.replace(params, **{key: getattr(Typed(), key)}) == Typed()


def test_a_tuple_stays_a_tuple_and_every_field_converts_at_once():
    text = {"n": "5", "x": "none", "r": "[1, 2]", "flag": "yes", "name": "123", "k": "2"}
    params = make_params(Typed, "typing", text)
    assert params == Typed(5, None, (1.0, 2.0), True, "123", 2)
    assert isinstance(params.r, tuple)


@pytest.mark.parametrize(("key", "text"), [("k", "0"), ("k", "-3"), ("r", "(1, 2, 3)"), ("n", "2.5")])
def test_a_value_out_of_its_declared_range_names_the_parameter(key, text):
    with pytest.raises(ParameterError, match=rf"tracker 'typing': parameter '{key}': .*, got {re.escape(text)}$"):
        make_params(Typed, "typing", {key: text})


@pydantic.dataclasses.dataclass(frozen=True)
class Shared:
    positive: Positive = 1.0
    non_negative: NonNegative = 0.0
    share: Share = 0.5


@pytest.mark.parametrize(
    ("key", "value"),
    [("positive", 0.0), ("positive", math.inf), ("non_negative", -1e-9), ("non_negative", math.nan), ("share", 1.5)],
)
def test_the_shared_vocabulary_refuses_what_it_names(key, value):
    with pytest.raises(ParameterError, match=rf"tracker 'shared': parameter '{key}'"):
        make_params(Shared, "shared", {key: value})
    with pytest.raises(pydantic.ValidationError):
        Shared(**{key: value})


def test_the_shared_vocabulary_takes_its_bounds():
    made = make_params(Shared, "shared", {"positive": "1e-9", "non_negative": "0", "share": "1"})
    assert made == Shared(1e-9, 0.0, 1.0)


def test_rules_across_fields_come_from_post_init():
    @dataclasses.dataclass(frozen=True)
    class Range:
        low: float = 0.0
        high: float = 1.0

        def __post_init__(self):
            if self.low > self.high:
                raise ValueError(f"low {self.low} must not exceed high {self.high}")

    with pytest.raises(ParameterError, match=r"^tracker 'ranged': low 2.0 must not exceed high 1.0$"):
        make_params(Range, "ranged", {"low": "2"})


def test_params_pydantic_cannot_validate_are_named():
    class Unknown:
        pass

    @dataclasses.dataclass(frozen=True)
    class Opaque:
        thing: Unknown = dataclasses.field(default_factory=Unknown)

    with pytest.raises(ParameterError, match=r"tracker 'opaque': its Params cannot be validated"):
        make_params(Opaque, "opaque")


def test_require_order_names_the_first_pair_out_of_order() -> None:
    import types

    import pytest

    from benchmark.parameters import require_order

    values = types.SimpleNamespace(low=1.0, high=2.0, a=5, b=3)
    require_order(values, ("low", "high"))
    with pytest.raises(ValueError, match=r"^a must not exceed b, got 5 > 3$"):
        require_order(values, ("low", "high"), ("a", "b"))
