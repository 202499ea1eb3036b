"""``trackbench replay``: one cell played frame by frame into a self-contained HTML page."""

from __future__ import annotations

import dataclasses
import re
from pathlib import Path
from typing import TYPE_CHECKING

import click

from benchmark.cli.options import cache_option, init_option

if TYPE_CHECKING:
    from benchmark.cli.session import Session
    from benchmark.replay.record import FrameRange


class FrameRangeParam(click.ParamType):
    """``A:B``: frames A to B - 1 (``A:`` to the end, ``:B`` from the start)."""

    name = "A:B"

    def convert(self, value: object, param: click.Parameter | None, ctx: click.Context | None) -> FrameRange:
        from benchmark.replay.record import FrameRange, FrameRangeError

        if not isinstance(value, str):
            return value  # type: ignore[return-value]  # already converted (a default)
        try:
            return FrameRange.parse(value)
        except FrameRangeError as exc:
            self.fail(str(exc), param, ctx)


def default_page(tracker: str, dataset: str, seed: int) -> Path:
    """``reports/replay/TRACKER_DATASET_sSEED.html``, the dataset's name made a file name."""
    stem = re.sub(r"[^A-Za-z0-9_.-]+", "-", f"{tracker}_{dataset}_s{seed}").strip("-")
    return Path("reports") / "replay" / f"{stem}.html"


@click.command("replay")
@click.option("--tracker", required=True, metavar="NAME", help="The tracker to replay.")
@click.option(
    "--dataset", required=True, metavar="NAME|PATH", help="A registered sequence (suite/name) or a sequence file."
)
@click.option("--seed", type=click.IntRange(min=0), default=0, show_default=True, help="The cell's seed.")
@click.option(
    "--frames",
    "frame_range",
    type=FrameRangeParam(),
    default=None,
    help="Frames A to B-1 only (the tracker still starts at frame 0).",
)
@init_option(help="Start from the first frame's truth, or from nothing.")
@click.option(
    "--out",
    type=click.Path(dir_okay=False, path_type=Path),
    default=None,
    help="The page to write [default: reports/replay/TRACKER_DATASET_sSEED.html].",
)
@cache_option
@click.pass_obj
def replay_command(
    session: Session,
    tracker: str,
    dataset: str,
    seed: int,
    frame_range: FrameRange | None,
    init: str,
    out: Path | None,
    cache: Path | None,
) -> None:
    """Play one cell as the runner does and write it as a page that replays it from file://.

    The page shows each frame with the truth (green) and the estimate (red)
    drawn on it, the outcome strip, the tracker's belief where it exposes
    one (particles per state dimension, or a Gaussian's mean and 2-sigma
    band), the numbers and the step time: the Cable Tracking GUI of
    seeds/000, section 4.7.  Camera frames show the image and the cable's
    borders; sonar pings the swath profile, the pipe and the particles
    across track; stereo frames a map with the target, the measurement and
    the estimate's 2-sigma ellipse, under the image pair where there is one.
    """
    from benchmark.files import make_folder
    from benchmark.frame_cache import FrameCache
    from benchmark.progress import Meter
    from benchmark.replay.page import write_replay
    from benchmark.replay.record import FrameRange, record_cell
    from benchmark.replay.views import view_of
    from benchmark.selection import make_cells, plan_training, select_sequences, select_trackers

    registry = session.registry
    entries = select_trackers(registry, [tracker])
    view = view_of(entries[0].modality)
    sequences = select_sequences(registry, (), (dataset,))
    cells = make_cells(entries, sequences, [seed], init, registry.modalities)  # type: ignore[arg-type]
    (cell,) = plan_training(registry, cells)
    cell = dataclasses.replace(cell, sequence=FrameCache(cache).wrap(cell.sequence))
    with Meter("frames") as meter:
        recording = record_cell(cell, frame_range or FrameRange(), report=meter, view=view)
    if recording.ended:
        click.echo(f"Warning: the tracker stopped the recording: {recording.ended}", err=True)
    path = out or default_page(entries[0].name, cell.dataset, seed)
    make_folder(path.parent)
    write_replay(recording, path, view)
    size = path.stat().st_size
    click.echo(
        f"wrote {path}: {len(recording.frames)} frames, {size / 1e6:.2f} MB; "
        f"steps {recording.step_s:.2f} s CPU, capture {recording.capture_s:.2f} s",
        err=True,
    )
