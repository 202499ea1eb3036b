"""Specs as plain data: pydantic checks every key, type and bound, and a DataError names file, key path and rule."""

from __future__ import annotations

import dataclasses
import pickle
import typing
from dataclasses import field
from typing import Annotated

import pydantic
import pytest
from annotated_types import Ge

from benchmark.errors import DataError
from benchmark.modalities.camera.modality import CAMERA
from benchmark.modalities.sonar.modality import SONAR
from benchmark.modalities.stereo.modality import STEREO
from benchmark.scenes.spec import (
    SPEC_CONFIG,
    Finite,
    Flag,
    Integer,
    Name,
    Number,
    Positive,
    TableSpec,
    Text,
    ordered,
    validate_table,
)


@pydantic.dataclasses.dataclass(frozen=True, config=SPEC_CONFIG)
class Inner:
    size: Positive = 1.0
    label: Text = "x"


@pydantic.dataclasses.dataclass(frozen=True, config=SPEC_CONFIG)
class Outer(TableSpec):
    name: Name
    count: Annotated[Integer, Ge(1)] = 1
    inner: Inner = field(default_factory=Inner)
    items: tuple[Inner, ...] = ()
    pair: Annotated[tuple[Finite, Finite], pydantic.AfterValidator(ordered)] = (0.0, 1.0)
    limit: Number | None = None
    flag: Flag = False

    def __post_init__(self) -> None:
        if self.flag and self.limit is None:
            raise ValueError("flag needs a limit")


def test_nested_tables_and_lists_become_nested_specs_and_tuples() -> None:
    spec = Outer.from_dict({"name": "a", "inner": {"size": 2}, "items": [{"label": "y"}, {}], "pair": [1, 2]})
    assert spec == Outer("a", inner=Inner(2.0), items=(Inner(label="y"), Inner()), pair=(1.0, 2.0))
    assert isinstance(spec.inner.size, float) and isinstance(spec.pair[0], float)
    assert Outer.from_dict({"name": "a", "limit": None}).limit is None
    assert Outer.from_dict({"name": "a", "limit": 3}).limit == 3.0
    assert Outer.from_dict({"name": "a", "limit": float("inf")}).limit == float("inf")


def test_round_trip_through_plain_data_and_pickle() -> None:
    spec = Outer("a", 3, Inner(0.5, "z"), (Inner(),), (2.0, 3.0), 1.5, True)
    data = spec.to_dict()
    assert data["inner"] == {"size": 0.5, "label": "z"}
    assert Outer.from_dict(data) == spec
    assert pickle.loads(pickle.dumps(spec)) == spec
    with pytest.raises(dataclasses.FrozenInstanceError):
        spec.count = 4  # type: ignore[misc]


@pytest.mark.parametrize(
    ("data", "message"),
    [
        ({"name": "a", "cout": 2}, r"^here: unknown key 'cout' \(known: name, count, inner, items, pair, limit, flag\)$"),
        ({"name": "a", "count": 2.5}, r"^here: count: expected an integer, got 2\.5$"),
        ({"name": "a", "count": True}, r"^here: count: expected an integer, got True$"),
        ({"name": "a", "count": 0}, r"^here: count: must be >= 1, got 0$"),
        ({"name": "a", "inner": {"size": "big"}}, r"^here: inner\.size: expected a number, got 'big'$"),
        ({"name": "a", "inner": {"size": 0}}, r"^here: inner\.size: must be > 0, got 0$"),
        ({"name": "a", "items": [{}, {"colour": 1}]}, r"^here: items\[1\]: unknown key 'colour' \(known: size, label\)$"),
        ({"name": "a", "items": {"size": 1}}, r"^here: items: expected a list, got \{'size': 1\}$"),
        ({"name": "a", "pair": [1]}, r"^here: pair: expected 2 values, got 1$"),
        ({"name": "a", "pair": [1, 2, 3]}, r"^here: pair: expected at most 2 values, got 3$"),
        ({"name": "a", "pair": [1, float("nan")]}, r"^here: pair\[1\]: must be finite, got nan$"),
        ({"name": "a", "pair": [2, 1]}, r"^here: pair: needs low <= high, got \[2\.0, 1\.0\]$"),
        ({"name": "a", "inner": 3}, r"^here: inner: expected a table for Inner, got 3$"),
        ({"name": "a", "flag": "yes"}, r"^here: flag: expected true or false, got 'yes'$"),
        ({"name": 7}, r"^here: name: expected a string, got 7$"),
        ({"name": ""}, r"^here: name: must not be empty$"),
        ({"name": "a", "flag": True}, r"^here: flag needs a limit$"),
        ({}, r"^here: missing required key 'name'$"),
        ({"count": 0, "inner": {"size": -1}}, r"^here: missing required key 'name'; here: count: .*; here: inner\.size: "),
    ],
)
def test_bad_data_is_a_data_error_naming_file_key_and_rule(data: dict, message: str) -> None:
    with pytest.raises(DataError, match=message):
        Outer.from_dict(data, source="here")


def test_a_table_of_the_wrong_kind_names_what_was_expected() -> None:
    with pytest.raises(DataError, match=r"^there: expected a table for Inner, got \[1\.0\]$"):
        validate_table(Inner, [1.0], "there")


def test_specs_made_in_python_are_checked_too() -> None:
    with pytest.raises(ValueError, match=r"size\n  Input should be greater than 0"):
        Inner(size=-1.0)
    with pytest.raises(ValueError, match="flag needs a limit"):
        Outer("a", flag=True)


def _nested_classes(root: type) -> set[type]:
    """``root`` and every dataclass its fields hold, at any depth (inside tuples and optionals too)."""
    found: set[type] = set()
    pending = [root]
    while pending:
        kind = pending.pop()
        if dataclasses.is_dataclass(kind) and kind not in found:
            found.add(kind)
            pending.extend(typing.get_type_hints(kind).values())
        else:
            pending.extend(arg for arg in typing.get_args(kind) if isinstance(arg, type) or typing.get_args(arg))
    return found


def _spec_types() -> list[type]:
    """The spec classes of every scene kind of the built-in modalities."""
    factories = [factory for modality in (CAMERA, SONAR, STEREO) for factory in modality.scene_kinds.values()]
    return sorted({factory.__self__.spec_type for factory in factories}, key=lambda kind: kind.__name__)


@pytest.mark.parametrize("root", _spec_types(), ids=lambda kind: kind.__name__)
def test_every_class_of_a_registered_spec_is_a_frozen_pydantic_dataclass_that_refuses_unknown_keys(root: type) -> None:
    classes = _nested_classes(root)
    assert len(classes) > 3
    for kind in classes:
        assert pydantic.dataclasses.is_pydantic_dataclass(kind), kind
        assert kind.__dataclass_params__.frozen, kind
        assert kind.__pydantic_config__.get("extra") == "forbid", kind
