"""What every sidecar shares: its place beside the data, its TOML tables, its per-frame CSV files."""

from __future__ import annotations

import math
from typing import Annotated

import pydantic
import pytest
from annotated_types import Ge

from benchmark.errors import DataError
from benchmark.scenes.spec import SPEC_CONFIG, Positive
from benchmark.sidecar import number_text, read_frame_csv, read_toml_table, sidecar_path


@pydantic.dataclasses.dataclass(frozen=True)
class Row:
    frame: Annotated[int, Ge(0)]
    depth_m: pydantic.FiniteFloat


@pydantic.dataclasses.dataclass(frozen=True, config=SPEC_CONFIG)
class Table:
    interval_s: Positive | None = None


COLUMNS = ("frame", "depth_m")


def test_the_sidecar_is_the_path_with_toml_for_a_suffix_and_beside_a_folder(tmp_path):
    (tmp_path / "DIR").mkdir()
    assert sidecar_path(tmp_path / "S.txt") == tmp_path / "S.toml"
    assert sidecar_path(tmp_path / "DIR") == tmp_path.resolve() / "DIR.toml"


def test_a_toml_table_is_validated_and_its_bytes_returned(tmp_path):
    path = tmp_path / "S.toml"
    path.write_text("interval_s = 0.5\n")
    assert read_toml_table(path, Table) == (Table(0.5), b"interval_s = 0.5\n")
    path.write_text("interval_s = 0\n")
    with pytest.raises(DataError, match=r"S.toml: interval_s: must be > 0, got 0"):
        read_toml_table(path, Table)
    path.write_text("interval_s = \n")
    with pytest.raises(DataError, match=r"S.toml: not a valid TOML sidecar"):
        read_toml_table(path, Table)


def test_csv_rows_are_read_by_frame_with_blank_lines_and_spaces_ignored(tmp_path):
    rows = read_frame_csv(tmp_path / "d.csv", b"frame, depth_m\n\n2, 1.5\n0,-1\n", Row, COLUMNS, n_frames=3)
    assert rows == {2: Row(2, 1.5), 0: Row(0, -1.0)}


@pytest.mark.parametrize(
    ("content", "message"),
    [
        (b"", r"d.csv:1: expected the header 'frame,depth_m', found 'nothing'"),
        (b"frame,depth\n", r"d.csv:1: expected the header 'frame,depth_m', found 'frame,depth'"),
        (b"frame,depth_m\n0,1,2\n", r"d.csv:2: expected 2 values \(frame,depth_m\), found 3"),
        (b"frame,depth_m\n0,nan\n", r"d.csv:2: depth_m"),
        (b"frame,depth_m\n-1,0\n", r"d.csv:2: frame"),
        (b"frame,depth_m\n1,0\n\n1,2\n", r"d.csv:4: frame 1 is listed twice"),
        (b"frame,depth_m\n3,0\n", r"d.csv:2: frame 3 is beyond the sequence's 3 frames"),
        (b"\xff", r"d.csv: not a UTF-8 text file"),
    ],
)
def test_a_bad_csv_file_is_refused_naming_the_file_and_line(tmp_path, content, message):
    with pytest.raises(DataError, match=message):
        read_frame_csv(tmp_path / "d.csv", content, Row, COLUMNS, n_frames=3)


def test_numbers_are_written_to_read_back_exactly_and_only_when_finite():
    value = 0.1 + 0.2
    assert float(number_text(value)) == value and number_text(3) == "3.0"
    with pytest.raises(ValueError, match="cannot be written to a sidecar"):
        number_text(math.inf)
