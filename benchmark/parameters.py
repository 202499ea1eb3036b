"""Tracker parameters: declared beside their fields, validated when they are made, hashed into keys.

A tracker's ``Params`` is a frozen dataclass whose defaults are its paper's
values.  One declarative mechanism validates every tracker's parameters:
pydantic checks them against their type hints, so a field declares its
range or its choices beside it, with ``annotated_types`` constraints and
``Literal``, and rules that tie fields together go in ``__post_init__``
(raising ``ValueError``)::

    @pydantic.dataclasses.dataclass(frozen=True)
    class Params:
        n_particles: Annotated[int, Ge(1)] = 500
        ess_fraction: Share = 0.5
        resampler: Literal["systematic", "multinomial"] = "systematic"

A pydantic dataclass is checked whenever it is made; a plain frozen
dataclass works too and is checked by :func:`make_params`, which the
registry calls for every registered tracker and every ``--param``.
pydantic was chosen over attrs validators or cattrs because its
dataclasses are standard dataclasses (``dataclasses.asdict`` and
``replace`` keep working, and third-party plain dataclasses validate
against their type hints unchanged), it converts command-line text by type
(``"0.5"`` to a float, ``"yes"`` to a bool), and its messages name the
field and the bound.

The aliases below are the vocabulary first-party trackers share.
"""

from __future__ import annotations

import ast
import dataclasses
import functools
import hashlib
import json
import typing
from collections.abc import Mapping
from typing import Annotated, Any

import pydantic
from annotated_types import Ge, Gt, Interval

from benchmark.errors import ParameterError

Finite = pydantic.FiniteFloat
"""Any finite number."""

Positive = Annotated[pydantic.FiniteFloat, Gt(0)]
"""A finite number above 0."""

NonNegative = Annotated[pydantic.FiniteFloat, Ge(0)]
"""A finite number, 0 or above."""

Share = Annotated[pydantic.FiniteFloat, Interval(ge=0, le=1)]
"""A share or fraction in ``[0, 1]``."""


def require_order(params: Any, *pairs: tuple[str, str]) -> None:
    """The cross-field rule most trackers share: each ``(low, high)`` pair of fields is ordered.

    Call it from ``__post_init__``, e.g. ``require_order(self, ("min_width_px", "max_width_px"))``.

    Raises
    ------
    ValueError
        ``"low must not exceed high, got a > b"`` for the first pair out of order.
    """
    for low, high in pairs:
        a, b = getattr(params, low), getattr(params, high)
        if a > b:
            raise ValueError(f"{low} must not exceed {high}, got {a} > {b}")


def make_params(params_class: type, tracker: str, overrides: Mapping[str, Any] | None = None) -> Any:
    """Build and validate a tracker's parameters from their defaults and ``overrides``.

    A value given as text (from the command line) is taken as text where the
    parameter's type accepts text (``"0.5"`` for a float, ``"yes"`` for a
    bool), and otherwise as the Python literal it spells (``"(-150, 150)"``
    for a tuple, ``"None"`` or ``"none"`` for an optional value).

    Parameters
    ----------
    params_class : type
        The tracker's ``Params``, a frozen dataclass with defaults.
    tracker : str
        The tracker's name, for messages.
    overrides : Mapping, optional
        Parameter names to values.

    Returns
    -------
    An instance of ``params_class``.

    Raises
    ------
    ParameterError
        For a name ``params_class`` does not declare, or a value that does
        not convert or breaks a declared rule; the message names the
        tracker, the parameter and the value.
    """
    overrides = dict(overrides or {})
    names = [field.name for field in dataclasses.fields(params_class)]
    unknown = sorted(set(overrides) - set(names))
    if unknown:
        known = ", ".join(names) or "none"
        raise ParameterError(f"tracker {tracker!r} has no parameter {', '.join(map(repr, unknown))} (known: {known})")
    try:
        validator = _validator(params_class)
    except pydantic.PydanticUserError as exc:
        raise ParameterError(f"tracker {tracker!r}: its Params cannot be validated: {exc}") from None
    hints = typing.get_type_hints(params_class, include_extras=True)
    given = {
        key: _from_text(hints[key], value) if isinstance(value, str) else value for key, value in overrides.items()
    }
    defaults = params_class()
    try:
        return validator.validate_python({**{name: getattr(defaults, name) for name in names}, **given})
    except pydantic.ValidationError as exc:
        raise ParameterError(_describe(tracker, exc)) from None


@functools.cache
def _validator(params_class: type) -> pydantic.TypeAdapter:
    return pydantic.TypeAdapter(params_class)


def _from_text(hint: Any, text: str) -> Any:
    """A command-line value: the text itself where the type accepts it, else the Python literal it spells."""
    try:
        pydantic.TypeAdapter(hint).validate_python(text)
        return text
    except pydantic.ValidationError:
        pass
    try:
        return ast.literal_eval(text.strip())
    except (ValueError, SyntaxError):
        return None if text.strip().lower() in ("none", "null") else text


def _describe(tracker: str, exc: pydantic.ValidationError) -> str:
    """One clause per failed check, each naming the parameter and the value."""
    problems = []
    for error in exc.errors(include_url=False):
        message = str(error["msg"]).removeprefix("Value error, ")
        location = ".".join(str(part) for part in error["loc"])
        problems.append(f"parameter {location!r}: {message}, got {error['input']!r}" if location else message)
    return f"tracker {tracker!r}: " + "; ".join(problems)


def params_key(name: str, version: str, params: Any, code: str = "") -> str:
    """Hash of a tracker's name, version, parameters and code digest: the results cache key."""
    payload = json.dumps(
        {"name": name, "version": version, "params": dataclasses.asdict(params), **({"code": code} if code else {})},
        sort_keys=True,
        default=repr,
    )
    return hashlib.sha256(payload.encode()).hexdigest()[:16]
