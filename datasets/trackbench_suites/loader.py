"""Suites written as TOML files: parsing, defaults and scene kinds.

Each ``*.toml`` file next to this module defines one suite::

    [suite]
    name = "camera"          # suite name; sequences are "camera/S1", ...
    kind = "camera"          # which scene class renders its sequences
    description = "..."
    training = "camera-train"  # optional: the suite that trains learning trackers
    scored = true            # false: a training split, left out of runs

    [defaults]               # merged under every sequence (tables merge
    focal_px = 380.0         # key by key, other values are replaced)

    [[sequence]]
    name = "S1"
    n_frames = 248
    seed = 1
    ...

The ``kind`` selects one of the scene kinds the registered modalities
declare (:attr:`benchmark.modality.Modality.scene_kinds`): a factory that
turns one merged sequence table into a :class:`benchmark.model.Sequence`.
A new modality declares its kinds, and its suites are more TOML files.
Errors name the file and the sequence.

A sequence may start from a sequence of another shipped suite, so that two
suites can show the same scene to different sensors without repeating its
definition::

    [[sequence]]
    name = "case1-medium"
    based_on = "stereo/case1-medium"

Its table is then the named sequence's merged table (its name dropped),
under this file's ``[defaults]``, under the entry itself.

A sequence may also start from a *world*: a table shipped in
``worlds/<name>.toml`` next to this module that declares the ranges a
family of suites draws its sequences from (a ``draw`` table,
:mod:`benchmark.scenes.draws`), so that the train, dev and test splits of
one world share a single definition::

    [defaults]
    world = "camera"        # worlds/camera.toml, under everything else

    [[sequence]]
    name = "w01"
    seed = 61001

The world's table lies under the sequence's (``based_on`` base, defaults
and entry merged); the key may stand in ``[defaults]`` or in an entry.

The file's layout is declared by :class:`SuiteFile` and checked by pydantic
like the specs of the sequences (:mod:`benchmark.scenes.spec`): an error
names the file, the key path (``suite.scored``, ``sequence[2].name``) and
the rule.
"""

from __future__ import annotations

import functools
import tomllib
from collections.abc import Callable, Iterator, Mapping
from dataclasses import field
from importlib import resources
from importlib.resources.abc import Traversable
from typing import Annotated, Any, NamedTuple

import pydantic
from annotated_types import MinLen

from benchmark.errors import DataError
from benchmark.modality import SceneFactory
from benchmark.model import Sequence
from benchmark.scenes.spec import SPEC_CONFIG, Flag, Name, Text, validate_table

BASE_KEY = "based_on"
"""Key of a sequence table that names the sequence, ``"<suite>/<sequence>"``, it starts from."""

WORLD_KEY = "world"
"""Key of a sequence table that names the world, ``worlds/<name>.toml``, it is drawn from."""

WORLDS_FOLDER = "worlds"

BaseResolver = Callable[[str, str], Mapping[str, Any]]
"""Returns the merged table of the sequence a reference names; the second argument says where it was asked for."""


def merge_tables(base: Mapping[str, Any], override: Mapping[str, Any]) -> dict[str, Any]:
    """``base`` updated by ``override``; nested tables merge key by key, anything else is replaced."""
    merged = dict(base)
    for key, value in override.items():
        if isinstance(value, Mapping) and isinstance(merged.get(key), Mapping):
            merged[key] = merge_tables(merged[key], value)
        else:
            merged[key] = value
    return merged


@pydantic.dataclasses.dataclass(frozen=True, config=SPEC_CONFIG)
class SuiteHeader:
    """The ``[suite]`` table.

    Attributes
    ----------
    name : str
        The suite name; its sequences are ``"<name>/<sequence>"``.
    kind : str
        The scene kind that builds its sequences, one the registered
        modalities declare (checked against them by :func:`parse_suite`).
    description : str
    training : str or None
        The suite that trains learning trackers for this one; not itself.
    scored : bool
        False for a training split, left out of runs.
    """

    name: Name
    kind: Text
    description: Text = ""
    training: Name | None = None
    scored: Flag = True

    def __post_init__(self) -> None:
        if self.training == self.name:
            raise ValueError(f"training must name another suite, got {self.training!r}")


@pydantic.dataclasses.dataclass(frozen=True, config=pydantic.ConfigDict(extra="ignore"))
class SequenceEntry:
    """What a ``[[sequence]]`` entry needs before its table is merged: a name (the scene's spec checks the rest)."""

    name: Name


@pydantic.dataclasses.dataclass(frozen=True, config=SPEC_CONFIG)
class SuiteFile:
    """The layout of a suite file: a ``[suite]`` header, ``[defaults]`` and named ``[[sequence]]`` entries."""

    suite: SuiteHeader
    sequence: Annotated[tuple[SequenceEntry, ...], MinLen(1)]
    defaults: dict[str, Any] = field(default_factory=dict)

    def __post_init__(self) -> None:
        names = [entry.name for entry in self.sequence]
        twice = sorted({name for name in names if names.count(name) > 1})
        if twice:
            raise ValueError(f"sequence name(s) {', '.join(map(repr, twice))} appear twice")


def _read(text: str, source: str) -> tuple[SuiteHeader, Mapping[str, Any], list[Mapping[str, Any]]]:
    """The ``[suite]`` header, ``[defaults]`` and ``[[sequence]]`` entries of a TOML document, checked."""
    try:
        document = _copied(_parsed(text))
    except tomllib.TOMLDecodeError as exc:
        raise DataError(f"{source}: not valid TOML: {exc}") from exc
    layout = validate_table(SuiteFile, document, source)
    return layout.suite, document.get("defaults", {}), document["sequence"]


def _tables(
    defaults: Mapping[str, Any], entries: list[Mapping[str, Any]], source: str, resolve: BaseResolver
) -> Iterator[tuple[str, dict[str, Any]]]:
    """``(name, merged table)`` of every entry, in file order, with ``based_on`` resolved and removed."""
    for entry in entries:
        short = entry["name"]
        table = merge_tables(defaults, entry)
        reference = table.pop(BASE_KEY, None)
        if reference is not None:
            where = f"{source} [sequence {short}]"
            if not isinstance(reference, str):
                raise DataError(f"{where}: {BASE_KEY} must be a string '<suite>/<sequence>', got {reference!r}")
            base = dict(resolve(reference, where))
            base.pop("name", None)
            table = merge_tables(merge_tables(base, defaults), entry)
            table.pop(BASE_KEY, None)
        world = table.pop(WORLD_KEY, None)
        if world is not None:
            table = merge_tables(shipped_world(world, f"{source} [sequence {short}]"), table)
        yield short, table


def shipped_world(name: Any, where: str) -> dict[str, Any]:
    """The table of the world ``worlds/<name>.toml`` shipped in this package.

    Raises
    ------
    DataError
        Naming ``where``, when ``name`` is not a plain name, no such world
        is shipped, or its file is not valid TOML.
    """
    if not isinstance(name, str) or not name.replace("-", "").replace("_", "").isalnum():
        raise DataError(f"{where}: {WORLD_KEY} must be the name of a shipped world, got {name!r}")
    item = resources.files(__package__).joinpath(WORLDS_FOLDER, f"{name}.toml")
    if not item.is_file():
        raise DataError(f"{where}: {WORLD_KEY} {name!r} names no world in {WORLDS_FOLDER}/")
    try:
        return _copied(_parsed(item.read_text(encoding="utf-8")))
    except tomllib.TOMLDecodeError as exc:
        raise DataError(f"{WORLDS_FOLDER}/{name}.toml: not valid TOML: {exc}") from exc


@functools.lru_cache(maxsize=64)
def _parsed(text: str) -> dict[str, Any]:
    """``text`` parsed as TOML once in a process (:func:`_copied` before use).

    A registry load reads each shipped suite again for every ``based_on``
    that names it, and each world for every sequence drawn in it; every
    load (each command of a process, or a test's) reads them all again.
    """
    return tomllib.loads(text)


def _copied(value: Any) -> Any:
    """A copy of parsed TOML whose tables and arrays are new (its other values are immutable)."""
    if isinstance(value, dict):
        return {key: _copied(item) for key, item in value.items()}
    if isinstance(value, list):
        return [_copied(item) for item in value]
    return value


def shipped_table(reference: str, where: str, _chain: tuple[str, ...] = ()) -> dict[str, Any]:
    """The merged table of a sequence of a suite shipped in this package.

    Parameters
    ----------
    reference : str
        ``"<suite>/<sequence>"``, the suite by its ``[suite]`` name.
    where : str
        Where the reference was found, for error messages.

    Returns
    -------
    dict
        The sequence's ``[defaults]`` merged with its entry (and its own
        ``based_on`` resolved), its short name under ``"name"``.

    Raises
    ------
    DataError
        When no shipped suite has that sequence, or references go round in a circle.
    """
    if reference in _chain:
        raise DataError(f"{where}: {BASE_KEY} references go round in a circle: {' -> '.join((*_chain, reference))}")
    suite, _, short = reference.partition("/")
    for item in suite_files():
        header, defaults, entries = _read(item.read_text(encoding="utf-8"), item.name)
        if header.name != suite:
            continue

        def resolve(inner: str, inner_where: str) -> dict[str, Any]:
            return shipped_table(inner, inner_where, (*_chain, reference))

        for name, table in _tables(defaults, entries, item.name, resolve):
            if name == short:
                return table
    raise DataError(f"{where}: {BASE_KEY} {reference!r} names no sequence of a shipped suite")


class SuiteDefinition(NamedTuple):
    """A suite as its file defines it.

    Attributes
    ----------
    name : str
        The suite name.
    sequences : list of Sequence
        Named ``"<suite>/<sequence>"``, in file order.
    training : str or None
        ``[suite] training``: the suite that trains learning trackers for this one.
    scored : bool
        ``[suite] scored`` (default true); false for a training split.
    """

    name: str
    sequences: list[Sequence]
    training: str | None = None
    scored: bool = True


def parse_suite(
    text: str, source: str, kinds: Mapping[str, SceneFactory], resolve: BaseResolver = shipped_table
) -> SuiteDefinition:
    """The suite a TOML document defines.

    Parameters
    ----------
    text : str
        The TOML document.
    source : str
        Its file name, for error messages.
    kinds : Mapping
        The scene kinds a suite may name, and the factory of each
        (:attr:`benchmark.registry.Registry.scene_kinds`).
    resolve : callable, optional
        Finds the table a ``based_on`` reference names; by default among
        the suites shipped in this package (:func:`shipped_table`).

    Returns
    -------
    SuiteDefinition
        Name, sequences and the ``[suite]`` keys ``training`` and ``scored``.

    Raises
    ------
    DataError
        For invalid TOML, a file that breaks the layout of :class:`SuiteFile`
        (an unknown or missing key, a ``training`` that is not another
        suite's name, a ``scored`` that is not a boolean, a sequence without
        a name, a repeated name), a ``kind`` no modality registered, a
        ``based_on`` that names nothing, or an invalid sequence definition.
    """
    header, defaults, entries = _read(text, source)
    if header.kind not in kinds:
        raise DataError(
            f"{source}: suite.kind: must be one of the registered scene kinds {sorted(kinds)}, got {header.kind!r}"
        )
    factory = kinds[header.kind]
    sequences: list[Sequence] = []
    for short, table in _tables(defaults, entries, source, resolve):
        table["name"] = f"{header.name}/{short}"
        sequences.append(factory(table, f"{source} [sequence {short}]"))
    return SuiteDefinition(header.name, sequences, header.training, header.scored)


def suite_files() -> Iterator[Traversable]:
    """The ``*.toml`` suite files shipped in this package, sorted by name."""
    folder = resources.files(__package__)
    yield from sorted((item for item in folder.iterdir() if item.name.endswith(".toml")), key=lambda i: i.name)


def load_suites(kinds: Mapping[str, SceneFactory]) -> list[SuiteDefinition]:
    """Every suite shipped in this package, built with the scene kinds ``kinds``."""
    return [parse_suite(item.read_text(encoding="utf-8"), item.name, kinds) for item in suite_files()]
