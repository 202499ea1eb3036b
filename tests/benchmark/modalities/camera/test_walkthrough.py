"""The README's walkthrough, end to end: a ROS 2 bag -> ``import rosbag`` -> ``label`` in Chromium -> ``run`` -> a board.

A short rendered dive (a camera scene of the suite's kind, 160x120 px) is
written into a ROS 2 bag with rosbags' own writer: ``sensor_msgs/Image``
frames and the vehicle's ``nav_msgs/Odometry``.  ``trackbench import
rosbag`` turns it into frames, an unlabelled sequence file and a sidecar
with the scene's calibration; the labeller, served from a thread as
``trackbench label`` serves it, gets both borders dragged onto the rendered
cable at five key frames in Chromium, interpolates and saves; ``trackbench
run --dataset`` then runs every camera tracker of the registry on the
labelled file (no ``--tracker`` selects them all), in this process
(``--in-process``) to save the workers' start-up.

``texture`` learns from labelled sequences and a user's own file names no
training suite, so the run trains it (``--train``) on a second dive of the
same scene kind, written here as a labelled sequence file: the README's
``--train camera-train`` renders the whole training suite, too slow for a
test.  Needs Python playwright and Chromium (the ``chromium`` fixture).
"""

from __future__ import annotations

import csv
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from click.testing import CliRunner, Result

from benchmark.cli import main
from benchmark.modalities.camera.geometry import cable_borders, pixel_to_model
from benchmark.modalities.camera.io.images import write_png
from benchmark.modalities.camera.io.sequence_file import read_sequence_file, write_sequence_file
from benchmark.modalities.camera.io.sidecar import read_sidecar
from benchmark.modalities.camera.labeller.app import drawing
from benchmark.modalities.camera.labeller.document import open_document
from benchmark.modalities.camera.model import CableState
from benchmark.modalities.camera.scenes.scene import CameraScene
from benchmark.plugins import load_registry

from .importers.test_rosbag import ROS2, Messages, write_bag
from .labeller.conftest import served
from .labeller.test_browser import distance, drag, interpolate_and_save, settle

sync_api = pytest.importorskip("playwright.sync_api", reason="the walkthrough labels in a browser: Python playwright")

N_FRAMES = 25
SIZE = (160, 120)
CALIBRATION = {"focal_px": 190.0, "pipe_diameter_m": 0.2, "tilt_deg": 50.0}
"""The scene's camera and pipe, given to ``import rosbag`` as its calibration options."""

KEY_FRAMES = (0, 6, 12, 18, 24)
INTERPOLATION_PX = 1.5
"""How far an interpolated label may lie from the rendered cable, px: the camera sways (``cx_m`` below), so
the borders move on a curve between key frames six frames apart; interpolating the true states themselves
misses it by up to 0.68 px, and a dragged key frame may be off by up to 0.5 px (the bound of key frames)."""

START_NS = 1_700_000_000_000_000_000
PERIOD_NS = 40_000_000


def dive(seed: int) -> CameraScene:
    """A dive of ``N_FRAMES`` small frames over a cable, the camera swaying sideways."""
    return CameraScene.from_dict({
        "name": f"dive-{seed}",
        "n_frames": N_FRAMES,
        "seed": seed,
        "frame_size": list(SIZE),
        "focal_px": CALIBRATION["focal_px"],
        "pipe_diameter_m": CALIBRATION["pipe_diameter_m"],
        "motion": {
            "cx_m": {"mean": 0.02, "waves": [{"amplitude": 0.15, "period_frames": 60.0}]},
            "cy_m": {"mean": 2.0},
            "phi_deg": {"mean": CALIBRATION["tilt_deg"]},
        },
    })


def record_bag(scene: CameraScene, folder: Path) -> Path:
    """The scene as a ROS 2 bag: mono8 images on ``/camera/image``, odometry on ``/odom``.

    The scene's speeds are lateral, vertical, frontal; ROS's body frame is x
    forward, y left, z up (what ``import rosbag`` turns back).
    """
    messages = Messages(ROS2.typestore)
    images, odometry = [], []
    for index in range(N_FRAMES):
        stamp = START_NS + index * PERIOD_NS
        speeds = scene.navigation(index)
        images.append((stamp, messages.raw_image(stamp, scene.render(index), "mono8")))
        odometry.append((stamp, messages.odometry(stamp, (speeds.frontal, -speeds.lateral, -speeds.vertical))))
    return write_bag(ROS2, folder, {"/camera/image": images, "/odom": odometry})


def write_labelled(scene: CameraScene, path: Path) -> Path:
    """The scene as a sequence file labelled with its truth: the training dive."""
    folder = path.with_suffix("")
    folder.mkdir()
    for index in range(N_FRAMES):
        write_png(folder / f"{index:03d}.png", scene.render(index))
    rows = ((scene.truth(index).cable, f"{folder.name}/{index:03d}.png") for index in range(N_FRAMES))
    write_sequence_file(path, rows)
    return path


def cli(*args: Any) -> Result:
    result = CliRunner().invoke(main, [str(arg) for arg in args])
    assert result.exit_code == 0, result.output
    return result


def label_key_frames(browser: Any, sequence_file: Path, scene: CameraScene) -> None:
    """Drag both borders onto the rendered cable at each key frame, interpolate and save, as a user would."""
    document = open_document(sequence_file)
    with served(document) as url:
        page = browser.new_page(viewport={"width": 1400, "height": 900})
        problems: list[str] = []
        page.on("pageerror", lambda error: problems.append(f"page error: {error}"))
        page.goto(url)
        settle(page)
        at = 0
        for index in KEY_FRAMES:
            for _ in range(index - at):
                page.keyboard.press("ArrowRight")
                settle(page)
            at = index
            assert page.inner_text("#position").startswith(f"frame {index + 1} / {N_FRAMES}")
            true_borders = drawing(scene.truth(index).cable, SIZE)
            for border in ("left", "right"):
                for end, target in enumerate(true_borders[border]):
                    drag(page, border, end, tuple(target))
            assert page.inner_text("#kind") == "key frame"
        interpolate_and_save(page, N_FRAMES - len(KEY_FRAMES))
        assert problems == []


def border_error_px(label: CableState, truth: CableState) -> float:
    """How far the labelled borders lie from the true ones in the image, px: at the ends of the true chords."""
    true_ends = drawing(truth, SIZE)
    return max(
        distance(line, pixel_to_model(*end, SIZE))
        for side, line in zip(("left", "right"), cable_borders(label), strict=True)
        for end in true_ends[side]
    )


def test_a_bag_imported_labelled_in_the_browser_and_run_by_every_camera_tracker_gives_a_ranked_board(
    chromium: Any, tmp_path: Path
) -> None:
    scene = dive(seed=31)
    bag = record_bag(scene, tmp_path)
    options = [f"--{key.replace('_', '-')}={value}" for key, value in CALIBRATION.items()]
    out = tmp_path / "dive"
    cli("import", "rosbag", bag, "--image-topic", "/camera/image", "--nav-topic", "/odom", "--out", out, *options)
    sequence_file = out / f"{bag.name}.txt"
    sidecar = read_sidecar(sequence_file, N_FRAMES)
    assert sidecar.calibration == scene.info.calibration
    assert sidecar.frame_interval_s == pytest.approx(scene.info.frame_interval_s)
    for index in range(N_FRAMES):
        recorded, imported = scene.navigation(index), sidecar.navigation[index]
        np.testing.assert_allclose(
            [imported.lateral, imported.vertical, imported.frontal],
            [recorded.lateral, recorded.vertical, recorded.frontal],
            atol=1e-12,
        )

    label_key_frames(chromium, sequence_file, scene)
    rows = read_sequence_file(sequence_file)
    assert len(rows) == N_FRAMES
    for index, row in enumerate(rows):
        bound = 0.5 if index in KEY_FRAMES else INTERPOLATION_PX
        assert border_error_px(row.cable, scene.truth(index).cable) < bound, (index, row.cable)

    training = write_labelled(dive(seed=32), tmp_path / "earlier-dive.txt")
    board = tmp_path / "board"
    cli("run", "--dataset", sequence_file, "--train", training, "--in-process", "--out", board)

    registry = load_registry()
    trackers = sorted(name for name, entry in registry.trackers.items() if entry.modality == "camera")
    assert "foresti_ekf" in trackers

    with (board / "leaderboard.csv").open() as handle:
        table = [row for row in csv.DictReader(handle) if row["dataset"] == str(sequence_file)]
    assert sorted(row["tracker"] for row in table) == trackers
    assert [int(row["rank"]) for row in table] == list(range(1, len(trackers) + 1))
    for row in table:
        assert (row["status"], row["frames"]) == ("ok", str(N_FRAMES)), row
        assert 0.0 <= float(row["correct_pct"]) <= 100.0, row
    assert float(table[0]["correct_pct"]) > 50.0
    assert (board / "leaderboard.md").is_file()
