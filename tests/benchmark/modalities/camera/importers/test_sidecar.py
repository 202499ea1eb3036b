"""The sidecar writer: the fixed TOML layout beside a sequence file, and the navigation CSV."""

from __future__ import annotations

import tomllib
from pathlib import Path

import pytest

from benchmark.errors import DataError
from benchmark.modalities.camera.importers.sidecar import (
    NAVIGATION_HEADER,
    SidecarCamera,
    sidecar_path,
    write_navigation_file,
    write_sidecar,
)
from benchmark.modalities.camera.model import VehicleSpeeds


def test_the_sidecar_is_the_sequence_file_with_suffix_toml() -> None:
    assert sidecar_path(Path("data/S.txt")) == Path("data/S.toml")


def test_every_part_is_written_in_the_fixed_order_and_reads_back(tmp_path: Path) -> None:
    camera = SidecarCamera(focal_px=800, pipe_diameter_m=0.3, tilt_deg=30)
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
        SidecarCamera(focal_px=0.0, pipe_diameter_m=0.3, tilt_deg=30)


def test_the_navigation_file_has_one_row_per_frame_from_0(tmp_path: Path) -> None:
    path = write_navigation_file(tmp_path / "n.csv", [VehicleSpeeds(0.1, -0.2, 1.5), VehicleSpeeds(0.0, 0.0, 1.25)])
    assert path.read_text() == f"{NAVIGATION_HEADER}\n0,0.1,-0.2,1.5\n1,0.0,0.0,1.25\n"


def test_an_unwritable_sidecar_is_a_data_error_naming_it(tmp_path: Path) -> None:
    with pytest.raises(DataError, match="S.toml"):
        write_sidecar(tmp_path / "missing" / "S.txt", frame_interval_s=0.04)
