"""Hook specifications of the ``trackbench`` pluggy project.

A plugin is a module (or object) registered under the entry-point group
``trackbench`` that implements any of these hooks, marked with
:data:`hookimpl` (re-exported as :data:`benchmark.hookimpl`)::

    from benchmark import hookimpl

    @hookimpl
    def trackbench_register_trackers(registry):
        registry.add_tracker(MyTracker)

The harness calls the hooks through pluggy, in this order: modalities,
then metrics (each for every modality or for one),
then trackers (each names a modality), then datasets (whose scene kinds
belong to modalities).  Pluggy's ``tryfirst``, ``trylast`` and wrappers
order and wrap the implementations of one hook.  The built-in modalities,
the first-party trackers and the shared suites are plugins of exactly this
kind.

Commands of the command line come from a second entry-point group,
``trackbench.commands``, whose plugins implement
:func:`trackbench_register_commands` only: ``trackbench --help`` lists them
without importing every tracker and its dependencies.

The speed bounds of ``trackbench speed`` come from a third group,
``trackbench.speed``, whose plugins implement
:func:`trackbench_register_speed_bounds` only.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import pluggy

if TYPE_CHECKING:
    from benchmark.cli.discovery import CommandRegistry
    from benchmark.registry import Registry
    from benchmark.speed.bounds import SpeedBounds

PROJECT_NAME = "trackbench"

hookspec = pluggy.HookspecMarker(PROJECT_NAME)
"""Marker of the hook specifications below."""

hookimpl = pluggy.HookimplMarker(PROJECT_NAME)
"""Marker for hook implementations in trackbench plugins."""


@hookspec
def trackbench_register_modalities(registry: Registry) -> None:
    """Add modalities, kinds of sensor data, to the registry.

    Call :meth:`Registry.add_modality` with a :class:`benchmark.modality.Modality`:
    its frame and estimate types, scorer, file readers, exporter, scene
    kinds and, optionally, how to draw a frame for the reports.  Trackers
    and sequences name a modality by its ``name``.

    Parameters
    ----------
    registry : Registry
        The registry of this session; errors raised here name the plugin.
    """


@hookspec
def trackbench_register_metrics(registry: Registry) -> None:
    """Add metrics, numbers reported about every cell, to the registry.

    Call :meth:`Registry.add_metric` with a :class:`benchmark.metrics.Metric`
    (and optionally the modality it is for): it then stands on the boards,
    with its interval over seeds, in the history and the nightly site, and
    is judged by the regressions, like the core metrics.

    Parameters
    ----------
    registry : Registry
        The registry of this session; errors raised here name the plugin.
    """


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


@hookspec
def trackbench_register_commands(registry: CommandRegistry) -> None:
    """Add commands to the ``trackbench`` command line.

    Called only on the plugins of the entry-point group
    ``trackbench.commands``, and only when the command line needs them (to
    list the commands, or to run one that is not built in).  Call
    :meth:`CommandRegistry.add_command` with a :class:`click.Command`; the
    command gets the session (:class:`benchmark.cli.session.Session`, with
    the plugin ``registry``) through ``click.pass_obj``, and its
    :class:`~benchmark.errors.TrackbenchError` is shown as one line
    ``Error: ...`` with exit status 2, as for the built-in commands.  Keep
    the module light: import what a command needs inside the command.

    Parameters
    ----------
    registry : CommandRegistry
        The commands of this session; a name already taken (by a built-in
        command or another plugin) is an error naming the plugin.
    """


@hookspec
def trackbench_register_speed_bounds(registry: SpeedBounds) -> None:
    """Declare what ``trackbench speed`` times a tracker (or a core component) against, and the goal.

    Called only on the plugins of the entry-point group
    ``trackbench.speed``, and only by ``trackbench speed``.  Call
    :meth:`benchmark.speed.bounds.SpeedBounds.add_bound` with a
    :class:`benchmark.speed.bounds.SpeedBound` per row: the subject (a
    tracker's name, or a component with its own workload), a factory of the
    bound's workload (an object with a tracker's ``reset`` and ``step`` doing
    the unavoidable part of the tracker's work on the same frames), the
    dataset whose frames are timed, and the goal (``RatioAtMost``,
    ``TimesFaster``, ``FpsAtLeast``, ``MsAtMost``).

    Parameters
    ----------
    registry : SpeedBounds
        The bounds of this invocation; errors raised here name the plugin.
    """
