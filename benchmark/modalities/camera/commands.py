"""The camera modality's own commands: ``diagnose``, ``pose-table``, ``import`` (``labels``, ``rosbag``) and ``label``.

Added to the command line through the ``trackbench_register_commands``
hook, under the entry point ``modality-camera`` of the
``trackbench.commands`` group, exactly as a third-party plugin adds its
commands.  The module stays light, so that listing the commands costs
little: each command imports what it needs when it runs.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING

import click

from benchmark.cli.options import OUT_OPTION, init_option
from benchmark.hookspecs import hookimpl
from benchmark.modalities.camera.labeller.command import label_command

if TYPE_CHECKING:
    from benchmark.cli.discovery import CommandRegistry
    from benchmark.cli.session import Session
    from benchmark.modalities.camera.io.sidecar import CameraTable


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
    from benchmark.progress import Meter
    from benchmark.selection import select_sequences, select_trackers
    from benchmark.store import DATABASE_NAME, ResultStore

    registry = session.registry
    (entry,) = select_trackers(registry, [tracker])
    sequences = select_sequences(registry, suites, datasets)
    database = out / DATABASE_NAME
    with ResultStore(database) if database.is_file() else nullcontext() as store, Meter("sequences") as meter:
        table, skipped = ceiling_report(entry, sequences, registry.modalities, store, report=meter)
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
@init_option("none", "Start from the first frame's truth, or from the tracker's own prior (the paper's x_0).")
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
    from benchmark.progress import Meter
    from benchmark.report.markdown import titled_table
    from benchmark.selection import select_sequences, select_trackers

    (entry,) = select_trackers(session.registry, [tracker])
    (sequence,) = select_sequences(session.registry, (), (dataset,))
    with Meter("frames") as meter:
        table = pose_table(entry.create(), sequence, first, frames, init == "truth", report=meter)
    text = titled_table(table, f"{entry.name} on {sequence.info.name}, frames {first}-{first + len(table) - 1}")
    click.echo(text)
    path = write_text_atomically(make_folder(out) / f"pose_{entry.name}.md", text, "pose table")
    click.echo(f"wrote {path}", err=True)


def _calibration_options(command: Callable[..., None]) -> Callable[..., None]:
    """The options of the sidecar's ``[camera]`` table."""
    options = [
        click.option("--focal-px", type=float, help="f / pixel pitch in px (seeds/004 eq. 3), for the sidecar."),
        click.option("--pipe-diameter-m", type=float, help="Diameter of the pipe or cable in m, for the sidecar."),
        click.option("--tilt-deg", type=float, help="Mounting tilt in deg (seeds/004 Fig. 2a), for the sidecar."),
    ]
    for option in reversed(options):
        command = option(command)
    return command


def _sidecar_camera(
    focal_px: float | None, pipe_diameter_m: float | None, tilt_deg: float | None
) -> CameraTable | None:
    """The ``[camera]`` table of the options, None without them; all three or none must be given."""
    from benchmark.modalities.camera.io.sidecar import CameraTable
    from benchmark.scenes.spec import validate_table

    given = {"focal_px": focal_px, "pipe_diameter_m": pipe_diameter_m, "tilt_deg": tilt_deg}
    if all(value is None for value in given.values()):
        return None
    missing = [f"--{name.replace('_', '-')}" for name, value in given.items() if value is None]
    if missing:
        raise click.UsageError(f"the camera calibration needs {', '.join(missing)} too")
    return validate_table(CameraTable, given, "camera calibration options")


@click.group("import")
def import_group() -> None:
    """Bring outside camera data in as image sequence files: labels from other tools, ROS bags."""


@import_group.command("labels")
@click.argument("labels", type=click.Path(path_type=Path))
@click.option(
    "--images",
    required=True,
    type=click.Path(path_type=Path),
    help="The folder the labels name their images in.",
)
@click.option("--out", required=True, type=click.Path(path_type=Path), help="The image sequence file to write.")
@click.option(
    "--frame-interval-s",
    type=click.FloatRange(min=0, min_open=True),
    help="Time between frames in s, for the sidecar.",
)
@_calibration_options
def import_labels_command(
    labels: Path,
    images: Path,
    out: Path,
    frame_interval_s: float | None,
    focal_px: float | None,
    pipe_diameter_m: float | None,
    tilt_deg: float | None,
) -> None:
    """Write an image sequence file from LABELS: a CSV file or a CVAT 1.1 XML export.

    CSV: a header, then one row per frame, either ``image,d,alpha,w,beta``
    (the cable state, px, rad, px, rad) or
    ``image,x1a,y1a,x2a,y2a,x1b,y1b,x2b,y2b`` (each border's two end points
    in pixels).  CVAT: per ``<image>``, two ``<polyline>`` borders, or none
    where no cable is seen.  With the calibration options or
    ``--frame-interval-s`` the sidecar OUT with suffix ``.toml`` is written too.
    """
    from benchmark.modalities.camera.importers.labels import import_labels
    from benchmark.modalities.camera.io.sidecar import write_sidecar

    camera = _sidecar_camera(focal_px, pipe_diameter_m, tilt_deg)
    path = import_labels(labels, images, out)
    click.echo(f"wrote {path}", err=True)
    if camera is not None or frame_interval_s is not None:
        sidecar = write_sidecar(path, frame_interval_s=frame_interval_s, camera=camera)
        click.echo(f"wrote {sidecar}", err=True)


@import_group.command("rosbag")
@click.argument("bag", type=click.Path(path_type=Path))
@click.option("--image-topic", required=True, metavar="TOPIC", help="Topic of sensor_msgs Image or CompressedImage.")
@click.option(
    "--nav-topic",
    metavar="TOPIC",
    help="Topic of nav_msgs Odometry or geometry_msgs TwistStamped: the vehicle speeds.",
)
@click.option(
    "--out",
    required=True,
    type=click.Path(file_okay=False, path_type=Path),
    help="Folder for the frames, the sequence file, its sidecar and the navigation file.",
)
@_calibration_options
def import_rosbag_command(
    bag: Path,
    image_topic: str,
    nav_topic: str | None,
    out: Path,
    focal_px: float | None,
    pipe_diameter_m: float | None,
    tilt_deg: float | None,
) -> None:
    """Write the images of the ROS 1 bag or ROS 2 bag folder BAG as an unlabelled image sequence file.

    OUT receives frame_00000.png, ..., NAME.txt (NAME the bag's stem, every
    frame nan: unlabelled) and the sidecar NAME.toml with the median frame
    interval; with --nav-topic also NAME.nav.csv, the speeds interpolated
    to each image's time (lateral = -y, vertical = -z, frontal = x of the
    ROS body frame).
    """
    from benchmark.modalities.camera.importers.rosbag import import_rosbag

    camera = _sidecar_camera(focal_px, pipe_diameter_m, tilt_deg)
    path = import_rosbag(bag, image_topic, out, nav_topic, camera)
    click.echo(f"wrote {path} and its frames", err=True)


@hookimpl
def trackbench_register_commands(registry: CommandRegistry) -> None:
    """Add ``diagnose``, ``pose-table``, ``import`` and ``label``."""
    for command in (diagnose_command, pose_table_command, import_group, label_command):
        registry.add_command(command)
