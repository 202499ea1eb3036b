"""``trackbench import labels``: CSV and CVAT labels into an image sequence file, through the command line."""

from __future__ import annotations

import tomllib
from pathlib import Path

import cv2
import numpy as np
import pytest
from click.testing import CliRunner, Result

from benchmark.cli import main
from benchmark.cli.discovery import load_commands
from benchmark.modalities.camera.geometry import cable_borders, model_to_pixel
from benchmark.modalities.camera.io.sequence_file import HEADER, read_sequence_file
from benchmark.modalities.camera.model import CableState

SIZE = (40, 30)
"""``(W, H)`` of the test images."""

TRUE = CableState(d=3.0, alpha=0.2, w=8.0, beta=0.05)


def import_labels(*args: str | Path) -> Result:
    return CliRunner().invoke(main, ["import", "labels", *(str(arg) for arg in args)])


@pytest.fixture
def images(tmp_path: Path) -> Path:
    folder = tmp_path / "images"
    folder.mkdir()
    for index in range(3):
        cv2.imwrite(str(folder / f"f{index}.png"), np.full(SIZE[::-1], 40 * index, np.uint8))
    return folder


def border_pixels(state: CableState) -> list[tuple[tuple[float, float], tuple[float, float]]]:
    """Two pixel points on each border of ``state``, 12 px either side of its foot point."""
    ends = []
    for line in cable_borders(state):
        x, y = line.nearest_point_to_origin()
        ends.append(
            tuple(model_to_pixel(x + s * line.dx, y + s * line.dy, SIZE) for s in (-12.0, 12.0))  # type: ignore[misc]
        )
    return ends


def assert_state_close(actual: CableState, expected: CableState) -> None:
    assert actual.as_array() == pytest.approx(expected.as_array(), abs=1e-9)


def test_import_is_the_camera_modality_s_command_added_through_the_hook() -> None:
    commands = load_commands(main.commands)
    assert commands.origins["import"].plugin == "modality-camera"
    assert sorted(commands.commands["import"].commands) == ["labels", "rosbag"]


def test_csv_cable_states_are_written_as_given_and_an_empty_row_is_unlabelled(tmp_path: Path, images: Path) -> None:
    labels = tmp_path / "labels.csv"
    labels.write_text("image,d,alpha,w,beta\nf0.png,3.5,-0.082,21.5,0.043\nf1.png,,,,\nf2.png,-1,0.1,9,0\n")
    out = tmp_path / "seq.txt"
    result = import_labels(labels, "--images", images, "--out", out)
    assert result.exit_code == 0, result.output
    text = out.read_text()
    assert text.splitlines()[0] == HEADER
    assert text.splitlines()[1] == "3.5 -0.082 21.5 0.043 # images/f0.png"
    rows = read_sequence_file(out)
    assert [row.image for row in rows] == [images / f"f{index}.png" for index in range(3)]
    assert rows[0].cable == CableState(3.5, -0.082, 21.5, 0.043)
    assert not rows[1].cable.is_known
    assert rows[2].cable == CableState(-1.0, 0.1, 9.0, 0.0)
    assert not out.with_suffix(".toml").exists()


def test_csv_border_end_points_become_the_cable_state(tmp_path: Path, images: Path) -> None:
    (a1, a2), (b1, b2) = border_pixels(TRUE)
    labels = tmp_path / "borders.csv"
    numbers = ",".join(repr(v) for v in (*a1, *a2, *b1, *b2))
    labels.write_text(f"image,x1a,y1a,x2a,y2a,x1b,y1b,x2b,y2b\nf0.png,{numbers}\nf1.png,nan,nan,,,,,,\n")
    out = tmp_path / "seq.txt"
    assert import_labels(labels, "--images", images, "--out", out).exit_code == 0
    first, second = read_sequence_file(out)
    assert_state_close(first.cable, TRUE)
    assert not second.cable.is_known


def test_cvat_polylines_become_the_cable_state_and_an_image_without_them_is_unlabelled(
    tmp_path: Path, images: Path
) -> None:
    (a1, a2), (b1, b2) = border_pixels(TRUE)
    middle = ((a1[0] + a2[0]) / 2 + 0.7, (a1[1] + a2[1]) / 2)  # an inner point, not used: the ends define a border
    labels = tmp_path / "annotations.xml"
    labels.write_text(
        f"""<?xml version="1.0" encoding="utf-8"?>
<annotations><version>1.1</version><meta/>
  <image id="0" name="f0.png" width="{SIZE[0]}" height="{SIZE[1]}">
    <polyline label="border" occluded="0" source="manual" z_order="0"
      points="{a1[0]!r},{a1[1]!r};{middle[0]!r},{middle[1]!r};{a2[0]!r},{a2[1]!r}"/>
    <polyline label="border" occluded="0" source="manual" z_order="0" points="{b2[0]!r},{b2[1]!r};{b1[0]!r},{b1[1]!r}"/>
  </image>
  <image id="1" name="f1.png" width="{SIZE[0]}" height="{SIZE[1]}"/>
</annotations>
"""
    )
    out = tmp_path / "nested" / "seq.txt"
    assert import_labels(labels, "--images", images, "--out", out).exit_code == 0
    first, second = read_sequence_file(out)
    assert_state_close(first.cable, TRUE)
    assert not second.cable.is_known
    assert second.image == images / "f1.png"


def test_the_calibration_options_write_the_sidecar(tmp_path: Path, images: Path) -> None:
    labels = tmp_path / "labels.csv"
    labels.write_text("image,d,alpha,w,beta\nf0.png,1,0,5,0\n")
    out = tmp_path / "seq.txt"
    options = ["--focal-px", "800", "--pipe-diameter-m", "0.3", "--tilt-deg", "30", "--frame-interval-s", "0.04"]
    assert import_labels(labels, "--images", images, "--out", out, *options).exit_code == 0
    text = (tmp_path / "seq.toml").read_text()
    assert tomllib.loads(text) == {
        "frame_interval_s": 0.04,
        "camera": {"focal_px": 800.0, "pipe_diameter_m": 0.3, "tilt_deg": 30.0},
    }
    assert text.startswith("frame_interval_s = 0.04\n[camera]\nfocal_px = 800.0\n")


LABEL_ERRORS = [
    ("a.txt", "image,d\n", "unknown label format"),
    ("a.csv", "image,d,alpha,w\nf0.png,1,0,5\n", "a.csv:1: header 'image,d,alpha,w' names neither column set"),
    ("a.csv", "image,d,alpha,w,beta\nf0.png,1,0,5\n", "a.csv:2: expected 5 cells"),
    ("a.csv", "image,d,alpha,w,beta\nf0.png,1,0,5,0\nf1.png,1,x,5,0\n", "a.csv:3: alpha:"),
    ("a.csv", "image,d,alpha,w,beta\nf0.png,1,nan,5,0\n", "a.csv:2: alpha: must be finite"),
    ("a.csv", "image,d,alpha,w,beta\nf0.png,1,0,-5,0\n", "a.csv:2: w: must be > 0"),
    ("a.csv", "image,d,alpha,w,beta\nf0.png,1,0,5,-0.1\n", "a.csv:2: beta: must be >= 0"),
    ("a.csv", "image,d,alpha,w,beta\n ,1,0,5,0\n", "a.csv:2: image: must not be empty"),
    ("a.csv", "image,d,alpha,w,beta\nnone.png,1,0,5,0\n", "a.csv:2: image 'none.png' is not a file"),
    ("a.csv", "image,d,alpha,w,beta\n", "no labelled images"),
    ("a.csv", "image,x1a,y1a,x2a,y2a,x1b,y1b,x2b,y2b\nf0.png,1,2,1,2,5,0,5,9\n", "a.csv:2: border a: its two end"),
    ("a.csv", "image,x1a,y1a,x2a,y2a,x1b,y1b,x2b,y2b\nnone.png,1,2,1,9,5,0,5,9\n", "a.csv:2: image"),
    ("a.xml", "<annotations><image", "a.xml: not well-formed XML"),
    ("a.xml", "<root/>", "a.xml: root element is <root>"),
    ("a.xml", "<annotations><track id='0'/></annotations>", "a.xml: holds <track> elements"),
    (
        "a.xml",
        "<annotations><image name='f0.png' width='40' height='30'><polyline points='1,2;3,4'/></image></annotations>",
        "a.xml: <image> 1 (name='f0.png'): 1 <polyline> elements",
    ),
    (
        "a.xml",
        "<annotations><image name='f0.png' width='40' height='0'/></annotations>",
        "a.xml: <image> 1 (name='f0.png'): height:",
    ),
    (
        "a.xml",
        "<annotations><image name='f0.png' width='40' height='30'>"
        "<polyline points='1,2;3,x'/><polyline points='1,2;3,4'/></image></annotations>",
        "a.xml: <image> 1 (name='f0.png'): <polyline> a: points[1][1]:",
    ),
    (
        "a.xml",
        "<annotations><image name='f0.png' width='40' height='30'>"
        "<polyline points='1,2'/><polyline points='1,2;3,4'/></image></annotations>",
        "a.xml: <image> 1 (name='f0.png'): <polyline> a: points:",
    ),
]


@pytest.mark.parametrize(("name", "content", "message"), LABEL_ERRORS)
def test_bad_labels_are_one_error_line_naming_file_place_and_field(
    tmp_path: Path, images: Path, name: str, content: str, message: str
) -> None:
    labels = tmp_path / name
    labels.write_text(content)
    out = tmp_path / "seq.txt"
    result = import_labels(labels, "--images", images, "--out", out)
    assert result.exit_code == 2
    assert result.output.startswith("Error: ") and message in result.output, result.output
    assert "Traceback" not in result.output
    assert not out.exists()


def test_a_missing_label_file_or_image_folder_is_an_error(tmp_path: Path, images: Path) -> None:
    labels = tmp_path / "labels.csv"
    result = import_labels(labels, "--images", images, "--out", tmp_path / "s.txt")
    assert result.exit_code == 2 and f"{labels}: no such label file" in result.output
    labels.write_text("image,d,alpha,w,beta\nf0.png,1,0,5,0\n")
    result = import_labels(labels, "--images", tmp_path / "nowhere", "--out", tmp_path / "s.txt")
    assert result.exit_code == 2 and "nowhere: no such image folder" in result.output


def test_calibration_options_come_all_three_and_valid(tmp_path: Path, images: Path) -> None:
    labels = tmp_path / "labels.csv"
    labels.write_text("image,d,alpha,w,beta\nf0.png,1,0,5,0\n")
    out = tmp_path / "seq.txt"
    result = import_labels(labels, "--images", images, "--out", out, "--focal-px", "800")
    assert result.exit_code == 2 and "--pipe-diameter-m, --tilt-deg" in result.output
    bad = ["--focal-px", "-1", "--pipe-diameter-m", "0.3", "--tilt-deg", "nan"]
    result = import_labels(labels, "--images", images, "--out", out, *bad)
    assert result.exit_code == 2
    assert "focal_px: must be > 0" in result.output and "tilt_deg: must be finite" in result.output
    assert not out.exists()
