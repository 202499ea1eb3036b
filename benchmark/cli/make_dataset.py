"""``trackbench make-dataset``: a suite's sequences written to disk in their modality's form."""

from __future__ import annotations

import sys
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
    from benchmark.progress import Meter
    from benchmark.selection import SelectionError

    registry = session.registry
    if suite not in registry.suites:
        raise SelectionError(f"unknown suite {suite!r} (known: {', '.join(sorted(registry.suites)) or 'none'})")
    sequences = registry.suites[suite].sequences
    with Meter("sequences", len(sequences)) as meter:
        for sequence in sequences:
            meter.write(str(export_sequence(sequence, out, registry.modalities)), sys.stdout)
            meter.advance()
