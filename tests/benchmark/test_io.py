"""Tests of benchmark.io: choosing a modality's reader for a dataset path, exporting by modality, file stems."""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

import cv2
import numpy as np
import pytest

from benchmark.errors import DataError
from benchmark.io import default_stem, export_sequence, open_sequence
from benchmark.modalities.camera.io.image_folder import ImageFolder
from benchmark.modalities.camera.io.sequence_file import ImageSequenceFile
from benchmark.modalities.camera.io.video import VideoFile
from benchmark.modalities.camera.modality import CAMERA
from benchmark.modalities.sonar.modality import SONAR
from benchmark.modalities.stereo.modality import STEREO
from benchmark.modality import ANY_FILE, Modality, Reader
from benchmark.model import Frame, Sequence, SequenceInfo

BUILT_IN = (CAMERA, SONAR, STEREO)


def test_a_folder_opens_as_image_folder(tmp_path, make_image):
    make_image(tmp_path / "a.png")
    assert isinstance(open_sequence(tmp_path, BUILT_IN), ImageFolder)
    assert isinstance(open_sequence(str(tmp_path), BUILT_IN), ImageFolder)


@pytest.mark.parametrize("name", ["clip.avi", "CLIP.AVI"])
def test_a_video_name_opens_as_video(tmp_path, name):
    path = tmp_path / name
    writer = cv2.VideoWriter(str(path), cv2.VideoWriter_fourcc(*"MJPG"), 5.0, (16, 8), True)
    if not writer.isOpened():
        pytest.skip("this OpenCV build cannot write MJPG into .avi")
    writer.write(np.zeros((8, 16, 3), dtype=np.uint8))
    writer.release()
    assert isinstance(open_sequence(path, BUILT_IN), VideoFile)


@pytest.mark.parametrize("name", ["seq.txt", "S1.seq", "labels", "ground truth.dat"])
def test_any_other_file_opens_as_image_sequence_file(tmp_path, name):
    path = tmp_path / name
    path.write_text("1 0 20 0 # a.png\n", encoding="utf-8")
    sequence = open_sequence(path, BUILT_IN)
    assert isinstance(sequence, ImageSequenceFile)
    assert [row.line for row in sequence.rows] == [1]
    assert sequence.rows[0].image == (tmp_path / "a.png").resolve()


def test_a_missing_path_is_named(tmp_path):
    with pytest.raises(DataError, match="no_such_dataset"):
        open_sequence(tmp_path / "no_such_dataset", BUILT_IN)


def test_a_malformed_file_is_reported_by_its_reader(tmp_path):
    path = tmp_path / "clip.mkv.txt"
    path.write_text("this is not a row\n", encoding="utf-8")
    with pytest.raises(DataError, match="clip.mkv.txt:1:"):
        open_sequence(path, BUILT_IN)


# ------------------------------------------------------------- reader dispatch, with recording readers
@dataclass(frozen=True)
class Opened(Sequence):
    """What a recording reader returns: which reader opened which path."""

    reader: str
    path: str

    @property
    def info(self) -> SequenceInfo:
        return SequenceInfo(self.path, "fake")

    def frames(self) -> Iterator[Frame]:
        return iter(())


def recording(name: str, **claims) -> Reader:
    return Reader(lambda path: Opened(name, str(path)), f"the {name} reader", **claims)


class NoScorer:
    error_columns = ()


def modality(name: str, *readers: Reader) -> Modality:
    return Modality(name, object, object, object, NoScorer(), readers=readers)  # type: ignore[arg-type]


DISPATCH = (
    modality("scans", recording("scan", suffixes=(".scan", ".sc2"))),
    modality("pictures", recording("folder", folders=True), recording("any", suffixes=(ANY_FILE,))),
)


@pytest.mark.parametrize(
    ("name", "reader"),
    [("a.scan", "scan"), ("B.SC2", "scan"), ("a.txt", "any"), ("scan", "any"), ("a.scan.bak", "any")],
)
def test_a_claimed_suffix_goes_to_its_reader_and_any_other_file_to_the_any_file_reader(tmp_path, name, reader):
    path = tmp_path / name
    path.write_text("x", encoding="utf-8")
    assert open_sequence(path, DISPATCH) == Opened(reader, str(path))


def test_a_folder_goes_to_the_folder_reader_whatever_its_name(tmp_path):
    folder = tmp_path / "looks_like.scan"
    folder.mkdir()
    assert open_sequence(folder, DISPATCH) == Opened("folder", str(folder))


def test_the_reader_gets_the_path_as_given(tmp_path):
    path = tmp_path / "a.scan"
    path.write_text("x", encoding="utf-8")
    assert open_sequence(str(path), DISPATCH).path == str(path)


def test_a_missing_path_is_a_data_error_naming_it_and_the_readers(tmp_path):
    with pytest.raises(DataError, match=r"nowhere\.scan: no such dataset.*the scan reader.*the any reader"):
        open_sequence(tmp_path / "nowhere.scan", DISPATCH)


def test_a_path_no_reader_claims_is_a_data_error_naming_it(tmp_path):
    text = tmp_path / "notes.txt"
    text.write_text("x", encoding="utf-8")
    with pytest.raises(DataError, match=r"notes\.txt: no registered reader opens this.*a swath file"):
        open_sequence(text, [SONAR])
    with pytest.raises(DataError, match=r"no registered reader opens this"):
        open_sequence(tmp_path, [SONAR])
    with pytest.raises(DataError, match=r"notes\.txt: .*no readers are registered"):
        open_sequence(text, [])


# ------------------------------------------------------------- export through the modality's exporter
@dataclass(frozen=True)
class Named(Sequence):
    name: str
    modality: str

    @property
    def info(self) -> SequenceInfo:
        return SequenceInfo(self.name, self.modality)

    def frames(self) -> Iterator[Frame]:
        return iter(())


def test_export_calls_the_exporter_of_the_sequence_s_modality_with_the_default_stem(tmp_path):
    calls = []

    def exporter(sequence: Sequence, out: Path, stem: str) -> Path:
        calls.append((sequence.info.name, out, stem))
        return out / f"{stem}.scan"

    scans = Modality("scans", object, object, object, NoScorer(), exporter=exporter)  # type: ignore[arg-type]
    written = export_sequence(Named("suite/seq", "scans"), str(tmp_path), {"scans": scans, "sonar": SONAR})
    assert written == tmp_path / "suite_seq.scan"
    assert calls == [("suite/seq", tmp_path, "suite_seq")]
    export_sequence(Named("suite/seq", "scans"), tmp_path, {"scans": scans}, stem="mine")
    assert calls[-1] == ("suite/seq", tmp_path, "mine")


def test_a_modality_without_exporter_or_not_registered_cannot_export(tmp_path):
    modalities = {"camera": CAMERA, "sonar": SONAR, "stereo": STEREO}
    with pytest.raises(DataError, match=r"s/1: stereo sequences cannot be exported \(exportable: camera, sonar\)"):
        export_sequence(Named("s/1", "stereo"), tmp_path, modalities)
    with pytest.raises(DataError, match=r"s/1: lidar sequences cannot be exported"):
        export_sequence(Named("s/1", "lidar"), tmp_path, modalities)
    with pytest.raises(DataError, match=r"exportable: none"):
        export_sequence(Named("s/1", "stereo"), tmp_path, {"stereo": STEREO})
    assert list(tmp_path.iterdir()) == []


def test_default_stem_replaces_path_separators():
    assert default_stem("suite/seq") == "suite_seq"
    assert default_stem("a\\b/c") == "a_b_c"
    assert default_stem("") == "sequence"
    assert default_stem("..") == "sequence"
