"""``trackbench run``: run the selected cells, store them and publish the leaderboard."""

from __future__ import annotations

import sys
from pathlib import Path
from typing import TYPE_CHECKING, Any

import click

from benchmark.cli.boards import show_publication
from benchmark.cli.options import DEFAULT_OUT, run_options
from benchmark.cli.session import EXIT_FAILED, Session

if TYPE_CHECKING:
    from collections.abc import Callable

    from benchmark.harness import RunSummary
    from benchmark.runner import Cell


@click.command("run")
@run_options
@click.option(
    "--out",
    type=click.Path(file_okay=False, path_type=Path),
    default=DEFAULT_OUT,
    show_default=True,
    help="Folder for results.sqlite and the leaderboards.",
)
@click.pass_context
def run(ctx: click.Context, out: Path, **options: Any) -> None:
    """Run trackers on datasets, store the cells and publish the leaderboard.

    Exits with 1 after publishing if a cell ended in error or timeout.
    """
    summary = run_benchmark(ctx, out, **options)
    if not summary.clean:
        ctx.exit(EXIT_FAILED)


def run_benchmark(
    ctx: click.Context,
    out: Path,
    *,
    suites: tuple[str, ...],
    trackers: tuple[str, ...],
    datasets: tuple[str, ...],
    seeds: int,
    jobs: int | None,
    in_process: bool,
    init: str,
    real_time: bool,
    step_times: tuple[str, ...],
    resume: bool,
    timeout: float,
    params: tuple[str, ...],
    train: tuple[str, ...],
    executor: str,
    scheduler: str | None,
    cache: Path | None,
    no_cache: bool,
    verbose: bool,
    only: Callable[[Cell], bool] | None = None,
    show_board: bool = True,
) -> RunSummary:
    """Run the cells the options of :func:`~benchmark.cli.options.run_options` select into ``out``, show the board and say how it went.

    ``only``, when given, keeps the selected cells it returns true for (a
    nightly's repeat of some series); ``show_board=False`` leaves the board
    in its files only.  Exits with 130 on the user's Ctrl-C, after
    publishing the cells finished.
    """
    from benchmark.executors import ExecutorOptions, open_executor
    from benchmark.frame_cache import FrameCache
    from benchmark.harness import run_benchmark
    from benchmark.progress import TerminalProgress
    from benchmark.selection import Selection, select_cells

    session: Session = ctx.obj
    registry = session.registry
    selection = Selection(trackers, suites, datasets, params, seeds, init, train, real_time, step_times)
    cells = select_cells(registry, selection)
    if only is not None:
        cells = [cell for cell in cells if only(cell)]
    options = {key: list(value) if isinstance(value, tuple) else value for key, value in ctx.params.items()}
    progress = TerminalProgress(verbose=verbose)
    runner = open_executor(executor, ExecutorOptions(jobs, in_process, scheduler))
    try:
        summary = run_benchmark(
            cells,
            registry.modalities,
            out,
            executor=runner,
            frame_cache=None if no_cache else FrameCache(cache),
            timeout_s=timeout,
            resume=resume,
            argv=sys.argv,
            options={**options, "out": str(out), "disable": list(session.disable)},
            problems=registry.problems,
            log=progress.write,
            progress=progress,
            metrics=registry.metrics,
        )
    finally:
        runner.close()
    if show_board:
        show_publication(summary.publication, full=False)
    click.echo(summary.describe(), err=True)
    if summary.interrupted:
        ctx.exit(128 + summary.interrupted)  # 130 for Ctrl-C, 143 for SIGTERM
    failed = summary.statuses.total() - summary.statuses["ok"]
    if failed:
        click.echo(f"{failed} of {summary.statuses.total()} cells did not end ok.", err=True)
    return summary
