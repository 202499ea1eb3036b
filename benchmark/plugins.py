"""The plugin manager: every tracker and suite comes through entry points.

Plugins are modules named in the entry-point group ``trackbench`` of any
installed distribution; trackbench's own trackers and suites are listed in
its own ``pyproject.toml`` and loaded by the same loop, so there is one path
for everybody.  After loading, ``check_pending()`` makes a misspelt hook
fail loudly.

A plugin is blocked with ``--disable NAME`` or by listing it, comma
separated, in the environment variable ``TRACKBENCH_DISABLE_PLUGINS``.
"""

from __future__ import annotations

import importlib.metadata
import os
from collections.abc import Iterable

import pluggy

from benchmark import hookspecs
from benchmark.errors import PluginError
from benchmark.registry import Origin, Registry

ENTRY_POINT_GROUP = "trackbench"
DISABLE_ENV = "TRACKBENCH_DISABLE_PLUGINS"
REGISTER_HOOKS = ("trackbench_register_trackers", "trackbench_register_datasets")


def disabled_from_environment() -> set[str]:
    """Plugin names listed in ``TRACKBENCH_DISABLE_PLUGINS``."""
    return {name.strip() for name in os.environ.get(DISABLE_ENV, "").split(",") if name.strip()}


def make_plugin_manager(disable: Iterable[str] = ()) -> tuple[pluggy.PluginManager, dict[str, Origin]]:
    """Load every plugin of the ``trackbench`` entry-point group.

    Parameters
    ----------
    disable : iterable of str
        Entry-point names to block, in addition to those in the environment.

    Returns
    -------
    manager : pluggy.PluginManager
        With the hook specifications added and the plugins registered.
    origins : dict
        For each registered plugin name, the distribution it came from.

    Raises
    ------
    PluginError
        If a plugin fails to import, does not validate against the hook
        specifications, or implements a hook that does not exist.
    """
    manager = pluggy.PluginManager(hookspecs.PROJECT_NAME)
    manager.add_hookspecs(hookspecs)
    for name in set(disable) | disabled_from_environment():
        manager.set_blocked(name)
    origins: dict[str, Origin] = {}
    for dist in importlib.metadata.distributions():
        for ep in dist.entry_points:
            if ep.group != ENTRY_POINT_GROUP or manager.is_blocked(ep.name) or manager.get_plugin(ep.name):
                continue
            origin = Origin(ep.name, f"{dist.metadata['name']} {dist.version}")
            try:
                plugin = ep.load()
            except Exception as exc:
                raise PluginError(
                    f"plugin {ep.name!r} ({origin.distribution}) failed to import {ep.value!r}: "
                    f"{type(exc).__name__}: {exc}. Disable it with --disable {ep.name} "
                    f"or {DISABLE_ENV}={ep.name}"
                ) from exc
            try:
                manager.register(plugin, name=ep.name)
            except pluggy.PluginValidationError as exc:
                raise PluginError(f"plugin {ep.name!r} ({origin.distribution}): {exc}") from exc
            origins[ep.name] = origin
    try:
        manager.check_pending()
    except pluggy.PluginValidationError as exc:
        raise PluginError(f"plugin {manager.get_name(exc.plugin)!r}: {exc}") from exc
    return manager, origins


def fill_registry(manager: pluggy.PluginManager, origins: dict[str, Origin]) -> Registry:
    """Call every plugin's register hooks, attributing each addition to it.

    Each implementation is called on its own so that an error, raised by the
    plugin or by the registry's checks, names the plugin responsible.
    """
    registry = Registry()
    for hook_name in REGISTER_HOOKS:
        # get_hookimpls() lists implementations in load order (pluggy calls them reversed).
        for impl in getattr(manager.hook, hook_name).get_hookimpls():
            origin = origins.get(impl.plugin_name, Origin(impl.plugin_name))
            with registry.acting_for(origin):
                try:
                    impl.function(*(dict(registry=registry)[arg] for arg in impl.argnames))
                except PluginError:
                    raise
                except Exception as exc:
                    raise PluginError(
                        f"plugin {origin.plugin!r} ({origin.distribution}) raised in {hook_name}: "
                        f"{type(exc).__name__}: {exc}"
                    ) from exc
    return registry


def load_registry(disable: Iterable[str] = ()) -> Registry:
    """Discover all plugins and return the registry they filled."""
    return fill_registry(*make_plugin_manager(disable))
