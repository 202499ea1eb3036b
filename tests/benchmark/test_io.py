"""Tests of benchmark.io: choosing a modality's reader for a dataset path, exporting by modality, file stems.

Also the identity of every file-backed sequence the built-in readers open,
and their refusal of paths that are not regular files.
"""

from __future__ import annotations

import os
import pickle
import stat
import threading
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import cv2
import numpy as np
import pytest

from benchmark.errors import DataError
from benchmark.io import default_stem, export_sequence, open_sequence
from benchmark.modalities.camera.io.image_folder import ImageFolder
from benchmark.modalities.camera.io.sequence_file import ImageSequenceFile, read_sequence_file, write_sequence_file
from benchmark.modalities.camera.io.video import VideoFile
from benchmark.modalities.camera.modality import CAMERA
from benchmark.modalities.camera.model import UNKNOWN_CABLE, CableState
from benchmark.modalities.sonar.io import SwathFile
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
    path = write_video(tmp_path / name)
    assert isinstance(open_sequence(path, BUILT_IN), VideoFile)


def write_video(path: Path) -> Path:
    writer = cv2.VideoWriter(str(path), cv2.VideoWriter_fourcc(*"MJPG"), 5.0, (16, 8), True)
    if not writer.isOpened():
        pytest.skip("this OpenCV build cannot write MJPG into .avi")
    writer.write(np.zeros((8, 16, 3), dtype=np.uint8))
    writer.release()
    return path


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


@pytest.mark.parametrize("order", [1, -1])
@pytest.mark.parametrize(("holds", "reader"), [(("left", "right"), "pairs"), (("left",), "folder"), ((), "folder")])
def test_a_folder_holding_a_reader_s_names_goes_to_it_before_the_plain_folder_reader(tmp_path, order, holds, reader):
    folder = tmp_path / "looks_like.scan"
    folder.mkdir()
    for name in holds:
        (folder / name).mkdir()
    stereo = modality("stereo", recording("pairs", folders=True, folder_holds=("left", "right")))
    assert open_sequence(folder, (*DISPATCH, stereo)[::order]) == Opened(reader, str(folder))


def test_a_folder_no_reader_takes_is_a_data_error(tmp_path):
    stereo = modality("stereo", recording("pairs", folders=True, folder_holds=("left", "right")))
    with pytest.raises(DataError, match=r"no registered reader opens this \(readers: the pairs reader\)"):
        open_sequence(tmp_path, (stereo,))


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
    modalities = {"camera": CAMERA, "sonar": SONAR, "stereo": STEREO, "scans": modality("scans")}
    message = r"s/1: scans sequences cannot be exported \(exportable: camera, sonar, stereo\)"
    with pytest.raises(DataError, match=message):
        export_sequence(Named("s/1", "scans"), tmp_path, modalities)
    with pytest.raises(DataError, match=r"s/1: lidar sequences cannot be exported"):
        export_sequence(Named("s/1", "lidar"), tmp_path, modalities)
    with pytest.raises(DataError, match=r"exportable: none"):
        export_sequence(Named("s/1", "scans"), tmp_path, {"scans": modality("scans")})
    assert list(tmp_path.iterdir()) == []


def test_default_stem_replaces_path_separators():
    assert default_stem("suite/seq") == "suite_seq"
    assert default_stem("a\\b/c") == "a_b_c"
    assert default_stem("") == "sequence"
    assert default_stem("..") == "sequence"


# ------------------------------------------------------------- paths that are not regular files
needs_fifo = pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="no named pipes on this platform")


def within(seconds: float, action: Callable[[], Any]) -> Any:
    """``action()``, in a daemon thread, so that a call that blocks fails the test instead of hanging it."""
    outcome: list[tuple[bool, Any]] = []

    def run() -> None:
        try:
            outcome.append((True, action()))
        except BaseException as exc:
            outcome.append((False, exc))

    thread = threading.Thread(target=run, daemon=True)
    thread.start()
    thread.join(seconds)
    assert outcome, f"still blocked after {seconds} s"
    ok, value = outcome[0]
    if not ok:
        raise value
    return value


@needs_fifo
@pytest.mark.parametrize("name", ["seq.txt", "labels", "pings.swaths", "clip.avi", "looks_like_a_folder"])
def test_open_sequence_refuses_a_fifo_without_opening_it(tmp_path, name):
    os.mkfifo(tmp_path / name)
    with pytest.raises(DataError, match=rf"{name}: it is a FIFO \(named pipe\), neither a file nor a folder"):
        within(5, lambda: open_sequence(tmp_path / name, BUILT_IN))


has_dev_null = os.path.exists("/dev/null") and stat.S_ISCHR(os.stat("/dev/null").st_mode)


@pytest.mark.skipif(not has_dev_null, reason="no /dev/null")
def test_open_sequence_refuses_a_device():
    with pytest.raises(DataError, match=r"/dev/null: it is a character device, neither a file nor a folder"):
        open_sequence("/dev/null", BUILT_IN)


@needs_fifo
@pytest.mark.parametrize(
    ("reader", "what"),
    [
        (ImageSequenceFile, "image sequence file"),
        (read_sequence_file, "image sequence file"),
        (SwathFile, "swath file"),
    ],
)
def test_file_readers_refuse_a_fifo_and_a_folder_without_opening_them(tmp_path, reader, what):
    os.mkfifo(tmp_path / "pipe")
    with pytest.raises(DataError, match=rf"pipe: cannot read {what}: it is a FIFO \(named pipe\), not a regular file"):
        within(5, lambda: reader(tmp_path / "pipe"))
    with pytest.raises(DataError, match=rf"cannot read {what}: it is a folder, not a regular file"):
        reader(tmp_path)


# ------------------------------------------------------------- identity of the sequences read from files
SWATHS = "# n_beams = 2\n# swath_angle_deg = 90\n# pipe_diameter_m = 0.5\n0.0 nan nan nan nan -1 1 10 10\n"


def sequence_file(folder: Path, make_image) -> Path:
    for name in ("a.png", "b.png"):
        make_image(folder / "frames" / name)
    path = folder / "seq.txt"
    write_sequence_file(path, [(CableState(1.5, 0.0, 20.0, 0.0), "frames/a.png"), (UNKNOWN_CABLE, "frames/b.png")])
    return path


def image_folder(folder: Path, make_image) -> Path:
    for name in ("a.png", "b.png"):
        make_image(folder / "frames" / name)
    return folder / "frames"


def swath_file(folder: Path, make_image) -> Path:
    path = folder / "pings.swaths"
    path.write_text(SWATHS, encoding="utf-8")
    return path


def video(folder: Path, make_image) -> Path:
    return write_video(folder / "clip.avi")


DATASETS = {"sequence file": sequence_file, "image folder": image_folder, "swath file": swath_file, "video": video}


@pytest.fixture(params=list(DATASETS))
def dataset(request, tmp_path, make_image) -> Path:
    """One dataset of each file-backed kind, in ``tmp_path/dir``."""
    folder = tmp_path / "dir"
    folder.mkdir()
    return DATASETS[request.param](folder, make_image)


def key_of(path: Path | str) -> str:
    return open_sequence(path, BUILT_IN).identity.key


def shift_mtime(path: Path, seconds: int = 10) -> None:
    status = path.stat()
    os.utime(path, ns=(status.st_atime_ns, status.st_mtime_ns + seconds * 1_000_000_000))


def test_two_spellings_of_a_dataset_have_one_key_and_their_own_names(dataset, monkeypatch):
    monkeypatch.chdir(dataset.parent)
    here = open_sequence(dataset.name, BUILT_IN)
    there = open_sequence(f"../dir/{dataset.name}", BUILT_IN)
    assert here.identity.key == there.identity.key
    for sequence, name in ((here, dataset.name), (there, f"../dir/{dataset.name}")):
        identity, info = sequence.identity, sequence.info
        assert (identity.name, identity.modality) == (info.name, info.modality) == (name, info.modality)
        assert identity.source == dataset.resolve().as_posix()


CHANGES: dict[str, Callable[[Path], object]] = {
    "sequence file": lambda path: shift_mtime(path.parent / "frames" / "a.png"),
    "image folder": lambda path: shift_mtime(path / "a.png"),
    "swath file": lambda path: path.write_text(SWATHS.replace("-1 1 10", "-1 2 10"), encoding="utf-8"),
    "video": lambda path: shift_mtime(path),
}
"""Per kind of dataset, a change that gives it a new identity."""


@pytest.mark.parametrize("kind", list(DATASETS))
def test_a_copy_keeps_the_identity_taken_when_the_dataset_was_opened(tmp_path, make_image, kind):
    path = DATASETS[kind](tmp_path, make_image)
    sequence = open_sequence(path, BUILT_IN)
    CHANGES[kind](path)
    copy = pickle.loads(pickle.dumps(sequence))
    assert copy.identity == sequence.identity
    assert key_of(path) != sequence.identity.key


@pytest.mark.parametrize("kind", ["sequence file", "swath file"])
def test_editing_the_file_changes_the_key_even_with_its_size_and_time_kept(tmp_path, make_image, kind):
    path = DATASETS[kind](tmp_path, make_image)
    before = key_of(path)
    status = path.stat()
    text = path.read_text(encoding="utf-8")
    edited = text.replace("1.5", "2.5") if kind == "sequence file" else text.replace("-1 1 10", "-1 2 10")
    assert edited != text and len(edited) == len(text)
    path.write_text(edited, encoding="utf-8")
    os.utime(path, ns=(status.st_atime_ns, status.st_mtime_ns))
    assert key_of(path) != before


@pytest.mark.parametrize("kind", ["sequence file", "image folder"])
def test_touching_or_replacing_an_image_changes_the_key(tmp_path, make_image, kind):
    path = DATASETS[kind](tmp_path, make_image)
    image = tmp_path / "frames" / "b.png"
    keys = [key_of(path)]
    shift_mtime(image)
    keys.append(key_of(path))
    status = image.stat()
    make_image(image, width=20)
    os.utime(image, ns=(status.st_atime_ns, status.st_mtime_ns))
    assert image.stat().st_size != status.st_size
    keys.append(key_of(path))
    assert len(set(keys)) == 3


@pytest.mark.parametrize("kind", ["sequence file", "image folder"])
def test_files_beside_the_images_do_not_change_the_key(tmp_path, make_image, kind):
    path = DATASETS[kind](tmp_path, make_image)
    before = key_of(path)
    (tmp_path / "frames" / "notes.txt").write_text("seen on the dive", encoding="utf-8")
    assert key_of(path) == before


def test_a_video_is_known_by_its_size_and_modification_time(tmp_path, make_image):
    path = video(tmp_path, make_image)
    before = key_of(path)
    shift_mtime(path)
    assert key_of(path) != before


@needs_fifo
def test_opening_and_naming_a_sequence_open_no_image(tmp_path):
    os.mkfifo(tmp_path / "pipe.png")
    path = tmp_path / "seq.txt"
    write_sequence_file(path, [(UNKNOWN_CABLE, "pipe.png")])
    sequence = within(5, lambda: open_sequence(path, BUILT_IN))
    identity = within(5, lambda: sequence.identity)
    assert (identity.name, identity.modality, identity.source) == (str(path), "camera", path.resolve().as_posix())
