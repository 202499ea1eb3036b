"""Sidecars: the calibration, frame interval and navigation a sequence on disk carries beside it."""

from __future__ import annotations

import math
import pickle
import tomllib
from pathlib import Path

import cv2
import numpy as np
import pytest

from benchmark.errors import DataError
from benchmark.modalities.camera.io.image_folder import ImageFolder
from benchmark.modalities.camera.io.sequence_file import ImageSequenceFile, write_sequence_file
from benchmark.modalities.camera.io.sidecar import (
    NAVIGATION_COLUMNS,
    CameraTable,
    read_sidecar,
    sidecar_path,
    write_navigation_file,
    write_sidecar,
)
from benchmark.modalities.camera.io.video import VideoFile
from benchmark.modalities.camera.model import UNKNOWN_CABLE, CameraCalibration, VehicleSpeeds

CAMERA = "[camera]\nfocal_px = 800.0\npipe_diameter_m = 0.3\ntilt_deg = 30\n"


def _sequence(folder: Path, make_image, n_frames: int = 3) -> Path:
    for index in range(n_frames):
        make_image(folder / "frames" / f"{index}.png")
    path = folder / "S.txt"
    write_sequence_file(path, [(UNKNOWN_CABLE, f"frames/{index}.png") for index in range(n_frames)])
    return path


def test_the_sidecar_is_the_path_with_toml_for_a_suffix_and_beside_a_folder(tmp_path):
    (tmp_path / "DIR").mkdir()
    assert sidecar_path(tmp_path / "S.txt") == tmp_path / "S.toml"
    assert sidecar_path(tmp_path / "V.mp4") == tmp_path / "V.toml"
    assert sidecar_path(tmp_path / "DIR") == tmp_path.resolve() / "DIR.toml"


def test_a_sequence_file_reads_calibration_interval_and_navigation_columns(tmp_path, make_image):
    path = _sequence(tmp_path, make_image)
    columns = "lateral_mps = [0.1, 0.2, 0.3]\nvertical_mps = [0, 0, 0]\nfrontal_mps = [1, 1, 1.5]\n"
    (tmp_path / "S.toml").write_text(f"frame_interval_s = 0.04\n{CAMERA}[navigation]\n{columns}")
    sequence = ImageSequenceFile(path)
    info = sequence.info
    assert info.frame_interval_s == 0.04
    assert info.calibration == CameraCalibration(800.0, 0.3, math.radians(30))
    frames = list(pickle.loads(pickle.dumps(sequence)).frames())
    assert [frame.navigation for frame in frames] == [
        VehicleSpeeds(0.1, 0.0, 1.0),
        VehicleSpeeds(0.2, 0.0, 1.0),
        VehicleSpeeds(0.3, 0.0, 1.5),
    ]
    assert [frame.time_s for frame in frames] == [0.0, 0.04, 0.08]


def test_a_navigation_csv_gives_speeds_to_the_frames_it_lists(tmp_path, make_image):
    path = _sequence(tmp_path, make_image)
    (tmp_path / "S.toml").write_text('[navigation]\nfile = "S.nav.csv"\n')
    (tmp_path / "S.nav.csv").write_text("frame,lateral_mps,vertical_mps,frontal_mps\n2,0.5,-0.1,1.2\n0,0,0,1\n")
    frames = list(ImageSequenceFile(path).frames())
    assert [frame.navigation for frame in frames] == [VehicleSpeeds(0.0, 0.0, 1.0), None, VehicleSpeeds(0.5, -0.1, 1.2)]


def test_an_image_folder_reads_the_sidecar_beside_it(tmp_path, make_image):
    for index in range(2):
        make_image(tmp_path / "DIR" / f"{index}.png")
    (tmp_path / "DIR.toml").write_text(f"frame_interval_s = 0.5\n{CAMERA}")
    info = ImageFolder(tmp_path / "DIR").info
    assert (info.frame_interval_s, info.calibration.focal_px) == (0.5, 800.0)


def test_a_video_takes_the_sidecars_interval_over_the_containers(tmp_path):
    path = tmp_path / "V.avi"
    writer = cv2.VideoWriter(str(path), cv2.VideoWriter_fourcc(*"MJPG"), 10.0, (16, 16))
    for value in (0, 100):
        writer.write(np.full((16, 16, 3), value, np.uint8))
    writer.release()
    assert VideoFile(path).info.frame_interval_s == pytest.approx(0.1)
    (tmp_path / "V.toml").write_text(f"frame_interval_s = 0.25\n{CAMERA}[navigation]\nfile = 'nav.csv'\n")
    (tmp_path / "nav.csv").write_text("frame,lateral_mps,vertical_mps,frontal_mps\n1,0,0,2\n")
    video = VideoFile(path)
    assert video.info.frame_interval_s == 0.25
    assert video.info.calibration is not None
    assert [frame.navigation for frame in video.frames()] == [None, VehicleSpeeds(0.0, 0.0, 2.0)]


def test_without_a_sidecar_the_identity_is_unchanged_and_an_edited_sidecar_is_another_dataset(tmp_path, make_image):
    path = _sequence(tmp_path, make_image)
    bare = ImageSequenceFile(path).identity
    with_nothing_but_comments = tmp_path / "S.toml"
    with_nothing_but_comments.write_text("# nothing yet\n")
    commented = ImageSequenceFile(path).identity
    with_nothing_but_comments.write_text(CAMERA)
    calibrated = ImageSequenceFile(path).identity
    with_nothing_but_comments.write_text(CAMERA.replace("800.0", "801.0"))
    edited = ImageSequenceFile(path).identity
    assert len({bare.key, commented.key, calibrated.key, edited.key}) == 4
    with_nothing_but_comments.unlink()
    assert ImageSequenceFile(path).identity == bare


def test_an_edited_navigation_file_is_another_dataset(tmp_path, make_image):
    path = _sequence(tmp_path, make_image)
    (tmp_path / "S.toml").write_text('[navigation]\nfile = "S.nav.csv"\n')
    navigation = tmp_path / "S.nav.csv"
    navigation.write_text("frame,lateral_mps,vertical_mps,frontal_mps\n0,0,0,1\n")
    before = ImageSequenceFile(path).identity.key
    navigation.write_text("frame,lateral_mps,vertical_mps,frontal_mps\n0,0,0,2\n")
    assert ImageSequenceFile(path).identity.key != before


@pytest.mark.parametrize(
    ("sidecar", "message"),
    [
        ("frame_interval = 0.04\n", "S.toml: unknown key 'frame_interval' (known: frame_interval_s, camera, navigation)"),
        ("[camera]\nfocal_px = 800.0\npipe_diameter_m = 0.3\ntilt_deg = 30\nlens = 'wide'\n", "camera: unknown key 'lens'"),
        ("frame_interval_s = 0\n", "S.toml: frame_interval_s: must be > 0, got 0"),
        ("frame_interval_s = '0.04'\n", "frame_interval_s: expected a number, got '0.04'"),
        (CAMERA.replace("800.0", "-1.0"), "S.toml: camera.focal_px: must be > 0, got -1.0"),
        (CAMERA.replace("tilt_deg = 30", "tilt_deg = 90"), "S.toml: camera.tilt_deg: must be < 90, got 90"),
        ("[camera]\nfocal_px = 800.0\n", "S.toml: camera: missing required key 'pipe_diameter_m'"),
        ("[navigation]\nlateral_mps = [0.1]\n", "S.toml: navigation: give file, or all of lateral_mps"),
        (
            "[navigation]\nlateral_mps = [0, 0]\nvertical_mps = [0, 0]\nfrontal_mps = [1]\n",
            "S.toml: navigation: the columns must be equally long, got lateral_mps 2, vertical_mps 2, frontal_mps 1",
        ),
        (
            "[navigation]\nlateral_mps = [0, 0]\nvertical_mps = [0, 0]\nfrontal_mps = [1, 1]\n",
            "S.toml: navigation: the columns hold 2 values, but the sequence has 3 frames",
        ),
        ("[navigation]\nfile = 'S.nav.csv'\nlateral_mps = [0]\n", "S.toml: navigation: give either file or the columns"),
        ("[navigation]\nfile = 'gone.csv'\n", "S.toml: navigation.file: "),
        ("[camera\n", "S.toml: not a valid TOML sidecar"),
    ],
)
def test_a_bad_sidecar_is_refused_naming_the_file_and_the_key(tmp_path, make_image, sidecar, message):
    path = _sequence(tmp_path, make_image)
    (tmp_path / "S.toml").write_text(sidecar)
    with pytest.raises(DataError, match="^" + str(tmp_path).replace("\\", "\\\\")) as caught:
        ImageSequenceFile(path)
    assert message in str(caught.value)


@pytest.mark.parametrize(
    ("csv", "message"),
    [
        ("frame,lateral,vertical,frontal\n0,0,0,1\n", "S.nav.csv:1: expected the header"),
        ("", "S.nav.csv:1: expected the header"),
        ("frame,lateral_mps,vertical_mps,frontal_mps\n0,0,0,1\n1,0,0\n", "S.nav.csv:3: expected 4 values"),
        ("frame,lateral_mps,vertical_mps,frontal_mps\n0,0,fast,1\n", "S.nav.csv:2: vertical_mps: "),
        ("frame,lateral_mps,vertical_mps,frontal_mps\n0,0,nan,1\n", "S.nav.csv:2: vertical_mps: "),
        ("frame,lateral_mps,vertical_mps,frontal_mps\n-1,0,0,1\n", "S.nav.csv:2: frame: must be >= 0"),
        ("frame,lateral_mps,vertical_mps,frontal_mps\n1,0,0,1\n\n1,0,0,1\n", "S.nav.csv:4: frame 1 is listed twice"),
        ("frame,lateral_mps,vertical_mps,frontal_mps\n3,0,0,1\n", "S.nav.csv:2: frame 3 is beyond the sequence's 3 frames"),
    ],
)
def test_a_malformed_navigation_csv_names_the_file_and_the_line(tmp_path, make_image, csv, message):
    path = _sequence(tmp_path, make_image)
    (tmp_path / "S.toml").write_text('[navigation]\nfile = "S.nav.csv"\n')
    (tmp_path / "S.nav.csv").write_text(csv)
    with pytest.raises(DataError) as caught:
        ImageSequenceFile(path)
    assert message in str(caught.value)


def test_a_sequence_says_what_it_lacks_and_the_line_that_adds_it_without_reading_an_image(tmp_path, make_image):
    path = _sequence(tmp_path, make_image)
    (tmp_path / "frames" / "0.png").unlink()  # info would need it; lacks must not
    lacks = ImageSequenceFile(path).lacks(("calibration", "frame_interval_s", "frame_size"))
    sidecar = tmp_path / "S.toml"
    assert lacks == {
        "calibration": f"camera calibration: add focal_px, pipe_diameter_m, tilt_deg under [camera] in {sidecar}",
        "frame_interval_s": f"frame interval: add frame_interval_s (s) at the top of {sidecar}",
    }
    sidecar.write_text(f"frame_interval_s = 0.1\n{CAMERA}")
    assert ImageSequenceFile(path).lacks(("calibration", "frame_interval_s")) == {}


def test_a_sequence_file_named_toml_is_not_its_own_sidecar(tmp_path, make_image):
    make_image(tmp_path / "0.png")
    path = tmp_path / "S.toml"
    write_sequence_file(path, [(UNKNOWN_CABLE, "0.png")])
    assert read_sidecar(path).content_digest is None
    assert ImageSequenceFile(path).info.calibration is None


def test_every_part_is_written_in_the_fixed_order_and_reads_back(tmp_path: Path) -> None:
    camera = CameraTable(focal_px=800, pipe_diameter_m=0.3, tilt_deg=30)
    path = write_sidecar(tmp_path / "S.txt", frame_interval_s=0.04, camera=camera, navigation_file='odd "name" é.csv')
    text = path.read_text(encoding="utf-8")
    assert text.splitlines()[:5] == [
        "frame_interval_s = 0.04",
        "[camera]",
        "focal_px = 800.0",
        "pipe_diameter_m = 0.3",
        "tilt_deg = 30.0",
    ]
    assert tomllib.loads(text)["navigation"] == {"file": 'odd "name" é.csv'}


def test_parts_not_given_are_left_out(tmp_path: Path) -> None:
    path = write_sidecar(tmp_path / "S.txt", navigation_file="S.nav.csv")
    assert path.read_text() == '[navigation]\nfile = "S.nav.csv"\n'


def test_the_camera_table_is_validated() -> None:
    with pytest.raises(ValueError, match="focal_px"):
        CameraTable(focal_px=0.0, pipe_diameter_m=0.3, tilt_deg=30)


def test_the_navigation_file_has_one_row_per_frame_from_0(tmp_path: Path) -> None:
    path = write_navigation_file(tmp_path / "n.csv", [VehicleSpeeds(0.1, -0.2, 1.5), VehicleSpeeds(0.0, 0.0, 1.25)])
    assert path.read_text() == f"{','.join(NAVIGATION_COLUMNS)}\n0,0.1,-0.2,1.5\n1,0.0,0.0,1.25\n"


def test_an_unwritable_sidecar_is_a_data_error_naming_it(tmp_path: Path) -> None:
    with pytest.raises(DataError, match="S.toml"):
        write_sidecar(tmp_path / "missing" / "S.txt", frame_interval_s=0.04)


def test_what_is_written_reads_back_as_the_same_calibration_interval_and_speeds(tmp_path: Path) -> None:
    speeds = [VehicleSpeeds(0.1, -0.2, 1.5), VehicleSpeeds(0.0, 0.0, 1.25)]
    write_navigation_file(tmp_path / "S.nav.csv", speeds)
    camera = CameraTable(focal_px=812.5, pipe_diameter_m=0.3, tilt_deg=31.0)
    write_sidecar(tmp_path / "S.txt", frame_interval_s=0.04, camera=camera, navigation_file="S.nav.csv")
    sidecar = read_sidecar(tmp_path / "S.txt", n_frames=2)
    assert sidecar.calibration == camera.calibration() and sidecar.frame_interval_s == 0.04
    assert [sidecar.navigation.get(frame) for frame in (0, 1)] == speeds
