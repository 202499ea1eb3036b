"""``trackbench new-tracker``: the skeleton of a tracker plugin package."""

from __future__ import annotations

from pathlib import Path

import click


@click.command("new-tracker")
@click.argument("name")
@click.option(
    "--modality", default="camera", show_default=True, help="The registered modality the tracker reads."
)
@click.option(
    "--out",
    type=click.Path(file_okay=False, path_type=Path),
    default=Path("."),
    show_default=True,
    help="Folder in which the plugin folder NAME is made.",
)
@click.pass_context
def new_tracker_command(ctx: click.Context, name: str, modality: str, out: Path) -> None:
    """Write a minimal tracker plugin package into OUT/NAME: pyproject.toml, trackbench_NAME and a test.

    Then `pip install -e OUT/NAME`, `trackbench check NAME` and `pytest OUT/NAME/tests`.
    """
    from benchmark.scaffold import ScaffoldError, new_tracker

    modalities = ctx.obj.registry.modalities
    if modality not in modalities:
        raise ScaffoldError(f"unknown modality {modality!r} (registered: {', '.join(sorted(modalities)) or 'none'})")
    folder = new_tracker(name, modalities[modality], out)
    for path in sorted(p for p in folder.rglob("*") if p.is_file()):
        click.echo(path)
