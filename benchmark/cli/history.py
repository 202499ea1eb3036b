"""``trackbench nightly``, ``compare`` and ``report``: runs kept in the history database, and its site."""

from __future__ import annotations

import re
import sys
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING, Any

import click

from benchmark.cli.options import (
    existing_history_option,
    history_option,
    run_options,
    site_option,
    threshold_options,
    thresholds,
)
from benchmark.cli.run import run_benchmark
from benchmark.cli.session import EXIT_FAILED, Session

if TYPE_CHECKING:
    from benchmark.closedloop.route import Route
    from benchmark.harness import RunSummary
    from benchmark.registry import Registry
    from benchmark.runner import Cell

EXIT_REGRESSION = 3
"""``nightly`` found an accuracy regression (after storing the run and writing the site)."""
EXIT_SPEED_REGRESSION = 4
"""``nightly --fail-on-speed`` found a speed regression, held on a repeat, and no accuracy regression."""

def registry_routes(registry: Registry) -> dict[str, Route]:
    """The routes of the registry's closed-loop datasets by dataset key, for the site's top views."""
    from benchmark.closedloop.topview import routes_by_dataset

    return routes_by_dataset(sequence for suite in registry.suites.values() for sequence in suite.sequences)


BYTE_UNITS = {"": 1, "b": 1, "kb": 10**3, "mb": 10**6, "gb": 10**9, "kib": 2**10, "mib": 2**20, "gib": 2**30}
"""The units a size may be given in (case ignored)."""


class ByteSize(click.ParamType):
    """A size in bytes: a number and an optional unit, ``50MB``, ``1.5 GB``, ``800kB``, ``64MiB``, ``0``."""

    name = "SIZE"

    def convert(self, value: object, param: click.Parameter | None, ctx: click.Context | None) -> int:
        if isinstance(value, int):
            return value
        found = re.fullmatch(r"\s*(\d+(?:\.\d*)?)\s*([A-Za-z]*)\s*", str(value))
        unit = found[2].lower() if found else ""
        if found is None or unit not in BYTE_UNITS:
            self.fail(f"{value!r} is not a size such as 50MB, 800kB or 0 (units: kB, MB, GB, KiB, MiB, GiB)",
                      param, ctx)
        return int(float(found[1]) * BYTE_UNITS[unit])


@click.command("nightly")
@run_options
@click.option(
    "--out",
    type=click.Path(file_okay=False, path_type=Path),
    default=Path("reports") / "nightly",
    show_default=True,
    help="Folder for the run's results.sqlite and leaderboards.",
)
@history_option
@site_option
@threshold_options
@click.option(
    "--fail-on-speed",
    is_flag=True,
    help="Exit with 4 when a speed regression held on its repeat (default: report it and exit 0).",
)
@click.option(
    "--replay-budget",
    "replay_budget",
    type=ByteSize(),
    default="50MB",
    show_default=True,
    help="Size of the replay pages of the night's failed cells, at most (0: none).",
)
@click.pass_context
def nightly(
    ctx: click.Context,
    out: Path,
    history: str,
    site: Path,
    min_effects: tuple[str, ...],
    window: int,
    min_step_s: float,
    fail_on_speed: bool,
    replay_budget: int,
    **options: Any,
) -> None:
    """Run the benchmark, add the run to the history, report its changes and rewrite the site.

    Takes every option of run; like run, it leaves out the suites that
    are not scored unless named, so the closed-loop routes run when named
    (--suite camera --suite routes): their frames depend on the tracker,
    so every cell renders its own.  The site then shows their closed-loop
    board and each run's path over its route.  Speed is the CPU time of the trackers'
    steps (cpu_fps; wall_fps is shown, not judged); a speed change counts
    when it exceeds the series' noise over the earlier runs on this machine
    and holds when its cells run once more into OUT/repeat.

    Exit status: 3 when an accuracy metric (a rate, an RMSE, robustness)
    regressed; else 4 when a speed regressed and --fail-on-speed is given
    (without it a speed regression is reported only); else 1 when a cell
    failed, as run does; else 0.

    Then the night's failed cells are replayed frame by frame into pages of
    the site, linked from their cell pages, until --replay-budget is spent:
    first the cells that did not end ok, then those of an accuracy
    regression, then the cells with the most false and missed frames.  A
    replay that cannot be made is a line here and a reason on its cell's
    page, and changes no exit status.
    """
    from benchmark.history.database import shown_location
    from benchmark.history.machine import describe_load
    from benchmark.frame_cache import FrameCache
    from benchmark.history.nightly import CHANGES_NAME, REPEAT_FOLDER, describe_changes, run_nightly
    from benchmark.history.replays import ReplayPlan
    from benchmark.progress import Meter
    from benchmark.selection import Selection, select_cells

    limits = thresholds(min_effects, window, min_step_s)

    def run(folder: Path, only: Callable[[Cell], bool] | None) -> RunSummary:
        if only is None:
            return run_benchmark(ctx, folder, **options)
        return run_benchmark(ctx, folder, **{**options, "resume": False}, only=only, show_board=False)

    session: Session = ctx.obj
    registry = session.registry
    selection = Selection(options["trackers"], options["suites"], options["datasets"], options["params"],
                          options["seeds"], options["init"], options["train"], options["real_time"],
                          options["step_times"])
    replays = ReplayPlan(replay_budget, lambda: select_cells(registry, selection),
                         None if options["no_cache"] else FrameCache(options["cache"]))
    with Meter("site pages") as pages:
        kept = run_nightly(
            run,
            history,
            out,
            site,
            registry.modalities,
            limits,
            argv=sys.argv,
            seeds=options["seeds"],
            metrics=registry.metrics,
            report=pages,
            replays=replays,
            log=lambda line: click.echo(line, err=True),
            routes=registry_routes(registry),
        )
    if kept.repeat is not None:
        repeated = kept.repeat.statuses.total()
        click.echo(f"speed changes held against a repeat of their {repeated} cells in {out / REPEAT_FOLDER}", err=True)
    title = f"Changes of nightly run {kept.run_id}"
    click.echo(describe_changes(kept.changes, title, registry.metrics, out / CHANGES_NAME))
    if kept.replays is not None and replay_budget:
        click.echo(kept.replays.describe(), err=True)
    click.echo(f"machine load during the run: {describe_load(kept.load)}", err=True)
    click.echo(f"history {shown_location(history)}: run {kept.run_id}; site {kept.index}", err=True)
    if kept.accuracy_regressed:
        ctx.exit(EXIT_REGRESSION)
    if kept.speed_regressed and fail_on_speed:
        ctx.exit(EXIT_SPEED_REGRESSION)
    if not kept.summary.clean:
        ctx.exit(EXIT_FAILED)


@click.command("compare")
@click.argument("run_a", type=int)
@click.argument("run_b", type=int)
@existing_history_option
@threshold_options
@click.option(
    "--html",
    "html",
    type=click.Path(dir_okay=False, path_type=Path),
    help="Also write the comparison as one self-contained HTML page to this file.",
)
@click.pass_obj
def compare(
    session: Session,
    run_a: int,
    run_b: int,
    history: str,
    min_effects: tuple[str, ...],
    window: int,
    min_step_s: float,
    html: Path | None,
) -> None:
    """Print what changed from nightly run RUN_A to RUN_B of the history.

    Speeds are compared only when both ran on the same machine; with one
    earlier run there is no noise estimate, so a speed change beyond the
    minimum effect is listed as unjudged.  With --html, the page shows the
    changes grouped by cause and every metric of both runs side by side.
    """
    from benchmark.errors import DataError
    from benchmark.history.database import History
    from benchmark.history.nightly import describe_changes
    from benchmark.history.regressions import find_changes

    limits = thresholds(min_effects, window, min_step_s)
    with History(history, must_exist=True) as database:
        cells = database.cells([run_a, run_b])
        missing = sorted({run_a, run_b} - set(cells["run_id"]))
        if missing:
            raise DataError(f"history database {database.location}: no run {', '.join(map(str, missing))}")
        changes = find_changes(cells, run_b, limits, against=[run_a], metrics=session.registry.metrics)
        click.echo(describe_changes(changes, f"Run {run_a} -> {run_b}", session.registry.metrics))
        if html is not None:
            from benchmark.site.compare import write_comparison

            registry = session.registry
            write_comparison(html, database, run_a, run_b, changes, registry.modalities, limits, registry.metrics)
            click.echo(f"wrote {html}", err=True)


@click.command("report")
@existing_history_option
@site_option
@threshold_options
@click.pass_obj
def report_command(
    session: Session, history: str, site: Path, min_effects: tuple[str, ...], window: int, min_step_s: float
) -> None:
    """Rebuild the static HTML report from the history database, without running anything."""
    from benchmark.errors import DataError
    from benchmark.history.database import History
    from benchmark.progress import Meter
    from benchmark.site import build_site

    with History(history, must_exist=True) as database:
        if database.runs().empty:
            raise DataError(f"history database {database.location}: no runs yet (run 'trackbench nightly' first)")
        with Meter("site pages") as pages:
            index = build_site(
                database,
                site,
                session.registry.modalities,
                thresholds=thresholds(min_effects, window, min_step_s),
                metrics=session.registry.metrics,
                report=pages,
                routes=registry_routes(session.registry),
            )
    click.echo(f"wrote {index}")
