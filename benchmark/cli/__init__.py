"""The ``trackbench`` command line.

::

    trackbench [--disable PLUGIN]... COMMAND

    list          trackers: name, version, modality, origin and parameters
    datasets      suites and their sequences
    run           run cells, store them and publish the leaderboard
    leaderboard   re-publish the leaderboard of an existing results database
    tables        a suite's results of the latest run as one table per case (stereo: Tables 6-8 of seeds/002)
    diagnose      the likelihood ceiling of a tracker's observation model on camera sequences
    pose-table    a camera tracker's pose estimates beside the truth, frame by frame (seeds/004)
    import        labels (CSV, CVAT) or a ROS bag in as an image sequence file with its sidecar
    label         label a camera sequence's cable by hand in the browser (seeds/000, appendix B)
    make-dataset  write a suite's sequences to disk (PNG frames plus sequence files, or swath files)
    cache         the frame cache: info (what it holds) and clear
    nightly       run, add the run to the history database, report its changes, rewrite the site
    compare       what changed between two runs of the history
    report        rebuild the site from the history without running anything
    check         the conformance checks of benchmark.testing on installed trackers
    replay        one cell frame by frame as a self-contained page: truth, estimate, belief (seeds/000, 4.7)
    new-tracker   write the skeleton of a tracker plugin package (pyproject, tracker, one-line test)
    speed         each tracker against the bound its plugin declares, alternating rounds, the ratio table

Each built-in command is a module of this package (``run``, ``boards``,
``history``, ...); ``diagnose``, ``pose-table`` and ``import`` are the camera
modality's (:mod:`benchmark.modalities.camera.commands`), added through the
``trackbench_register_commands`` hook as any plugin's commands are
(:mod:`benchmark.cli.discovery`).

``run`` forms a cell for every selected tracker, sequence and seed whose
modalities match, and runs the cells on an executor (``--executor local``:
a pool of ``--jobs`` worker processes; ``--executor dask``: a Dask cluster,
``--scheduler ADDRESS`` or a local one).  Simulated sequences are rendered
once into the frame cache (``--cache DIR``, ``$TRACKBENCH_CACHE``, or the
platform's cache folder; ``--no-cache`` renders in every cell) and read
back by every other cell and run.  Each finished cell is stored in
``DIR/results.sqlite``, and ``leaderboard.csv``, ``leaderboard.md`` and
``leaderboard.html`` are written into ``DIR``.  A progress bar goes to stderr on a
terminal; elsewhere (a CI log) a line every few seconds counts the cells
done, failed and left with the time remaining, and each failed cell gets a
line of its own.  One line sums the run up at the end.  To stdout goes a
summary that fits the terminal, one row per tracker and board, naming the
files with the full boards (``trackbench leaderboard`` prints those).

Exit status, as pytest's:

* 0: done, every cell ``ok``;
* 1: done, the board written, but some cell ended in ``error`` or
  ``timeout``, or a plugin could not be loaded (its trackers or commands
  are unavailable; ``--strict-plugins`` makes that an error instead);
* 2: nothing ran: a usage or data error (an unknown name, a bad parameter,
  an unreadable file, a broken plugin, a results folder in use, a
  ``--history`` that cannot be opened, lacks its driver or is not a
  history), reported as one line ``Error: ...`` without a traceback;
* 3: ``nightly`` found an accuracy regression (the run is kept in the
  history and the site written);
* 4: ``nightly --fail-on-speed`` found a speed regression that held on
  its repeat, and no accuracy regression (without the flag a speed
  regression is reported and the status is 0 or 1);
* 130: the user's Ctrl-C; finished cells are kept and published.
"""

from __future__ import annotations

from typing import Any

import click

from benchmark.cli.boards import leaderboard_command, tables_command
from benchmark.cli.cache import cache_group
from benchmark.cli.check import check_command
from benchmark.cli.discovery import CommandRegistry, load_commands
from benchmark.cli.history import EXIT_REGRESSION, EXIT_SPEED_REGRESSION, compare, nightly, report_command
from benchmark.cli.listing import list_datasets, list_trackers
from benchmark.cli.make_dataset import make_dataset
from benchmark.cli.new_tracker import new_tracker_command
from benchmark.cli.replay import replay_command
from benchmark.cli.run import run
from benchmark.cli.session import EXIT_FAILED, EXIT_INTERRUPTED, ReportedError, Session
from benchmark.cli.speed import speed_command
from benchmark.errors import TrackbenchError
from benchmark.text import one_line, printable

__all__ = ["EXIT_FAILED", "EXIT_INTERRUPTED", "EXIT_REGRESSION", "EXIT_SPEED_REGRESSION", "TrackbenchGroup", "main"]

BUILT_IN_COMMANDS = (
    list_trackers,
    list_datasets,
    run,
    leaderboard_command,
    tables_command,
    make_dataset,
    cache_group,
    nightly,
    compare,
    report_command,
    check_command,
    replay_command,
    new_tracker_command,
    speed_command,
)
"""The commands of this package; plugins add theirs through ``trackbench_register_commands``."""

_PLUGIN_COMMANDS = "trackbench.plugin_commands"
"""Where the context keeps the plugins' commands once loaded."""


class TrackbenchGroup(click.Group):
    """A command group that reports trackbench's own errors without a traceback.

    It also sets the exit status for the user's Ctrl-C, and for plugins that
    were left out while the command otherwise succeeded.  Beside its own
    commands it offers those plugins add (:mod:`benchmark.cli.discovery`),
    loaded only when they are needed: to list the commands, or to run one
    that is not built in.
    """

    def list_commands(self, ctx: click.Context) -> list[str]:
        return sorted({*super().list_commands(ctx), *self.plugin_commands(ctx).commands})

    def get_command(self, ctx: click.Context, cmd_name: str) -> click.Command | None:
        return super().get_command(ctx, cmd_name) or self.plugin_commands(ctx).commands.get(cmd_name)

    def plugin_commands(self, ctx: click.Context) -> CommandRegistry:
        """The commands of the plugins not disabled, loaded on first use; plugins left out are reported on stderr."""
        if _PLUGIN_COMMANDS not in ctx.meta:
            try:
                commands = load_commands(
                    self.commands, ctx.params.get("disable", ()), strict=ctx.params.get("strict_plugins", False)
                )
            except TrackbenchError as exc:
                raise ReportedError(printable(str(exc))) from exc
            for problem in commands.problems:
                click.echo(f"Warning: {one_line(problem)}", err=True)
            ctx.meta[_PLUGIN_COMMANDS] = commands
        return ctx.meta[_PLUGIN_COMMANDS]

    def invoke(self, ctx: click.Context) -> Any:
        try:
            result = super().invoke(ctx)
        except TrackbenchError as exc:
            raise ReportedError(printable(str(exc))) from exc
        except KeyboardInterrupt:
            click.echo("Interrupted.", err=True)
            ctx.exit(EXIT_INTERRUPTED)
        session = ctx.obj
        commands = ctx.meta.get(_PLUGIN_COMMANDS)
        if (isinstance(session, Session) and session.problems) or (commands is not None and commands.problems):
            ctx.exit(EXIT_FAILED)
        return result


@click.group(cls=TrackbenchGroup, commands=BUILT_IN_COMMANDS)
@click.option(
    "--disable",
    "disable",
    multiple=True,
    metavar="NAME",
    help="Block the plugin with this entry-point name (repeatable).",
)
@click.option(
    "--strict-plugins",
    is_flag=True,
    help="A plugin that fails to import is an error (exit 2), not a warning that leaves its trackers out.",
)
@click.version_option(package_name="subsea-trackbench", prog_name="trackbench")
@click.pass_context
def main(ctx: click.Context, disable: tuple[str, ...], strict_plugins: bool) -> None:
    """trackbench: a benchmark for subsea cable and pipeline trackers."""
    ctx.obj = Session(disable, strict_plugins)
