"""``trackbench cache``: the frame cache's ``info`` and ``clear``."""

from __future__ import annotations

from pathlib import Path

import click

from benchmark.cli.options import cache_option


@click.group("cache")
def cache_group() -> None:
    """The frame cache: simulated sequences rendered once, read by every run."""


@cache_group.command("info")
@cache_option
def cache_info(cache: Path | None) -> None:
    """List the cached sequences, their sizes and the cache's folder."""
    from benchmark.frame_cache import FrameCache

    frames = FrameCache(cache)
    entries = frames.entries()
    for entry in entries:
        count = "?" if entry.frames is None else entry.frames
        size = f"{entry.size_bytes / 1e6:.1f} MB"
        click.echo(f"{entry.name}  {entry.modality}  {count} frames  {size}  {entry.path.name}")
    total = sum(entry.size_bytes for entry in entries)
    leftovers = frames.leftovers()
    extra = f", {len(leftovers)} leftover files" if leftovers else ""
    click.echo(f"{frames.folder}: {len(entries)} sequences, {total / 1e6:.1f} MB{extra}")


@cache_group.command("clear")
@cache_option
def cache_clear(cache: Path | None) -> None:
    """Remove every cached sequence; the next run renders them again."""
    from benchmark.frame_cache import FrameCache

    frames = FrameCache(cache)
    removed, freed = frames.clear()
    click.echo(f"{frames.folder}: removed {removed} sequences, {freed / 1e6:.1f} MB")
