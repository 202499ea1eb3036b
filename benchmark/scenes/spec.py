"""Specs as plain data: the frozen dataclasses every simulated sequence is defined by, declared and checked by pydantic.

A scene's spec is a tree of frozen pydantic dataclasses that a suite file
writes as a TOML table.  Each field declares its type and its range beside
it, with the vocabulary below and ``annotated_types`` constraints, the way
tracker parameters do (:mod:`benchmark.parameters`); a rule that ties
fields together goes in ``__post_init__``, raising ``ValueError``::

    @pydantic.dataclasses.dataclass(frozen=True, config=SPEC_CONFIG)
    class Ripples:
        wavelength_m: Positive = 0.12
        sharpness: Share = 0.85

pydantic checks a spec whenever it is made, from Python or from plain data,
so that a spec that exists is valid.  Unlike a tracker parameter given on
the command line, a value in a suite file is taken as written: a number
must be a number (an integer is taken as a float where a float is
declared), an integer an integer, a flag ``true`` or ``false``; a list
becomes a tuple and a table a nested spec.  :class:`TableSpec` gives a
spec class ``from_dict`` and ``to_dict``; every problem with the data is one
:class:`benchmark.errors.DataError` naming the file, the path of the key
(``optics.water.lamps[0].cone_deg``) and the rule it breaks
(``must be > 0, got -1.0``).
"""

from __future__ import annotations

import dataclasses
import functools
import typing
from collections.abc import Mapping, Sequence
from typing import Annotated, Any, Self

import pydantic
from annotated_types import Ge, Gt, Interval

from benchmark.errors import DataError

SPEC_CONFIG = pydantic.ConfigDict(extra="forbid")
"""The configuration of every spec class: a key the class does not declare is an error."""

Number = Annotated[float, pydantic.Strict()]
"""Any number, infinities included (an open end of a stretch); an integer is taken as a float."""

Finite = Annotated[Number, pydantic.AllowInfNan(False)]
"""Any finite number."""

Positive = Annotated[Finite, Gt(0)]
"""A finite number above 0."""

NonNegative = Annotated[Finite, Ge(0)]
"""A finite number, 0 or above."""

Share = Annotated[Finite, Interval(ge=0, le=1)]
"""A share or fraction in ``[0, 1]``."""

Probability = Annotated[Finite, Interval(ge=0, lt=1)]
"""A probability below 1, in ``[0, 1)``."""

Integer = pydantic.StrictInt
"""An integer, written as one."""

Flag = pydantic.StrictBool
"""``true`` or ``false``."""

Text = pydantic.StrictStr
"""A string."""

Name = Annotated[pydantic.StrictStr, pydantic.StringConstraints(min_length=1)]
"""A non-empty string."""


def strictly_increasing(points: tuple[tuple[float, float], ...]) -> tuple[tuple[float, float], ...]:
    """``points`` unchanged when their first coordinates increase strictly, else ``ValueError``."""
    firsts = [first for first, _ in points]
    if any(b <= a for a, b in zip(firsts, firsts[1:])):
        raise ValueError(f"the points' first values must increase strictly, got {firsts}")
    return points


def ordered(pair: tuple[float, float]) -> tuple[float, float]:
    """``pair`` unchanged when it is ``(low, high)`` with ``low <= high``, else ``ValueError``."""
    if pair[0] > pair[1]:
        raise ValueError(f"needs low <= high, got {list(pair)}")
    return pair


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
            ``"camera.toml [sequence S1]"``).

        Raises
        ------
        DataError
            Naming ``source``, the path of each key at fault and what is
            wrong with it: an unknown key, a missing required key, a value
            of the wrong type or out of its range, or fields that break a
            rule that ties them together.
        """
        return validate_table(cls, data, source)

    def to_dict(self) -> dict[str, Any]:
        """The spec as plain data; :meth:`from_dict` gives back an equal spec."""
        return dataclasses.asdict(self)  # type: ignore[call-overload]


def validate_table(kind: Any, data: Any, source: str) -> Any:
    """``data`` validated as ``kind`` (a pydantic dataclass or model, or any type pydantic validates).

    Raises
    ------
    DataError
        Naming ``source`` and, for every problem, the key path and the rule
        (:func:`describe_problems`).
    """
    try:
        return _adapter(kind).validate_python(data)
    except pydantic.ValidationError as exc:
        raise DataError(describe_problems(exc, source, kind)) from None


@functools.cache
def _adapter(kind: Any) -> pydantic.TypeAdapter[Any]:
    return pydantic.TypeAdapter(kind)


_MESSAGES: dict[str, str] = {
    "greater_than": "must be > {gt}, got {input!r}",
    "greater_than_equal": "must be >= {ge}, got {input!r}",
    "less_than": "must be < {lt}, got {input!r}",
    "less_than_equal": "must be <= {le}, got {input!r}",
    "finite_number": "must be finite, got {input!r}",
    "float_type": "expected a number, got {input!r}",
    "int_type": "expected an integer, got {input!r}",
    "bool_type": "expected true or false, got {input!r}",
    "string_type": "expected a string, got {input!r}",
    "string_too_short": "must not be empty",
    "tuple_type": "expected a list, got {input!r}",
    "list_type": "expected a list, got {input!r}",
    "dict_type": "expected a table, got {input!r}",
    "model_type": "expected a table, got {input!r}",
    "dataclass_type": "expected a table for {class_name}, got {input!r}",
    "literal_error": "must be {expected}, got {input!r}",
    "too_long": "expected at most {max_length} values, got {actual_length}",
    "too_short": "expected at least {min_length} values, got {actual_length}",
}
"""What each kind of pydantic error says, in the words of a suite file; others keep pydantic's words."""


def describe_problems(exc: pydantic.ValidationError, source: str, kind: Any = None) -> str:
    """Every problem pydantic found, as ``source: key.path: what is wrong, got value``, joined by ``"; "``.

    Parameters
    ----------
    exc : pydantic.ValidationError
        What pydantic found.
    source : str
        Where the data came from (a file, a file and a sequence).
    kind : type, optional
        The type that was validated; with it an unknown key lists the keys
        its table knows.
    """
    return "; ".join(_describe(error, source, kind) for error in exc.errors(include_url=False))


def _describe(error: Any, source: str, kind: Any) -> str:
    location, code, value = tuple(error["loc"]), error["type"], error.get("input")
    if code in ("unexpected_keyword_argument", "extra_forbidden"):
        known = _known_keys(kind, location[:-1])
        return _at(source, location[:-1], f"unknown key {location[-1]!r}" + (f" (known: {known})" if known else ""))
    if code in ("missing", "missing_argument") and location and isinstance(location[-1], int):
        return _at(source, location[:-1], f"expected {_tuple_length(kind, location[:-1])} values, got {len(value)}")
    if code in ("missing", "missing_argument"):
        return _at(source, location[:-1], f"missing required key {location[-1]!r}")
    if code == "value_error":
        return _at(source, location, str(error["ctx"]["error"]))
    context = {key: f"{bound:g}" if isinstance(bound, float) else bound for key, bound in error.get("ctx", {}).items()}
    template = _MESSAGES.get(code, "{msg}, got {input!r}")
    return _at(source, location, template.format(**context, msg=error["msg"], input=value))


def _at(source: str, location: Sequence[Any], message: str) -> str:
    path = "".join(f"[{part}]" if isinstance(part, int) else f".{part}" for part in location).lstrip(".")
    return f"{source}: {path}: {message}" if path else f"{source}: {message}"


def _type_at(kind: Any, location: Sequence[Any]) -> Any:
    """The declared type at ``location`` inside ``kind``, Annotated and None stripped; None if it cannot be told."""
    for part in location:
        kind = _bare(kind)
        if isinstance(part, int):
            args = typing.get_args(kind)
            kind = args[0] if len(args) == 2 and args[1] is Ellipsis else args[part] if part < len(args) else None
        elif dataclasses.is_dataclass(kind) or hasattr(kind, "model_fields"):
            kind = typing.get_type_hints(kind, include_extras=True).get(part)
        else:
            return None
    return _bare(kind)


def _bare(kind: Any) -> Any:
    while typing.get_origin(kind) is Annotated:
        kind = typing.get_args(kind)[0]
    inner = [arg for arg in typing.get_args(kind) if arg is not type(None)]
    return _bare(inner[0]) if type(None) in typing.get_args(kind) and len(inner) == 1 else kind


def _known_keys(kind: Any, location: Sequence[Any]) -> str:
    """The keys the table at ``location`` declares, or "" where its type cannot be told (the message goes without)."""
    try:
        table = _type_at(kind, location)
    except (NameError, TypeError, IndexError):
        return ""
    if dataclasses.is_dataclass(table):
        return ", ".join(field.name for field in dataclasses.fields(table))
    return ", ".join(getattr(table, "model_fields", {}))


def _tuple_length(kind: Any, location: Sequence[Any]) -> int | str:
    args = typing.get_args(_type_at(kind, location))
    return len(args) if args and args[-1] is not Ellipsis else "more"
