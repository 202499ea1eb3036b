"""Specs as plain data: TableSpec and build_dataclass check every key and type on the way."""

from __future__ import annotations

from dataclasses import dataclass, field

import pytest

from benchmark.errors import DataError
from benchmark.scenes.spec import TableSpec, build_dataclass


@dataclass(frozen=True)
class Inner:
    size: float = 1.0
    label: str = "x"


@dataclass(frozen=True)
class Outer(TableSpec):
    name: str
    count: int = 1
    inner: Inner = field(default_factory=Inner)
    items: tuple[Inner, ...] = ()
    pair: tuple[float, float] = (0.0, 1.0)
    limit: float | None = None
    flag: bool = False

    def __post_init__(self) -> None:
        if self.count < 1:
            raise ValueError(f"count must be >= 1, got {self.count}")


def test_nested_tables_and_lists_become_nested_specs_and_tuples() -> None:
    spec = Outer.from_dict({"name": "a", "inner": {"size": 2}, "items": [{"label": "y"}, {}], "pair": [1, 2]})
    assert spec == Outer("a", inner=Inner(2.0), items=(Inner(label="y"), Inner()), pair=(1.0, 2.0))
    assert isinstance(spec.inner.size, float) and isinstance(spec.pair[0], float)
    assert Outer.from_dict({"name": "a", "limit": None}).limit is None
    assert Outer.from_dict({"name": "a", "limit": 3}).limit == 3.0


def test_round_trip_through_plain_data() -> None:
    spec = Outer("a", 3, Inner(0.5, "z"), (Inner(),), (2.0, 3.0), 1.5, True)
    data = spec.to_dict()
    assert data["inner"] == {"size": 0.5, "label": "z"}
    assert Outer.from_dict(data) == spec


@pytest.mark.parametrize(
    ("data", "message"),
    [
        ({"name": "a", "cout": 2}, r"here: unknown key\(s\) 'cout'; known keys: name, count, inner"),
        ({"name": "a", "count": 2.5}, r"here\.count: expected an integer, got 2\.5"),
        ({"name": "a", "count": True}, r"here\.count: expected an integer"),
        ({"name": "a", "inner": {"size": "big"}}, r"here\.inner\.size: expected a number, got 'big'"),
        ({"name": "a", "items": [{}, {"colour": 1}]}, r"here\.items\[1\]: unknown key\(s\) 'colour'"),
        ({"name": "a", "items": {"size": 1}}, r"here\.items: expected a list, got dict"),
        ({"name": "a", "pair": [1]}, r"here\.pair: expected 2 values, got 1"),
        ({"name": "a", "inner": 3}, r"here\.inner: expected a table for Inner, got int"),
        ({"name": "a", "flag": "yes"}, r"here\.flag: expected a bool, got 'yes'"),
        ({"name": 7}, r"here\.name: expected a str, got 7"),
        ({"name": "a", "count": 0}, r"here: count must be >= 1, got 0"),
        ({}, r"here: .*name"),
    ],
)
def test_bad_data_is_a_data_error_naming_where_it_is(data: dict, message: str) -> None:
    with pytest.raises(DataError, match=message):
        Outer.from_dict(data, source="here")


def test_build_dataclass_needs_a_table_and_a_supported_type() -> None:
    with pytest.raises(DataError, match=r"there: expected a table for Inner, got list"):
        build_dataclass(Inner, [1.0], "there")

    @dataclass(frozen=True)
    class Odd:
        mapping: dict = field(default_factory=dict)

    with pytest.raises(DataError, match=r"there\.mapping: unsupported field type"):
        build_dataclass(Odd, {"mapping": {}}, "there")
