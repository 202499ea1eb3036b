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

Splits of one world (train, dev and test drawn from the same declared
ranges) share those ranges through a *world*: a file
``worlds/<name>.toml`` next to this module that holds one ``[defaults]``
table (typically with a ``draw`` table, :mod:`benchmark.scenes.draws`) and
nothing else a suite has.  A suite names it in its header::

    [suite]
    name = "sonar-dev"
    kind = "sonar"
    world = "sonar-wide"     # worlds/sonar-wide.toml [defaults] under this file's

and the world's ``[defaults]`` lie under the file's own ``[defaults]``, so
the three splits differ only in their sequences' names and seeds, and a
range changed in the world changes all of them.
"""

from __future__ import annotations

import tomllib
from collections.abc import Callable, Iterator, Mapping
from importlib import resources
from importlib.resources.abc import Traversable
from typing import Any, NamedTuple

from benchmark.errors import DataError
from benchmark.modality import SceneFactory
from benchmark.model import Sequence

WORLD_FOLDER = "worlds"
"""Folder next to this module holding the worlds suites may name (``[suite] world``)."""

BASE_KEY = "based_on"
"""Key of a sequence table that names the sequence, ``"<suite>/<sequence>"``, it starts from."""

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


def _read(text: str, source: str) -> tuple[Mapping[str, Any], Mapping[str, Any], list[Any]]:
    """The ``[suite]`` header, ``[defaults]`` and ``[[sequence]]`` entries of a TOML document, checked."""
    try:
        document = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise DataError(f"{source}: not valid TOML: {exc}") from exc
    unknown = sorted(set(document) - {"suite", "defaults", "sequence"})
    if unknown:
        raise DataError(f"{source}: unknown top-level key(s) {unknown}; expected suite, defaults, sequence")
    header = document.get("suite")
    if not isinstance(header, Mapping) or not isinstance(header.get("name"), str) or not header["name"]:
        raise DataError(f"{source}: needs a [suite] table with a non-empty name")
    defaults = document.get("defaults", {})
    entries = document.get("sequence", [])
    if not isinstance(defaults, Mapping) or not isinstance(entries, list) or not entries:
        raise DataError(f"{source}: needs [defaults] as a table and at least one [[sequence]]")
    world = header.get("world")
    if world is not None:
        defaults = merge_tables(world_defaults(world, source), defaults)
    return header, defaults, entries


def world_files() -> dict[str, Traversable]:
    """The worlds shipped in this package's :data:`WORLD_FOLDER`, by name (file name without ``.toml``)."""
    folder = resources.files(__package__) / WORLD_FOLDER
    if not folder.is_dir():
        return {}
    return {item.name.removesuffix(".toml"): item for item in folder.iterdir() if item.name.endswith(".toml")}


def world_defaults(name: Any, where: str) -> dict[str, Any]:
    """The ``[defaults]`` table of the world ``name`` (``worlds/<name>.toml``).

    Parameters
    ----------
    name : Any
        The value of a suite's ``[suite] world``.
    where : str
        The suite file naming it, for error messages.

    Raises
    ------
    DataError
        Naming ``where`` when ``name`` is not the name of a shipped world,
        or the world's file when it is not valid TOML or holds anything but
        one ``[defaults]`` table.
    """
    worlds = world_files()
    if not isinstance(name, str) or name not in worlds:
        raise DataError(f"{where}: [suite] world {name!r} is not one of the shipped worlds {sorted(worlds)}")
    source = f"{WORLD_FOLDER}/{worlds[name].name}"
    try:
        document = tomllib.loads(worlds[name].read_text(encoding="utf-8"))
    except tomllib.TOMLDecodeError as exc:
        raise DataError(f"{source}: not valid TOML: {exc}") from exc
    defaults = document.get("defaults")
    if set(document) != {"defaults"} or not isinstance(defaults, Mapping):
        raise DataError(f"{source}: a world holds one [defaults] table and nothing else, got {sorted(document)}")
    return dict(defaults)


def _tables(
    defaults: Mapping[str, Any], entries: list[Any], source: str, resolve: BaseResolver
) -> Iterator[tuple[str, dict[str, Any]]]:
    """``(name, merged table)`` of every entry, in file order, with ``based_on`` resolved and removed."""
    seen: set[str] = set()
    for position, entry in enumerate(entries, start=1):
        short = entry.get("name") if isinstance(entry, Mapping) else None
        if not isinstance(short, str) or not short:
            raise DataError(f"{source}: [[sequence]] number {position} needs a non-empty name")
        if short in seen:
            raise DataError(f"{source}: sequence name {short!r} appears twice")
        seen.add(short)
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
        yield short, table


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
        if header["name"] != suite:
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
        For invalid TOML, a missing or unknown ``[suite]`` key or ``kind``, a
        ``training`` that is not a suite name or a ``scored`` that is not a
        boolean, a sequence without a name, a repeated name, a ``based_on``
        that names nothing, or an invalid sequence definition.
    """
    header, defaults, entries = _read(text, source)
    suite = header["name"]
    kind = header.get("kind")
    if kind not in kinds:
        raise DataError(f"{source}: [suite] kind {kind!r} is not one of the registered scene kinds {sorted(kinds)}")
    extra = sorted(set(header) - {"name", "kind", "description", "training", "scored", "world"})
    if extra:
        raise DataError(f"{source}: unknown [suite] key(s) {extra}")
    training = header.get("training")
    if training is not None and (not isinstance(training, str) or not training or training == suite):
        raise DataError(f"{source}: [suite] training must name another suite, got {training!r}")
    scored = header.get("scored", True)
    if not isinstance(scored, bool):
        raise DataError(f"{source}: [suite] scored must be true or false, got {scored!r}")
    factory = kinds[kind]
    sequences: list[Sequence] = []
    for short, table in _tables(defaults, entries, source, resolve):
        table["name"] = f"{suite}/{short}"
        sequences.append(factory(table, f"{source} [sequence {short}]"))
    return SuiteDefinition(suite, sequences, training, scored)


def suite_files() -> Iterator[Traversable]:
    """The ``*.toml`` suite files shipped in this package, sorted by name."""
    folder = resources.files(__package__)
    yield from sorted((item for item in folder.iterdir() if item.name.endswith(".toml")), key=lambda i: i.name)


def load_suites(kinds: Mapping[str, SceneFactory]) -> list[SuiteDefinition]:
    """Every suite shipped in this package, built with the scene kinds ``kinds``."""
    return [parse_suite(item.read_text(encoding="utf-8"), item.name, kinds) for item in suite_files()]
