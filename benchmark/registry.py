"""The registry that plugins fill with trackers and suites.

Plugins receive a :class:`Registry` in their ``trackbench_register_*`` hooks
(the pattern of tox's ``tox_register_tox_env``).  The registry checks every
addition and names the plugin that made a bad one.
"""

from __future__ import annotations

import dataclasses
import inspect
from collections.abc import Iterable, Iterator, Mapping
from contextlib import contextmanager
from dataclasses import dataclass
from typing import Any

from benchmark.errors import ParameterError, PluginError
from benchmark.model import MODALITIES, Sequence
from benchmark.tracker import Tracker, params_key


@dataclass(frozen=True)
class Origin:
    """Where a registered item came from: the plugin and its distribution."""

    plugin: str = "<direct>"
    distribution: str = "-"


@dataclass(frozen=True)
class TrackerEntry:
    """A registered tracker: its class, its parameters and its origin."""

    name: str
    tracker_class: type[Tracker]
    params: Any
    origin: Origin = Origin()

    @property
    def version(self) -> str:
        return self.tracker_class.version

    @property
    def modality(self) -> str:
        return self.tracker_class.modality

    @property
    def cache_key(self) -> str:
        """Hash of name, version and parameters (see :func:`benchmark.tracker.params_key`)."""
        return params_key(self.name, self.version, self.params)

    def create(self) -> Tracker:
        """A fresh tracker instance with these parameters."""
        return self.tracker_class(self.params)

    def with_params(self, overrides: Mapping[str, Any]) -> TrackerEntry:
        """This entry with some parameters changed (names are checked)."""
        current = dataclasses.asdict(self.params)
        current.update(overrides)
        return dataclasses.replace(self, params=self.tracker_class.make_params(current))


@dataclass(frozen=True)
class SuiteEntry:
    """A registered suite: named sequences of one or more modalities."""

    name: str
    sequences: tuple[Sequence, ...]
    origin: Origin = Origin()


class Registry:
    """Trackers and suites contributed by plugins.

    Examples
    --------
    >>> registry = Registry()
    >>> registry.add_tracker(MyTracker)                                  # doctest: +SKIP
    >>> registry.add_tracker(MyTracker, name="mine-fast", params={"n": 10})  # doctest: +SKIP
    """

    def __init__(self) -> None:
        self.trackers: dict[str, TrackerEntry] = {}
        self.suites: dict[str, SuiteEntry] = {}
        self._origin = Origin()

    @contextmanager
    def acting_for(self, origin: Origin) -> Iterator[None]:
        """Attribute additions made inside the block to ``origin``."""
        previous, self._origin = self._origin, origin
        try:
            yield
        finally:
            self._origin = previous

    def _fail(self, message: str) -> PluginError:
        return PluginError(f"plugin {self._origin.plugin!r} ({self._origin.distribution}): {message}")

    def add_tracker(
        self, tracker_class: type[Tracker], *, name: str | None = None, params: Mapping[str, Any] | None = None
    ) -> TrackerEntry:
        """Register a tracker class, optionally as a named variant with other parameters.

        Raises
        ------
        PluginError
            If the class does not fulfil the tracker contract, the name is
            taken, or a parameter is unknown.
        """
        if not (inspect.isclass(tracker_class) and issubclass(tracker_class, Tracker)):
            raise self._fail(f"{tracker_class!r} is not a subclass of benchmark.Tracker")
        if inspect.isabstract(tracker_class):
            missing = ", ".join(sorted(tracker_class.__abstractmethods__))
            raise self._fail(f"tracker class {tracker_class.__name__} does not implement {missing}")
        for attribute in ("name", "version", "modality"):
            if not isinstance(getattr(tracker_class, attribute, None), str) or not getattr(tracker_class, attribute):
                raise self._fail(f"tracker class {tracker_class.__name__} must set a non-empty str {attribute!r}")
        if tracker_class.modality not in MODALITIES:
            raise self._fail(
                f"tracker {tracker_class.name!r} has modality {tracker_class.modality!r}; expected one of {MODALITIES}"
            )
        params_class = tracker_class.Params
        if not (dataclasses.is_dataclass(params_class) and params_class.__dataclass_params__.frozen):
            raise self._fail(f"tracker {tracker_class.name!r}: Params must be a frozen dataclass")
        try:
            params_class()
        except TypeError as exc:
            raise self._fail(f"tracker {tracker_class.name!r}: every parameter needs a default ({exc})") from exc
        entry_name = name or tracker_class.name
        if entry_name in self.trackers:
            other = self.trackers[entry_name].origin
            raise self._fail(f"tracker name {entry_name!r} is already registered by plugin {other.plugin!r}")
        try:
            values = tracker_class.make_params(params)
        except ParameterError as exc:
            raise self._fail(str(exc)) from exc
        entry = TrackerEntry(entry_name, tracker_class, values, self._origin)
        self.trackers[entry_name] = entry
        return entry

    def add_suite(self, name: str, sequences: Iterable[Sequence]) -> SuiteEntry:
        """Register a suite of sequences under ``name``.

        Sequence names (``info.name``) must be unique across all suites.

        Raises
        ------
        PluginError
            If the suite or one of its sequence names is taken, or an item
            is not a :class:`benchmark.model.Sequence`.
        """
        if name in self.suites:
            raise self._fail(f"suite {name!r} is already registered by plugin {self.suites[name].origin.plugin!r}")
        items = tuple(sequences)
        taken = {seq.info.name for suite in self.suites.values() for seq in suite.sequences}
        for item in items:
            if not isinstance(item, Sequence):
                raise self._fail(f"suite {name!r}: {item!r} is not a benchmark.model.Sequence")
            if item.info.name in taken:
                raise self._fail(f"suite {name!r}: sequence name {item.info.name!r} is already registered")
            taken.add(item.info.name)
        entry = SuiteEntry(name, items, self._origin)
        self.suites[name] = entry
        return entry

    def sequence(self, name: str) -> Sequence:
        """A registered sequence by its full name (``suite/sequence``).

        Raises
        ------
        KeyError
            With the list of known names.
        """
        for suite in self.suites.values():
            for seq in suite.sequences:
                if seq.info.name == name:
                    return seq
        known = ", ".join(seq.info.name for suite in self.suites.values() for seq in suite.sequences)
        raise KeyError(f"no registered sequence {name!r} (known: {known or 'none'})")
