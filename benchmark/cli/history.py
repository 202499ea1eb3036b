"""``trackbench nightly``, ``compare`` and ``report``: runs kept in the history database, and its site."""

from __future__ import annotations

import functools
import sys
from pathlib import Path
from typing import Any

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

EXIT_REGRESSION = 3
"""``nightly`` found a regression (after storing the run and writing the site)."""


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
@click.pass_context
def nightly(
    ctx: click.Context,
    out: Path,
    history: str,
    site: Path,
    min_effects: tuple[str, ...],
    window: int,
    **options: Any,
) -> None:
    """Run the benchmark, add the run to the history, report its changes and rewrite the site.

    Takes every option of run.  Exits with 3 when a regression was found,
    else with 1 when a cell failed, as run does.
    """
    from benchmark.history.database import shown_location
    from benchmark.history.nightly import CHANGES_NAME, describe_changes, run_nightly

    limits = thresholds(min_effects, window)
    run = functools.partial(run_benchmark, ctx, out, **options)
    session: Session = ctx.obj
    registry = session.registry
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
    )
    title = f"Changes of nightly run {kept.run_id}"
    click.echo(describe_changes(kept.changes, title, registry.metrics, out / CHANGES_NAME))
    click.echo(f"history {shown_location(history)}: run {kept.run_id}; site {kept.index}", err=True)
    if kept.regressed:
        ctx.exit(EXIT_REGRESSION)
    if not kept.summary.clean:
        ctx.exit(EXIT_FAILED)


@click.command("compare")
@click.argument("run_a", type=int)
@click.argument("run_b", type=int)
@existing_history_option
@threshold_options
@click.pass_obj
def compare(
    session: Session, run_a: int, run_b: int, history: str, min_effects: tuple[str, ...], window: int
) -> None:
    """Print what changed from nightly run RUN_A to RUN_B of the history.

    Speeds are compared only when both ran on the same machine.
    """
    from benchmark.errors import DataError
    from benchmark.history.database import History
    from benchmark.history.nightly import describe_changes
    from benchmark.history.regressions import find_changes

    limits = thresholds(min_effects, window)
    with History(history, must_exist=True) as database:
        cells = database.cells([run_a, run_b])
    missing = sorted({run_a, run_b} - set(cells["run_id"]))
    if missing:
        raise DataError(f"history database {database.location}: no run {', '.join(map(str, missing))}")
    changes = find_changes(cells, run_b, limits, against=[run_a], metrics=session.registry.metrics)
    click.echo(describe_changes(changes, f"Run {run_a} -> {run_b}", session.registry.metrics))


@click.command("report")
@existing_history_option
@site_option
@threshold_options
@click.pass_obj
def report_command(session: Session, history: str, site: Path, min_effects: tuple[str, ...], window: int) -> None:
    """Rebuild the static HTML report from the history database, without running anything."""
    from benchmark.errors import DataError
    from benchmark.history.database import History
    from benchmark.site import build_site

    with History(history, must_exist=True) as database:
        if database.runs().empty:
            raise DataError(f"history database {database.location}: no runs yet (run 'trackbench nightly' first)")
        index = build_site(
            database,
            site,
            session.registry.modalities,
            thresholds=thresholds(min_effects, window),
            metrics=session.registry.metrics,
        )
    click.echo(f"wrote {index}")
