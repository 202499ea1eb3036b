"""The camera modality's own commands: ``trackbench diagnose`` and ``trackbench pose-table``.

Added to the command line through the ``trackbench_register_commands``
hook, under the entry point ``modality-camera`` of the
``trackbench.commands`` group, exactly as a third-party plugin adds its
commands.  The module stays light, so that listing the commands costs
little: each command imports what it needs when it runs.
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

import click

from benchmark.cli.options import OUT_OPTION
from benchmark.hookspecs import hookimpl
from benchmark.modalities.camera.labeller.command import label_command

if TYPE_CHECKING:
    from benchmark.cli.discovery import CommandRegistry
    from benchmark.cli.session import Session


@click.command("diagnose")
@click.option("--tracker", required=True, metavar="NAME", help="The tracker whose observation model to test.")
@click.option("--suite", "suites", multiple=True, metavar="SUITE", help="Every sequence of a suite (repeatable).")
@click.option(
    "--dataset",
    "datasets",
    multiple=True,
    metavar="NAME|PATH",
    help="A registered sequence (suite/name) or a sequence file (repeatable).",
)
@OUT_OPTION
@click.pass_obj
def diagnose_command(
    session: Session, tracker: str, suites: tuple[str, ...], datasets: tuple[str, ...], out: Path
) -> None:
    """Print the likelihood ceiling of a tracker on each selected camera sequence.

    On every labelled frame, the states in a window around the true cable
    are scored with the tracker's own observation model; the ceiling is the
    share of frames whose best-scoring state is correct (Foresti's rule),
    the most a tracker reporting that model's best state can reach.  Beside
    it: the tracker's correct_pct in its latest run in OUT/results.sqlite
    with the same parameters, if any.  Also written to OUT/diagnose_NAME.md.
    """
    from contextlib import nullcontext

    from benchmark.files import make_folder, write_text_atomically
    from benchmark.modalities.camera.diagnostics import ceiling_markdown, ceiling_report
    from benchmark.selection import select_sequences, select_trackers
    from benchmark.store import DATABASE_NAME, ResultStore

    registry = session.registry
    (entry,) = select_trackers(registry, [tracker])
    sequences = select_sequences(registry, suites, datasets)
    database = out / DATABASE_NAME
    with ResultStore(database) if database.is_file() else nullcontext() as store:
        table, skipped = ceiling_report(entry, sequences, registry.modalities, store)
    for line in skipped:
        click.echo(line, err=True)
    text = ceiling_markdown(table, entry.name)
    click.echo(text)
    path = write_text_atomically(make_folder(out) / f"diagnose_{entry.name}.md", text, "diagnosis")
    click.echo(f"wrote {path}", err=True)


@click.command("pose-table")
@click.option("--tracker", required=True, metavar="NAME", help="A camera tracker that reports the camera pose.")
@click.option("--dataset", required=True, metavar="NAME|PATH", help="A camera sequence whose truth has the pose.")
@click.option("--first", type=click.IntRange(min=0), default=0, show_default=True, help="First frame shown.")
@click.option("--frames", type=click.IntRange(min=1), default=12, show_default=True, help="Number of frames shown.")
@click.option(
    "--init",
    type=click.Choice(["truth", "none"]),
    default="none",
    show_default=True,
    help="Start from the first frame's truth, or from the tracker's own prior (the paper's x_0).",
)
@OUT_OPTION
@click.pass_obj
def pose_table_command(
    session: Session, tracker: str, dataset: str, first: int, frames: int, init: str, out: Path
) -> None:
    """Print a pose tracker's measurement, state, error and covariance per frame, as Foresti's Tables III-IV.

    The tracker runs in this process from frame 0; frames FIRST to
    FIRST+FRAMES-1 are shown.  Also written to OUT/pose_NAME.md.
    """
    from benchmark.files import make_folder, write_text_atomically
    from benchmark.modalities.camera.pose_table import pose_table
    from benchmark.report.markdown import titled_table
    from benchmark.selection import select_sequences, select_trackers

    (entry,) = select_trackers(session.registry, [tracker])
    (sequence,) = select_sequences(session.registry, (), (dataset,))
    table = pose_table(entry.create(), sequence, first, frames, init == "truth")
    text = titled_table(table, f"{entry.name} on {sequence.info.name}, frames {first}-{first + len(table) - 1}")
    click.echo(text)
    path = write_text_atomically(make_folder(out) / f"pose_{entry.name}.md", text, "pose table")
    click.echo(f"wrote {path}", err=True)


@hookimpl
def trackbench_register_commands(registry: CommandRegistry) -> None:
    """Add ``diagnose``, ``pose-table`` and ``label``."""
    registry.add_command(diagnose_command)
    registry.add_command(pose_table_command)
    registry.add_command(label_command)
