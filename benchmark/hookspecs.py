"""Hook specifications of the ``trackbench`` pluggy project.

A plugin is a module (or object) registered under the entry-point group
``trackbench`` that implements any of these hooks, marked with
:data:`benchmark.hookimpl`::

    from benchmark import hookimpl

    @hookimpl
    def trackbench_register_trackers(registry):
        registry.add_tracker(MyTracker)

The first-party trackers and suites are plugins of exactly this kind.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import pluggy

if TYPE_CHECKING:
    from benchmark.registry import Registry

PROJECT_NAME = "trackbench"

hookspec = pluggy.HookspecMarker(PROJECT_NAME)


@hookspec
def trackbench_register_trackers(registry: Registry) -> None:
    """Add tracker classes to the registry.

    Call :meth:`Registry.add_tracker` once per tracker class, or several
    times with different ``name`` and ``params`` to register variants.

    Parameters
    ----------
    registry : Registry
        The registry of this session; errors raised here name the plugin.
    """


@hookspec
def trackbench_register_datasets(registry: Registry) -> None:
    """Add suites of sequences to the registry.

    Call :meth:`Registry.add_suite` with a suite name and its
    :class:`benchmark.model.Sequence` objects.  Sequences must be lazy and
    picklable: cells run in worker processes.

    Parameters
    ----------
    registry : Registry
        The registry of this session; errors raised here name the plugin.
    """
