"""The plugin manager: every modality, tracker and suite comes through entry points.

Plugins are modules named in the entry-point group ``trackbench`` of any
installed distribution; trackbench's own modalities, trackers and suites
are listed in its own ``pyproject.toml`` and loaded the same way, so there
is one path for everybody.  Loading and calling go through pluggy itself:
:meth:`pluggy.PluginManager.load_setuptools_entrypoints` imports and
registers each plugin, ``check_pending()`` makes a misspelt hook fail
loudly, and each ``trackbench_register_*`` hook is one pluggy hook call, so
``tryfirst``, ``trylast``, wrappers and pluggy's tracing work as they do
for pytest's plugins.

The same machinery loads the plugins of another entry-point group with
its own hooks (:class:`PluginGroup`): the commands of the command line come
from the group ``trackbench.commands`` (:mod:`benchmark.cli.discovery`), so
that listing them imports no tracker.  A plugin implementing a hook that is
called only on another group's plugins fails like a misspelt hook.

Two distributions that offer an entry point of the same name are an error
naming both: one would otherwise silently shadow the other.  A plugin that
fails to import or does not validate against the hook specifications is
left out, and so is one whose register hook raises (``SystemExit``
included) or adds something invalid: its trackers are unavailable, the
registry lists the problem (:attr:`benchmark.registry.Registry.problems`)
and every other plugin works.
With ``strict=True`` (``trackbench --strict-plugins``, for CI) it is an
error instead.  A plugin is
blocked with ``--disable NAME`` or by listing it, comma separated, in the
environment variable ``TRACKBENCH_DISABLE_PLUGINS``.

Every error names the plugin at fault.  While a hook runs, the registry
attributes each addition to the plugin whose hook implementation is on the
call stack (:func:`calling_plugin`); an exception escaping a hook is
attributed to the innermost implementation in its traceback.  Where one
function serves several plugins, closures are told apart by what they
captured, and a plain shared function is attributed to all its plugins.
"""

from __future__ import annotations

import importlib.metadata
import inspect
import os
import traceback
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass
from types import CodeType, FrameType
from typing import TypeVar

import pluggy
from pluggy import HookImpl

from benchmark import hookspecs
from benchmark.errors import PluginError
from benchmark.registry import Origin, PluginRecords, Registry
from benchmark.shared_modules import Snapshot

ENTRY_POINT_GROUP = "trackbench"
DISABLE_ENV = "TRACKBENCH_DISABLE_PLUGINS"
REGISTER_HOOKS = (
    "trackbench_register_modalities",
    "trackbench_register_metrics",
    "trackbench_register_trackers",
    "trackbench_register_datasets",
)
"""The hooks that fill a registry, in the order they are called."""


@dataclass(frozen=True)
class PluginGroup:
    """An entry-point group of plugins, the hooks called on them in that order, and what leaving one out costs."""

    name: str
    hooks: tuple[str, ...]
    lost: str


REGISTRY_PLUGINS = PluginGroup(ENTRY_POINT_GROUP, REGISTER_HOOKS, "its trackers are unavailable")
"""The plugins that fill a :class:`~benchmark.registry.Registry` with modalities, trackers and suites."""

Records = TypeVar("Records", bound=PluginRecords)


def disabled_from_environment() -> set[str]:
    """Plugin names listed in ``TRACKBENCH_DISABLE_PLUGINS``."""
    return {name.strip() for name in os.environ.get(DISABLE_ENV, "").split(",") if name.strip()}


def entry_points(group: str = ENTRY_POINT_GROUP) -> dict[str, dict[str, importlib.metadata.EntryPoint]]:
    """The entry points of ``group`` by name, each with the distributions (``"name version"``) offering it.

    A distribution found twice on the path (an editable install seen from
    its own folder, say) counts once.
    """
    found: dict[str, dict[str, importlib.metadata.EntryPoint]] = {}
    seen: set[str] = set()
    for dist in importlib.metadata.distributions():
        name = dist.metadata["name"]
        if name in seen:
            continue
        seen.add(name)
        for ep in dist.entry_points:
            if ep.group == group:
                found.setdefault(ep.name, {})[f"{name} {dist.version}"] = ep
    return found


class PluginManager(pluggy.PluginManager):
    """pluggy's manager, which also remembers the plugins it had to leave out."""

    def __init__(self, lost: str = REGISTRY_PLUGINS.lost) -> None:
        super().__init__(hookspecs.PROJECT_NAME)
        self.add_hookspecs(hookspecs)
        self.problems: list[str] = []
        self.lost = lost

    def leave_out(self, name: str, error: PluginError, strict: bool) -> None:
        """Unregister and block plugin ``name`` and note why, or raise ``error`` when ``strict``."""
        if strict:
            raise error
        self.set_blocked(name)
        self.problems.append(f"{error} (left out: {self.lost})")


def make_plugin_manager(
    disable: Iterable[str] = (), *, strict: bool = False, group: PluginGroup = REGISTRY_PLUGINS
) -> tuple[PluginManager, dict[str, Origin]]:
    """Load every plugin of an entry-point group (by default ``trackbench``).

    Parameters
    ----------
    disable : iterable of str
        Entry-point names to block, in addition to those in the environment.
    strict : bool
        Raise for a plugin that fails to import or to validate, instead of
        leaving it out and noting it in ``manager.problems``.
    group : PluginGroup
        The entry-point group, and the hooks its plugins may implement: one
        that implements a hook called only on another group's plugins fails
        like a misspelt hook.

    Returns
    -------
    manager : PluginManager
        With the hook specifications added, the plugins registered and the
        problems of those left out.
    origins : dict
        For each registered plugin name, where it came from.

    Raises
    ------
    PluginError
        If two distributions offer the same entry-point name; with
        ``strict``, also if a plugin fails to import, does not validate
        against the hook specifications, or implements a hook that does not
        exist, or one of another group.
    """
    manager = PluginManager(group.lost)
    for name in set(disable) | disabled_from_environment():
        manager.set_blocked(name)
    origins: dict[str, Origin] = {}
    for name, offers in entry_points(group.name).items():
        if manager.is_blocked(name):
            continue
        if len(offers) > 1:
            raise PluginError(
                f"plugin name {name!r} of the {group.name!r} entry-point group is taken twice, by "
                f"{' and '.join(sorted(offers))}; uninstall one, or disable the name with --disable {name}"
            )
        ((distribution, ep),) = offers.items()
        shared = Snapshot.take()
        try:
            manager.load_setuptools_entrypoints(group.name, name=name)
        except pluggy.PluginValidationError as exc:
            shared.restore()
            manager.leave_out(name, PluginError(f"plugin {name!r} ({distribution}): {exc}"), strict)
            continue
        except (Exception, SystemExit) as exc:  # a plugin's sys.exit() at import must not end the command
            shared.restore()
            error = PluginError(
                f"plugin {name!r} ({distribution}) failed to import {ep.value!r}: "
                f"{type(exc).__name__}: {' '.join(str(exc).split())}. "
                f"Disable it with --disable {name} or {DISABLE_ENV}={name}"
            )
            manager.leave_out(name, error, strict)
            continue
        changed = shared.restore()
        if changed:
            error = PluginError(
                f"plugin {name!r} ({distribution}) changed {', '.join(changed)} when imported, which would change "
                f"every other tracker's numbers (restored). Disable it with --disable {name} or {DISABLE_ENV}={name}"
            )
            manager.leave_out(name, error, strict)
            continue
        origins[name] = Origin(name, distribution)
    while True:
        try:
            manager.check_pending()
            break
        except pluggy.PluginValidationError as exc:
            name = manager.get_name(exc.plugin) or "?"
            origin = origins.pop(name, Origin(name))
            manager.leave_out(name, PluginError(f"plugin {name!r} ({origin.distribution}): {exc}"), strict)
    for name, origin in list(origins.items()):
        foreign = [caller.name for caller in manager.get_hookcallers(manager.get_plugin(name)) or ()]
        foreign = [hook for hook in foreign if hook not in group.hooks]
        if foreign:
            del origins[name]
            error = PluginError(
                f"plugin {name!r} ({origin.distribution}) of the {group.name!r} entry-point group implements "
                f"{', '.join(foreign)}, which is called only on the plugins of another group"
            )
            manager.leave_out(name, error, strict)
    return manager, origins


Implementations = Mapping[CodeType, Sequence[tuple[HookImpl, Origin]]]
"""The code of the register hook implementations, each with the implementations (and plugins) running it."""


def _implementations(
    manager: pluggy.PluginManager, origins: Mapping[str, Origin], hook_names: Sequence[str]
) -> Implementations:
    found: dict[CodeType, list[tuple[HookImpl, Origin]]] = {}
    for hook_name in hook_names:
        for impl in getattr(manager.hook, hook_name).get_hookimpls():
            origin = origins.get(impl.plugin_name, Origin(impl.plugin_name))
            found.setdefault(impl.function.__code__, []).append((impl, origin))
    return found


def _runs_in(impl: HookImpl, frame: FrameType) -> bool:
    """Whether ``frame`` runs ``impl`` rather than another implementation of the same code.

    Closures of one factory differ by what they captured, methods of one
    class by the object they are bound to; plain functions cannot be told apart.
    """
    function = impl.function
    if inspect.ismethod(function):
        return frame.f_locals.get(frame.f_code.co_varnames[0]) is function.__self__
    cells = function.__closure__ or ()
    return bool(cells) and all(
        frame.f_locals.get(name) is cell.cell_contents for name, cell in zip(frame.f_code.co_freevars, cells)
    )


def _frame_origin(frame: FrameType, candidates: Sequence[tuple[HookImpl, Origin]]) -> Origin:
    """The plugin whose implementation runs in ``frame``; all of them where that stays ambiguous."""
    if len(candidates) > 1:
        candidates = [(impl, origin) for impl, origin in candidates if _runs_in(impl, frame)] or candidates
    plugins = list(dict.fromkeys(origin for _, origin in candidates))
    if len(plugins) == 1:
        return plugins[0]
    return Origin(" or ".join(o.plugin for o in plugins), " or ".join(o.distribution for o in plugins))


def calling_plugin(implementations: Implementations, frame: FrameType | None) -> Origin:
    """The plugin whose hook implementation is nearest ``frame`` on the call stack."""
    while frame is not None:
        if frame.f_code in implementations:
            return _frame_origin(frame, implementations[frame.f_code])
        frame = frame.f_back
    return Origin()


def _raising_plugin(exc: BaseException, implementations: Implementations) -> Origin:
    """The plugin of the innermost hook implementation in ``exc``'s traceback."""
    frames = [frame for frame, _ in traceback.walk_tb(exc.__traceback__) if frame.f_code in implementations]
    return _frame_origin(frames[-1], implementations[frames[-1].f_code]) if frames else Origin()


def fill_registry(
    manager: pluggy.PluginManager,
    origins: Mapping[str, Origin],
    make: Callable[[], Records] = Registry,
    hook_names: Sequence[str] = REGISTER_HOOKS,
) -> Records:
    """Call the hooks that fill a new ``make()`` through pluggy, attributing every addition to its plugin.

    Raises
    ------
    PluginError
        For a bad addition or an exception raised by a hook, naming the plugin.
    """
    registry = make()
    implementations = _implementations(manager, origins, hook_names)
    registry.attribute_with(lambda: calling_plugin(implementations, inspect.currentframe()))
    try:
        for hook_name in hook_names:
            try:
                getattr(manager.hook, hook_name)(registry=registry)
            except PluginError:
                raise
            except (Exception, SystemExit) as exc:
                origin = _raising_plugin(exc, implementations)
                raise PluginError(
                    f"plugin {origin.plugin!r} ({origin.distribution}) raised in {hook_name}: "
                    f"{type(exc).__name__}: {exc}",
                    plugin=origin.plugin,
                ) from exc
    finally:
        registry.attribute_with(None)
    return registry


def load_registry(disable: Iterable[str] = (), *, strict: bool = False) -> Registry:
    """Discover all plugins and return the registry they filled, with the problems of those left out.

    See :func:`load_plugins`.
    """
    return load_plugins(Registry, REGISTRY_PLUGINS, disable, strict=strict)


def load_plugins(
    make: Callable[[], Records], group: PluginGroup, disable: Iterable[str] = (), *, strict: bool = False
) -> Records:
    """Load the plugins of ``group`` and return the ``make()`` their hooks filled, with the problems of those left out.

    A plugin whose register hook raises, or adds something invalid, is left
    out like one that fails to import, and the registry is filled again
    without it, so that nothing it added before failing remains.  ``strict``
    makes any of these an error (:func:`make_plugin_manager`).

    Raises
    ------
    PluginError
        With ``strict``, for any plugin left out; always, for a failure that
        cannot be pinned on one plugin.
    """
    manager, origins = make_plugin_manager(disable, strict=strict, group=group)
    while True:
        try:
            registry = fill_registry(manager, origins, make, group.hooks)
            break
        except PluginError as exc:
            if exc.plugin not in origins:
                raise
            origins = {name: origin for name, origin in origins.items() if name != exc.plugin}
            manager.leave_out(exc.plugin, exc, strict)
    if strict and registry.problems:
        raise PluginError(registry.problems[0])
    registry.problems.extend(manager.problems)
    return registry
