"""``trackbench list`` and ``trackbench datasets``: what the plugins registered."""

from __future__ import annotations

import dataclasses

import click

from benchmark.cli.session import Session
from benchmark.text import one_line


@click.command("list")
@click.pass_obj
def list_trackers(session: Session) -> None:
    """List the trackers with their origin and parameters."""
    trackers = session.registry.trackers
    if not trackers:
        click.echo("No trackers registered.")
    for problem in session.problems:
        click.echo(f"unavailable: {one_line(problem)}")
    for entry in trackers.values():
        click.echo(
            f"{entry.name} {entry.version}  modality {entry.modality}  "
            f"from {entry.origin.distribution} (plugin {entry.origin.plugin})"
        )
        values = dataclasses.asdict(entry.params)
        if not values:
            click.echo("    (no parameters)")
        for key, value in values.items():
            click.echo(f"    {key} = {value!r}")


@click.command("datasets")
@click.pass_obj
def list_datasets(session: Session) -> None:
    """List the suites and their sequences, with the conditions each drawn sequence was drawn under."""
    from benchmark.scenes.draws import condition_label

    suites = session.registry.suites
    if not suites:
        click.echo("No suites registered.")
    for suite in suites.values():
        roles = ([] if suite.scored else ["training split, not scored unless named"]) + (
            [f"trains on {suite.training}"] if suite.training else []
        )
        role = f"  [{'; '.join(roles)}]" if roles else ""
        click.echo(f"{suite.name}  from {suite.origin.distribution} (plugin {suite.origin.plugin}){role}")
        for sequence in suite.sequences:
            info = sequence.info
            frames = "?" if info.n_frames is None else str(info.n_frames)
            description = str(info.extra.get("description", "")).strip()
            drawn = info.extra.get("conditions") or {}
            if drawn:
                described = ", ".join(f"{name} {condition_label(value)}" for name, value in drawn.items())
                description = f"{description} Drawn: {described}.".strip()
            line = f"    {info.name}  {info.modality}  {frames} frames"
            click.echo(f"{line}  {description}" if description else line)
