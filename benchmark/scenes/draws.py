"""Sequences drawn from declared ranges: a suite states the world, the seed picks a scene in it.

A suite that should cover a wide world (every water type, light, seabed and
altitude a tracker may meet) does not list its scenes one by one.  Its
sequence tables carry a ``draw`` table instead: each entry names a
*condition*, declares the distribution it is drawn from, and says where in
the sequence table the drawn value goes::

    [defaults.draw.water]
    choice = ["I", "III", "1C", "5C", "9C"]
    into = "optics.water.jerlov"

    [defaults.draw.altitude_m]
    uniform = [0.8, 3.5]
    into = "motion.cy_m.mean"

    [defaults.draw.polarity.options]
    dark-on-sand = { cable = { albedo = 0.1 }, seabed = { albedo = 0.55 } }
    bright-on-mud = { cable = { albedo = 0.6 }, seabed = { albedo = 0.15 } }

:func:`resolve_draws` draws every entry, in the order the table declares
them, from one generator seeded by the sequence's ``seed`` (a stream of its
own, so the scene's other random streams do not move), writes the values
into a copy of the table and returns it with the drawn conditions.  The
concrete table is what the scene is built from, so a drawn sequence is a
pure function of its table and seed, its identity is the concrete spec's,
and the frame cache treats it like any other scene.

The distributions:

``uniform = [low, high]``, ``log_uniform = [low, high]``
    A float, uniform in the value or in its logarithm.
``integers = [low, high]``
    An integer, both ends included.
``choice = [value, ...]``
    One of the values (any TOML value: numbers, strings, lists, tables).
``options = { name = table, ... }``
    One of the named tables, merged key by key into the sequence table at
    ``into`` (the root when ``into`` is left out); the condition's value is
    the option's name.  An option may carry a ``draw`` table of its own,
    drawn after the entries declared before it.

``choice`` and ``options`` take ``weights`` (one per value, any positive
scale).  ``options`` may depend on a condition drawn before it: with
``given = "polarity"`` and ``allowed = { dark = ["sand", "gravel"], bright
= ["mud"] }`` only the options allowed for the value drawn for
``polarity`` are drawn from (with their weights), so a bright cable is
never laid on sand.  Every value lands at ``into``, a dotted path of table keys;
missing tables on the way are created, and a whole number steps into a
list already written (``motion.phi_deg.waves.0.amplitude`` draws the
amplitude of the first wave).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np
import pydantic

from benchmark.errors import DataError
from benchmark.scenes.spec import describe_problems

DRAW_KEY = "draw"
"""Key of a sequence table that holds its draws."""

DRAW_STREAM = 0x64726177
"""Second word of the draws' seed, so they never share a stream with a scene's own ``SeedSequence(seed)``."""

Conditions = dict[str, Any]
"""Drawn conditions by name: the value drawn, or the option's name."""

_Pair = tuple[pydantic.FiniteFloat, pydantic.FiniteFloat]


class _Draw(pydantic.BaseModel):
    """What every draw declares: where its value goes."""

    model_config = pydantic.ConfigDict(extra="forbid", frozen=True)

    into: str = ""

    def value(self, rng: np.random.Generator, drawn: Conditions) -> tuple[Any, Any]:
        """The value to write and the condition to record, given the conditions ``drawn`` so far."""
        raise NotImplementedError


class _Uniform(_Draw):
    uniform: _Pair

    def value(self, rng: np.random.Generator, drawn: Conditions) -> tuple[Any, Any]:
        low, high = self.uniform
        drawn = float(rng.uniform(low, high))
        return drawn, drawn


class _LogUniform(_Draw):
    log_uniform: tuple[pydantic.PositiveFloat, pydantic.PositiveFloat]

    def value(self, rng: np.random.Generator, drawn: Conditions) -> tuple[Any, Any]:
        low, high = self.log_uniform
        drawn = float(math.exp(rng.uniform(math.log(low), math.log(high))))
        return drawn, drawn


class _Integers(_Draw):
    integers: tuple[int, int]

    def value(self, rng: np.random.Generator, drawn: Conditions) -> tuple[Any, Any]:
        low, high = self.integers
        drawn = int(rng.integers(low, high, endpoint=True))
        return drawn, drawn


class _Choice(_Draw):
    choice: list[Any]
    weights: list[pydantic.PositiveFloat] | None = None

    def value(self, rng: np.random.Generator, drawn: Conditions) -> tuple[Any, Any]:
        picked = self.choice[_pick(rng, len(self.choice), self.weights)]
        return picked, picked


class _Options(_Draw):
    options: dict[str, dict[str, Any]]
    weights: list[pydantic.PositiveFloat] | None = None
    given: str = ""
    allowed: dict[str, list[str]] = {}

    def value(self, rng: np.random.Generator, drawn: Conditions) -> tuple[Any, Any]:
        names = list(self.options)
        weights = self.weights
        if self.given:
            allowed = set(self.allowed[str(drawn[self.given])])
            kept = [i for i, name in enumerate(names) if name in allowed]
            names = [names[i] for i in kept]
            weights = None if weights is None else [weights[i] for i in kept]
        name = names[_pick(rng, len(names), weights)]
        return self.options[name], name


def _pick(rng: np.random.Generator, count: int, weights: list[float] | None) -> int:
    """Index of the value drawn among ``count``, uniformly or by ``weights``."""
    if weights is None:
        return int(rng.integers(count))
    cumulative = np.cumsum(weights)
    return int(np.searchsorted(cumulative, rng.uniform(0.0, cumulative[-1]), side="right"))


_DRAW_TYPES: dict[str, type[_Draw]] = {
    "uniform": _Uniform,
    "log_uniform": _LogUniform,
    "integers": _Integers,
    "choice": _Choice,
    "options": _Options,
}


def parse_draw(name: str, entry: Any, where: str) -> _Draw:
    """One entry of a ``draw`` table, checked.

    Raises
    ------
    DataError
        Naming ``where`` and the entry, when it is not a table with exactly
        one distribution of :data:`_DRAW_TYPES`, its values do not fit it
        (a range whose ends are out of order, weights of the wrong length,
        no values), or a ``choice``/range lacks ``into``.
    """
    at = f"{where}.{DRAW_KEY}.{name}"
    if not isinstance(entry, Mapping):
        raise DataError(f"{at}: expected a table with one of {', '.join(_DRAW_TYPES)}, got {entry!r}")
    kinds = [key for key in entry if key in _DRAW_TYPES]
    if len(kinds) != 1:
        raise DataError(f"{at}: needs exactly one of {', '.join(_DRAW_TYPES)}, got {sorted(entry)}")
    (kind,) = kinds
    try:
        draw = _DRAW_TYPES[kind].model_validate(entry)
    except pydantic.ValidationError as exc:
        raise DataError(describe_problems(exc, at, _DRAW_TYPES[kind])) from None
    _check_draw(draw, kind, at)
    return draw


def _check_draw(draw: _Draw, kind: str, at: str) -> None:
    """The rules a single field's type cannot state."""
    if kind != "options" and not draw.into:
        raise DataError(f"{at}: needs into = 'dotted.path' saying where the drawn value goes")
    bounds = getattr(draw, kind)
    if kind in ("uniform", "log_uniform", "integers") and bounds[0] > bounds[1]:
        raise DataError(f"{at}: {kind} needs low <= high, got {list(bounds)}")
    if kind in ("choice", "options"):
        if not bounds:
            raise DataError(f"{at}: {kind} needs at least one value")
        weights = getattr(draw, "weights", None)
        if weights is not None and len(weights) != len(bounds):
            raise DataError(f"{at}: weights needs one value per {kind} entry ({len(bounds)}), got {len(weights)}")
    if isinstance(draw, _Options) and (bool(draw.given) != bool(draw.allowed)):
        raise DataError(f"{at}: given and allowed go together (options allowed for each value of a condition)")
    if isinstance(draw, _Options):
        for value, names in draw.allowed.items():
            unknown = sorted(set(names) - set(draw.options))
            if unknown or not names:
                raise DataError(f"{at}: allowed[{value!r}] must name some of the options, got {names}")


def _merge(base: Mapping[str, Any], override: Mapping[str, Any]) -> dict[str, Any]:
    """``base`` updated by ``override``, nested tables key by key."""
    merged = dict(base)
    for key, value in override.items():
        if isinstance(value, Mapping) and isinstance(merged.get(key), Mapping):
            merged[key] = _merge(merged[key], value)
        else:
            merged[key] = value
    return merged


def _place(table: Any, path: str, value: Any, merge: bool, at: str) -> Any:
    """A copy of ``table`` with ``value`` at the dotted ``path`` (merged into a table there if ``merge``).

    A key that is a whole number steps into a list already there (``waves.0.amplitude``).
    """
    if not path:
        return _merge(table, value) if merge else value
    head, _, rest = path.partition(".")
    if isinstance(table, list):
        if not head.isdigit() or int(head) >= len(table):
            raise DataError(f"{at}: into {path!r}: {head!r} is not an index of a list of {len(table)}")
        updated_list = list(table)
        updated_list[int(head)] = _place(table[int(head)], rest, value, merge, at)
        return updated_list
    inner = table.get(head, {})
    if not isinstance(inner, Mapping | list) and (rest or merge):
        raise DataError(f"{at}: into {path!r} passes through {head!r}, which is not a table")
    updated = dict(table)
    updated[head] = _place(dict(inner) if isinstance(inner, Mapping) else inner, rest, value, merge, at)
    return updated


def draw_stream(seed: int) -> np.random.Generator:
    """The generator a sequence's draws come from: a stream of its own under ``seed``."""
    return np.random.Generator(np.random.PCG64(np.random.SeedSequence([seed, DRAW_STREAM])))


def resolve_draws(table: Mapping[str, Any], where: str = "<dict>") -> tuple[dict[str, Any], Conditions]:
    """The concrete sequence table a ``draw`` table stands for, and the conditions drawn.

    Parameters
    ----------
    table : Mapping
        A sequence table; its ``draw`` table (if any) is resolved and
        removed.  Its ``seed`` (default 0) seeds the draws.
    where : str
        Where the table came from, for error messages.

    Returns
    -------
    table : dict
        The table without ``draw``, every drawn value in place.
    conditions : dict
        Condition name to the value drawn (the option's name for
        ``options``), in the order drawn.

    Raises
    ------
    DataError
        For a ``draw`` that is not a table, an entry that is not a valid
        draw (:func:`parse_draw`), a path through a value that is not a
        table, or a condition drawn twice.
    """
    pending = table.get(DRAW_KEY)
    concrete = {key: value for key, value in table.items() if key != DRAW_KEY}
    if pending is None:
        return concrete, {}
    seed = concrete.get("seed", 0)
    if isinstance(seed, bool) or not isinstance(seed, int) or seed < 0:
        raise DataError(f"{where}.seed: the draws need a non-negative integer seed, got {seed!r}")
    rng = draw_stream(seed)
    conditions: Conditions = {}
    queue = _entries(pending, where)
    while queue:
        name, entry = queue.pop(0)
        if name in conditions:
            raise DataError(f"{where}.{DRAW_KEY}.{name}: condition drawn twice (an option declares it again)")
        draw = parse_draw(name, entry, where)
        _check_given(draw, conditions, f"{where}.{DRAW_KEY}.{name}")
        value, conditions[name] = draw.value(rng, conditions)
        if isinstance(draw, _Options):
            nested = value.get(DRAW_KEY)
            value = {key: item for key, item in value.items() if key != DRAW_KEY}
            if nested is not None:
                queue = _entries(nested, f"{where}.{DRAW_KEY}.{name}.options.{conditions[name]}") + queue
        concrete = _place(concrete, draw.into, value, isinstance(draw, _Options), f"{where}.{DRAW_KEY}.{name}")
    return concrete, conditions


def _check_given(draw: _Draw, conditions: Conditions, at: str) -> None:
    """An ``options`` draw that depends on a condition needs it drawn before, with a value ``allowed`` names."""
    if not isinstance(draw, _Options) or not draw.given:
        return
    if draw.given not in conditions:
        raise DataError(f"{at}: given {draw.given!r} is not a condition drawn before it")
    if str(conditions[draw.given]) not in draw.allowed:
        raise DataError(f"{at}: allowed says nothing for {draw.given} = {conditions[draw.given]!r}")


def _entries(pending: Any, where: str) -> list[tuple[str, Any]]:
    """The ``(name, entry)`` pairs of a ``draw`` table, in declared order."""
    if not isinstance(pending, Mapping):
        raise DataError(f"{where}.{DRAW_KEY}: expected a table of named draws, got {pending!r}")
    return list(pending.items())


def condition_label(value: Any) -> str:
    """A drawn condition as text: ``640x480`` for a frame size, 3 significant digits for a float."""
    if isinstance(value, list | tuple) and all(isinstance(item, int) for item in value):
        return "x".join(map(str, value))
    if isinstance(value, float):
        return f"{value:.3g}"
    return str(value)


__all__ = ["DRAW_KEY", "Conditions", "condition_label", "draw_stream", "parse_draw", "resolve_draws"]
