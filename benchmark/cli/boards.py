"""``trackbench leaderboard`` and ``trackbench tables``: the boards of a results database already written."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

import click

from benchmark.cli.options import OUT_OPTION
from benchmark.cli.session import Session

if TYPE_CHECKING:
    from benchmark.harness import Publication
    from benchmark.store import ResultStore


def show_publication(publication: Publication, *, full: bool = True) -> None:
    """Print a run's boards to stdout, in full or summed up to fit the terminal, and name the files written.

    ``full=False`` prints one row per tracker and board as wide as the
    terminal, and the files holding the full boards
    (:func:`benchmark.report.summary.summary_text`); ``full=True`` prints
    every row and column, and the files written to stderr.
    """
    if not full:
        from benchmark.report.summary import summary_text

        click.echo(summary_text(publication.boards, publication.files, publication.problems, publication.metrics))
        return
    from benchmark.report import to_text

    click.echo(to_text(publication.boards, problems=publication.problems, metrics=publication.metrics))
    for path in publication.files:
        click.echo(f"wrote {path}", err=True)


def results_store(out: Path) -> ResultStore:
    """The results database in ``out``, which must hold at least one run."""
    from benchmark.errors import DataError
    from benchmark.store import DATABASE_NAME, ResultStore

    database = out / DATABASE_NAME
    if not database.is_file():
        raise DataError(f"{database}: no results database (run 'trackbench run --out {out}' first)")
    store = ResultStore(database)
    if store.latest_run() is None:
        store.close()
        raise DataError(f"{database}: no finished cells yet")
    return store


@click.command("leaderboard")
@OUT_OPTION
@click.option("--all-runs", is_flag=True, help="Take the latest cell of every run, not only the latest run.")
@click.pass_obj
def leaderboard_command(session: Session, out: Path, all_runs: bool) -> None:
    """Print and export the leaderboard of an existing results database.

    The leaderboard of a run holds the cells it ran and those it resumed;
    for each tracker, dataset, seed and initialisation the latest cell.
    """
    from benchmark.harness import publish

    with results_store(out) as store:
        registry = session.registry
        show_publication(publish(store, registry.modalities, out, all_runs=all_runs, metrics=registry.metrics))


@click.command("tables")
@click.argument("suite")
@OUT_OPTION
@click.option("--metric", "metrics", multiple=True, help="Board column to show (repeatable; default: every RMSE).")
@click.pass_obj
def tables_command(session: Session, suite: str, out: Path, metrics: tuple[str, ...]) -> None:
    """Print SUITE's results of the latest run as one table per case.

    For suites whose sequences are named SUITE/CASE-CONDITION, such as
    stereo/case1-slow: rows are metric and tracker, columns the conditions,
    as in Tables 6-8 of Sinisterra et al.  Also written to
    OUT/tables_SUITE.md.
    """
    from benchmark.files import write_text_atomically
    from benchmark.leaderboard import load_leaderboards
    from benchmark.report.grid import grid_markdown, grid_tables
    from benchmark.selection import SelectionError

    suites = session.registry.suites
    if suite not in suites:
        raise SelectionError(f"unknown suite {suite!r} (known: {', '.join(sorted(suites)) or 'none'})")
    order = [sequence.identity.name for sequence in suites[suite].sequences]
    with results_store(out) as store:
        boards = load_leaderboards(
            store, session.registry.modalities, store.latest_run(), metrics=session.registry.metrics
        )
    rows = [board[board["dataset"].isin(order)] for board in boards.values()]
    board = next((part for part in rows if not part.empty), None)
    if board is None:
        raise SelectionError(f"the latest run in {out} has no results for suite {suite!r}")
    shown = list(metrics) or [column for column in board.columns if column.startswith("rmse_")]
    unknown = [metric for metric in shown if metric not in board.columns]
    if unknown:
        raise SelectionError(f"no column {', '.join(unknown)} (known: {', '.join(board.columns)})")
    text = grid_markdown(grid_tables(board, shown, order), f"{suite}: results per case")
    click.echo(text)
    path = write_text_atomically(out / f"tables_{suite}.md", text, "tables")
    click.echo(f"wrote {path}", err=True)
