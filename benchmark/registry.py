"""The registry that plugins fill with modalities, metrics, trackers and suites.

Plugins receive a :class:`Registry` in their ``trackbench_register_*`` hooks
(the pattern of tox's ``tox_register_tox_env``).  The registry checks every
addition against what is already there (a tracker's modality must be
registered, a file suffix read by one modality only) and names the plugin
that made a bad one.  Which plugin is adding something is told by
:meth:`Registry.acting_for`, or found by the function the plugin manager
hands to :meth:`Registry.attribute_with` while pluggy calls the hooks.
"""

from __future__ import annotations

import dataclasses
import inspect
from collections.abc import Callable, Iterable, Iterator, Mapping
from contextlib import contextmanager
from dataclasses import dataclass
from typing import Any

from benchmark.errors import ParameterError, PluginError
from benchmark.identity import code_digest
from benchmark.metrics import CORE, Metric, Metrics
from benchmark.modality import Modality, SceneFactory
from benchmark.model import INFO_FIELDS, Sequence
from benchmark.parameters import params_key
from benchmark.tracker import Tracker


class _InvalidTracker(Exception):
    """A tracker class that breaks the tracker contract; it costs only that tracker."""


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
        """Hash of name, version, parameters and the tracker's package's code (:func:`benchmark.identity.code_digest`).

        An edit of the package without a version bump is a new key, so
        ``--resume`` runs its cells again instead of showing old results.
        """
        return params_key(self.name, self.version, self.params, code_digest(self.tracker_class.__module__))

    @property
    def params_key(self) -> str:
        """Hash of name, version and parameters only: what seeds the tracker's training, whatever its code."""
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
    """A registered suite: named sequences of one or more modalities.

    Attributes
    ----------
    training : str or None
        The suite whose labelled sequences train the trackers that learn
        (:class:`benchmark.tracker.Learns`) before they run on this one.
    scored : bool
        False for a training split: a run that names no suite leaves it out.
    """

    name: str
    sequences: tuple[Sequence, ...]
    origin: Origin = Origin()
    training: str | None = None
    scored: bool = True


class PluginRecords:
    """What plugins add through their hooks, each addition attributed to the plugin that made it.

    The base of every registry a plugin manager fills (:class:`Registry`
    here, :class:`benchmark.cli.discovery.CommandRegistry` for commands):
    it knows which plugin is adding something, notes the problems of
    plugins, and words their errors.
    """

    def __init__(self) -> None:
        self.problems: list[str] = []
        """Plugins that could not be loaded, one line each (naming plugin, distribution and exception)."""
        self._origin: Origin | None = None
        self._find_origin: Callable[[], Origin] | None = None

    @contextmanager
    def acting_for(self, origin: Origin) -> Iterator[None]:
        """Attribute additions made inside the block to ``origin``."""
        previous, self._origin = self._origin, origin
        try:
            yield
        finally:
            self._origin = previous

    def attribute_with(self, find_origin: Callable[[], Origin] | None) -> None:
        """Ask ``find_origin()`` who makes each addition outside :meth:`acting_for` (None: nobody to ask)."""
        self._find_origin = find_origin

    @property
    def origin(self) -> Origin:
        """The plugin that is adding something now."""
        if self._origin is not None:
            return self._origin
        return self._find_origin() if self._find_origin is not None else Origin()

    def add_problem(self, message: str) -> None:
        """Note, for the calling plugin, something it could not register, such as one invalid suite file.

        The rest of what it registers is kept; the problem is shown as a
        warning and in the board's Problems section, and the command exits
        non-zero.
        """
        origin = self.origin
        self.problems.append(f"plugin {origin.plugin!r} ({origin.distribution}): {message}")

    def _fail(self, message: str) -> PluginError:
        origin = self.origin
        return PluginError(f"plugin {origin.plugin!r} ({origin.distribution}): {message}", plugin=origin.plugin)


class Registry(PluginRecords):
    """Modalities, metrics, trackers and suites contributed by plugins.

    Examples
    --------
    >>> registry = Registry()
    >>> registry.add_modality(CAMERA)                                    # doctest: +SKIP
    >>> registry.add_tracker(MyTracker)                                  # doctest: +SKIP
    >>> registry.add_tracker(MyTracker, name="mine-fast", params={"n": 10})  # doctest: +SKIP
    """

    def __init__(self) -> None:
        super().__init__()
        self.modalities: dict[str, Modality] = {}
        self.trackers: dict[str, TrackerEntry] = {}
        self.suites: dict[str, SuiteEntry] = {}
        self.metrics: Metrics = CORE
        """The metrics of every board: the core ones, the modalities' errors and those plugins added."""

    def add_modality(self, modality: Modality) -> Modality:
        """Register a modality: a kind of sensor data, its types, scorer, readers and scene kinds.

        Raises
        ------
        PluginError
            If ``modality`` is not a :class:`~benchmark.modality.Modality`,
            its name is taken, its error columns are not named ``err_*``, or
            one of its file suffixes, its folder reader or one of its scene
            kinds is already another modality's.
        """
        if not isinstance(modality, Modality):
            raise self._fail(f"{modality!r} is not a benchmark.modality.Modality")
        if not isinstance(modality.name, str) or not modality.name:
            raise self._fail(f"a modality needs a non-empty str name, not {modality.name!r}")
        if modality.name in self.modalities:
            raise self._fail(f"modality {modality.name!r} is already registered")
        columns = modality.error_columns
        if not all(isinstance(column, str) and column.startswith("err_") for column in columns):
            raise self._fail(f"modality {modality.name!r}: error columns must be named err_<what>_<unit>: {columns}")
        readers_of = {claim: name for name, known in self.modalities.items() for claim in known.claims}
        for claim in modality.claims:
            if claim in readers_of:
                other = readers_of[claim]
                raise self._fail(f"modality {modality.name!r}: {claim} is already read by modality {other!r}")
        kinds_of = {kind: name for name, known in self.modalities.items() for kind in known.scene_kinds}
        for kind in modality.scene_kinds:
            if kind in kinds_of:
                other = kinds_of[kind]
                raise self._fail(f"modality {modality.name!r}: scene kind {kind!r} belongs to modality {other!r}")
        self.modalities[modality.name] = modality
        return modality

    def add_metric(self, metric: Metric, modality: str | None = None) -> Metric:
        """Register a metric, for every modality or for ``modality`` alone.

        Raises
        ------
        PluginError
            If ``metric`` is not a :class:`~benchmark.metrics.Metric`,
            ``modality`` is not registered, or the metric's name (or a
            column derived from it) is already taken.
        """
        if modality is not None and modality not in self.modalities:
            raise self._fail(f"metric for unknown modality {modality!r}")
        try:
            self.metrics = self.metrics.adding(metric, modality)
        except ValueError as exc:
            raise self._fail(str(exc)) from None
        return metric

    @property
    def scene_kinds(self) -> dict[str, SceneFactory]:
        """Every registered modality's scene kinds: name to factory."""
        return {kind: make for modality in self.modalities.values() for kind, make in modality.scene_kinds.items()}

    def add_tracker(
        self, tracker_class: type[Tracker], *, name: str | None = None, params: Mapping[str, Any] | None = None
    ) -> TrackerEntry | None:
        """Register a tracker class, optionally as a named variant with other parameters.

        A class that does not fulfil the tracker contract, a name already
        taken or a parameter the class does not declare costs only this
        tracker: it is left out, the problem is noted for the calling plugin
        (:meth:`add_problem`, an error with ``--strict-plugins``) and the
        plugin's other trackers are kept.

        Returns
        -------
        TrackerEntry or None
            The entry; None when the tracker was left out.
        """
        try:
            entry = self._tracker_entry(tracker_class, name, params)
        except (_InvalidTracker, ParameterError) as exc:
            self.add_problem(f"{exc}; the tracker is left out")
            return None
        self.trackers[entry.name] = entry
        return entry

    def _tracker_entry(
        self, tracker_class: type[Tracker], name: str | None, params: Mapping[str, Any] | None
    ) -> TrackerEntry:
        """The entry of a tracker class, or an error saying which part of the contract it breaks."""
        if not (inspect.isclass(tracker_class) and issubclass(tracker_class, Tracker)):
            raise _InvalidTracker(f"{tracker_class!r} is not a subclass of benchmark.Tracker")
        if inspect.isabstract(tracker_class):
            missing = ", ".join(sorted(tracker_class.__abstractmethods__))
            raise _InvalidTracker(f"tracker class {tracker_class.__name__} does not implement {missing}")
        for attribute in ("name", "version", "modality"):
            if not isinstance(getattr(tracker_class, attribute, None), str) or not getattr(tracker_class, attribute):
                raise _InvalidTracker(f"tracker class {tracker_class.__name__} must set a non-empty str {attribute!r}")
        if tracker_class.modality not in self.modalities:
            known = ", ".join(self.modalities) or "none"
            raise _InvalidTracker(
                f"tracker {tracker_class.name!r} has modality {tracker_class.modality!r}, which no plugin "
                f"registered (registered: {known})"
            )
        unknown_needs = [need for need in tracker_class.needs if need not in INFO_FIELDS]
        if unknown_needs:
            raise _InvalidTracker(
                f"tracker {tracker_class.name!r}: needs must be a tuple of SequenceInfo fields "
                f"({', '.join(sorted(INFO_FIELDS))}), got {tracker_class.needs!r}"
            )
        params_class = tracker_class.Params
        if not (dataclasses.is_dataclass(params_class) and params_class.__dataclass_params__.frozen):
            raise _InvalidTracker(f"tracker {tracker_class.name!r}: Params must be a frozen dataclass")
        try:
            params_class()
        except TypeError as exc:
            raise _InvalidTracker(f"tracker {tracker_class.name!r}: every parameter needs a default ({exc})") from exc
        entry_name = name or tracker_class.name
        if entry_name in self.trackers:
            other = self.trackers[entry_name].origin
            raise _InvalidTracker(f"tracker name {entry_name!r} is already registered by plugin {other.plugin!r}")
        return TrackerEntry(entry_name, tracker_class, tracker_class.make_params(params), self.origin)

    def add_suite(
        self, name: str, sequences: Iterable[Sequence], *, training: str | None = None, scored: bool = True
    ) -> SuiteEntry:
        """Register a suite of sequences under ``name``.

        Sequence names (``identity.name``) must be unique across all suites.
        Nothing is read from the sequences but their identities.  ``training``
        names the suite that trains learning trackers for this one (it may be
        registered later); ``scored=False`` marks a training split, which
        runs leave out unless they name it.

        Raises
        ------
        PluginError
            If the suite or one of its sequence names is taken, or an item
            is not a :class:`benchmark.model.Sequence` of a registered modality.
        """
        if name in self.suites:
            raise self._fail(f"suite {name!r} is already registered by plugin {self.suites[name].origin.plugin!r}")
        items = tuple(sequences)
        taken = {seq.identity.name for suite in self.suites.values() for seq in suite.sequences}
        for item in items:
            if not isinstance(item, Sequence):
                raise self._fail(f"suite {name!r}: {item!r} is not a benchmark.model.Sequence")
            identity = item.identity
            if identity.name in taken:
                raise self._fail(f"suite {name!r}: sequence name {identity.name!r} is already registered")
            if identity.modality not in self.modalities:
                raise self._fail(
                    f"suite {name!r}: sequence {identity.name!r} has modality {identity.modality!r}, "
                    f"which no plugin registered (registered: {', '.join(self.modalities) or 'none'})"
                )
            taken.add(identity.name)
        entry = SuiteEntry(name, items, self.origin, training, scored)
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
                if seq.identity.name == name:
                    return seq
        known = ", ".join(seq.identity.name for suite in self.suites.values() for seq in suite.sequences)
        raise KeyError(f"no registered sequence {name!r} (known: {known or 'none'})")
