"""Specs as plain data: the frozen dataclasses every simulated sequence is defined by.

A scene's spec is a tree of frozen dataclasses that a suite file writes as
a TOML table.  :class:`TableSpec` gives a spec class ``from_dict`` and
``to_dict``; :func:`build_dataclass` does the work, checking every key and
type on the way, so that an unknown key or a value of the wrong type is a
:class:`benchmark.errors.DataError` naming the file, the table and the key.
"""

from __future__ import annotations

import dataclasses
import types
import typing
from collections.abc import Mapping
from typing import Any, Self

from benchmark.errors import DataError


class TableSpec:
    """A spec that is built from plain data (a TOML table) and turned back into it."""

    @classmethod
    def from_dict(cls, data: Mapping[str, Any], source: str = "<dict>") -> Self:
        """Build a spec from a plain mapping (e.g. a parsed TOML table).

        Parameters
        ----------
        data : Mapping
            Keys are the field names of this class and of the nested classes;
            nested specs are nested tables, tuples are lists.
        source : str
            Where the data came from, used in error messages (e.g.
            ``"camera.toml [S1]"``).

        Raises
        ------
        DataError
            Naming ``source`` and the key at fault, for an unknown key, a
            missing required key, a value of the wrong type or a value out of
            range.
        """
        return build_dataclass(cls, data, source)

    def to_dict(self) -> dict[str, Any]:
        """The spec as plain data; :meth:`from_dict` gives back an equal spec."""
        return dataclasses.asdict(self)  # type: ignore[call-overload]


def build_dataclass(cls: type, data: Any, where: str) -> Any:
    """Build a (nested) frozen dataclass from plain data, checking keys and types.

    Raises
    ------
    DataError
        Naming ``where`` and the path of the key at fault.
    """
    if not isinstance(data, Mapping):
        raise DataError(f"{where}: expected a table for {cls.__name__}, got {type(data).__name__}")
    hints = typing.get_type_hints(cls)
    names = [f.name for f in dataclasses.fields(cls)]
    unknown = sorted(set(data) - set(names))
    if unknown:
        raise DataError(f"{where}: unknown key(s) {', '.join(map(repr, unknown))}; known keys: {', '.join(names)}")
    values = {name: _convert(hints[name], value, f"{where}.{name}") for name, value in data.items()}
    try:
        return cls(**values)
    except TypeError as exc:
        raise DataError(f"{where}: {exc}") from exc
    except ValueError as exc:
        raise DataError(f"{where}: {exc}") from exc


def _convert(kind: Any, value: Any, where: str) -> Any:
    origin, args = typing.get_origin(kind), typing.get_args(kind)
    if dataclasses.is_dataclass(kind):
        return build_dataclass(kind, value, where)
    if origin in (typing.Union, types.UnionType):
        if value is None and type(None) in args:
            return None
        (inner,) = [arg for arg in args if arg is not type(None)]
        return _convert(inner, value, where)
    if origin is tuple:
        if not isinstance(value, list | tuple):
            raise DataError(f"{where}: expected a list, got {type(value).__name__}")
        if len(args) == 2 and args[1] is Ellipsis:
            return tuple(_convert(args[0], item, f"{where}[{i}]") for i, item in enumerate(value))
        if len(value) != len(args):
            raise DataError(f"{where}: expected {len(args)} values, got {len(value)}")
        return tuple(_convert(arg, item, f"{where}[{i}]") for i, (arg, item) in enumerate(zip(args, value)))
    if kind is float:
        if isinstance(value, bool) or not isinstance(value, int | float):
            raise DataError(f"{where}: expected a number, got {value!r}")
        return float(value)
    if kind is int:
        if isinstance(value, bool) or not isinstance(value, int):
            raise DataError(f"{where}: expected an integer, got {value!r}")
        return value
    if kind is bool or kind is str:
        if not isinstance(value, kind):
            raise DataError(f"{where}: expected a {kind.__name__}, got {value!r}")
        return value
    raise DataError(f"{where}: unsupported field type {kind!r}")
