"""``trackbench make-dataset``: a suite's sequences written to disk in their modality's form."""

from __future__ import annotations

from pathlib import Path

import click

from benchmark.cli.session import Session


@click.command("make-dataset")
@click.argument("suite")
@click.option(
    "--out", type=click.Path(file_okay=False, path_type=Path), required=True, help="Folder to write the sequences to."
)
@click.pass_obj
def make_dataset(session: Session, suite: str, out: Path) -> None:
    """Write every sequence of SUITE to disk in its modality's form.

    Camera sequences become PNG frames plus an image sequence file, sonar
    sequences a swath file, stereo image pairs left/ and right/ folders with
    their sidecar.
    """
    from benchmark.io import export_sequence
    from benchmark.selection import SelectionError

    registry = session.registry
    if suite not in registry.suites:
        raise SelectionError(f"unknown suite {suite!r} (known: {', '.join(sorted(registry.suites)) or 'none'})")
    for sequence in registry.suites[suite].sequences:
        click.echo(export_sequence(sequence, out, registry.modalities))
