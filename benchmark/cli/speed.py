"""``trackbench speed``: each tracker against the bound its plugin declares, in alternating rounds."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

import click

from benchmark.cli.options import cache_option

if TYPE_CHECKING:
    from benchmark.cli.session import Session


class TableFile(click.Path):
    """A file the table is written to: ``.csv`` or ``.md``."""

    def convert(self, value: object, param: click.Parameter | None, ctx: click.Context | None) -> Path:
        from benchmark.speed.table import WRITERS

        path = Path(super().convert(value, param, ctx))
        if path.suffix not in WRITERS:
            self.fail(f"{path}: the table is written as {' or '.join(WRITERS)}, not {path.suffix or 'no suffix'}")
        return path


@click.command("speed")
@click.option(
    "--tracker",
    "trackers",
    multiple=True,
    metavar="NAME",
    help="A tracker or component with a declared bound (repeatable) [default: all].",
)
@click.option("--rounds", type=click.IntRange(min=1), default=7, show_default=True, help="Timed rounds of each.")
@click.option(
    "--frames", type=click.IntRange(min=1), default=40, show_default=True, help="Frames of the dataset timed."
)
@click.option(
    "--out",
    "outs",
    multiple=True,
    type=TableFile(dir_okay=False),
    help="Also write the table to FILE.csv or FILE.md (repeatable).",
)
@cache_option
@click.pass_obj
def speed_command(
    session: Session,
    trackers: tuple[str, ...],
    rounds: int,
    frames: int,
    outs: tuple[Path, ...],
    cache: Path | None,
) -> None:
    """Time each tracker against its bound or peer on the same frames and print the ratio table.

    Bounds come from the plugins of the entry-point group
    ``trackbench.speed`` (:mod:`benchmark.speed.bounds`).  Frames are read
    once; then, in each round, the tracker and each bound are reset with the
    same seed and stepped over the frames, one after the other, timed by
    this thread's CPU time on one native thread.  The table shows medians
    over rounds and the median of the per-round ratios ours / bound, with
    the goal each plugin declares and whether it is met.
    """
    from benchmark.progress import Meter
    from benchmark.speed.bounds import load_bounds
    from benchmark.speed.measure import time_subject
    from benchmark.speed.subjects import chosen_subjects, prepare_subject
    from benchmark.speed.table import WRITERS, terminal_table
    from benchmark.text import one_line
    from benchmark.workers import limit_native_threads

    bounds = load_bounds(session.disable, strict=session.strict_plugins)
    for problem in bounds.problems:
        click.echo(f"Warning: {one_line(problem)}", err=True)
    names = chosen_subjects(bounds, trackers)
    registry = session.registry
    limit_native_threads()
    rows = []
    planned = [(1 + len(bounds.of(name))) * (rounds + 1) for name in names]  # each workload: warm-up + rounds
    with Meter("passes", sum(planned)) as meter:
        for index, name in enumerate(names):
            meter.note = f"{name} ({index + 1}/{len(names)})"
            subject = prepare_subject(registry, bounds, name, frames, cache)
            offset = sum(planned[:index])
            rows += time_subject(subject, rounds, lambda done, total, offset=offset: meter.report(offset + done))
    click.echo(terminal_table(rows))
    for path in outs:
        WRITERS[path.suffix](rows, path)
        click.echo(f"wrote {path}", err=True)
