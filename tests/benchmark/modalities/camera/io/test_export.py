"""Exporting a camera sequence as PNG frames plus an image sequence file, and reading it back."""

from __future__ import annotations

import re
from collections.abc import Iterator
from pathlib import Path

import numpy as np
import pytest

from benchmark.errors import DataError
from benchmark.io import default_stem
from benchmark.io import export_sequence as export_by_modality
from benchmark.io import open_sequence as open_by_modality
from benchmark.modalities.camera.io.export import export_camera_sequence
from benchmark.modalities.camera.io.sequence_file import ImageSequenceFile
from benchmark.modalities.camera.modality import CAMERA
from benchmark.modalities.camera.model import UNKNOWN_CABLE, CableState, CameraTruth
from benchmark.modalities.sonar.modality import SONAR
from benchmark.modalities.stereo.modality import STEREO
from benchmark.model import Frame, Sequence, SequenceInfo

MODALITIES = {"camera": CAMERA, "sonar": SONAR, "stereo": STEREO}


def export_sequence(sequence: Sequence, out_dir: Path | str, *, stem: str | None = None) -> Path:
    """Export through benchmark.io with the built-in modalities, as ``trackbench make-dataset`` does."""
    return export_by_modality(sequence, out_dir, MODALITIES, stem=stem)


def open_sequence(path: Path) -> Sequence:
    return open_by_modality(path, MODALITIES.values())


class TinySequence(Sequence):
    """Three random grey frames with known truth, one of them unlabelled."""

    def __init__(self, name: str = "tiny/one", seed: int = 7, modality: str = "camera") -> None:
        self.name, self.seed, self.modality = name, seed, modality
        self.cables = [CableState(2.5, -0.0821, 21.25, 0.043), UNKNOWN_CABLE, CableState(-3.0, 0.1, 18.0, 0.0)]
        self.produced: list[int] = []
        self.written_before: list[bool] = []
        self.out: Path | None = None

    @property
    def info(self) -> SequenceInfo:
        return SequenceInfo(name=self.name, modality=self.modality, n_frames=3, frame_size=(10, 6))

    def images(self) -> list[np.ndarray]:
        rng = np.random.default_rng(self.seed)
        return [rng.integers(0, 256, size=(6, 10), dtype=np.uint8) for _ in range(3)]

    def frames(self) -> Iterator[Frame]:
        for index, (image, cable) in enumerate(zip(self.images(), self.cables, strict=True)):
            if self.out is not None and index:
                previous = self.out / default_stem(self.name) / f"frame_{index - 1:05d}.png"
                self.written_before.append(previous.is_file())
            self.produced.append(index)
            yield Frame(index=index, observation=image, truth=CameraTruth(cable=cable), time_s=index / 25)


def test_export_round_trips_through_open_sequence(tmp_path):
    sequence = TinySequence()
    path = export_sequence(sequence, tmp_path / "out")
    assert path == tmp_path / "out" / "tiny_one.txt"
    opened = open_sequence(path)
    assert isinstance(opened, ImageSequenceFile)
    frames = list(opened.frames())
    assert len(frames) == 3
    for frame, image, cable in zip(frames, sequence.images(), sequence.cables, strict=True):
        assert np.array_equal(frame.observation, image)
        assert np.array_equal(frame.truth.cable.as_array(), cable.as_array(), equal_nan=True)
    assert opened.info.frame_size == (10, 6)


def test_export_writes_relative_paths_so_the_folder_can_move(tmp_path):
    out = tmp_path / "out"
    path = export_sequence(TinySequence(), out, stem="S1")
    text = path.read_text(encoding="utf-8")
    assert str(tmp_path) not in text
    assert [line.split("#", 1)[1].strip() for line in text.splitlines()[1:]] == [
        "S1/frame_00000.png",
        "S1/frame_00001.png",
        "S1/frame_00002.png",
    ]
    moved = tmp_path / "moved"
    out.rename(moved)
    assert len(list(open_sequence(moved / "S1.txt"))) == 3


def test_export_streams_frame_by_frame(tmp_path):
    sequence = TinySequence()
    sequence.out = tmp_path
    export_sequence(sequence, tmp_path)
    assert sequence.produced == [0, 1, 2]
    assert sequence.written_before == [True, True]


@pytest.mark.parametrize("stem", ["", "a/b", "..", "a\\b"])
def test_stems_with_separators_are_refused(tmp_path, stem):
    with pytest.raises(ValueError, match="stem"):
        export_sequence(TinySequence(), tmp_path, stem=stem)


def test_png_write_failure_is_a_data_error_and_leaves_no_sequence_file(tmp_path):
    (tmp_path / "S1" / "frame_00001.png").mkdir(parents=True)
    with pytest.raises(DataError, match="frame 1.*frame_00001.png"):
        export_sequence(TinySequence(), tmp_path, stem="S1")
    assert not (tmp_path / "S1.txt").exists()


def test_exporting_under_a_file_is_a_data_error_naming_the_output_folder(tmp_path):
    blocker = tmp_path / "blocker"
    blocker.write_text("mine", encoding="utf-8")
    for out in (blocker / "sub", blocker):
        with pytest.raises(DataError, match=rf"^{re.escape(str(out))}: cannot create folder"):
            export_sequence(TinySequence(), out)
    assert [item.name for item in tmp_path.iterdir()] == ["blocker"]
    assert blocker.read_text(encoding="utf-8") == "mine"


def test_sequences_of_a_modality_without_exporter_are_refused(tmp_path):
    with pytest.raises(DataError, match="tiny/one: lidar sequences cannot be exported.*camera"):
        export_sequence(TinySequence(modality="lidar"), tmp_path)
    assert list(tmp_path.iterdir()) == []


def test_the_camera_exporter_writes_under_the_stem_it_is_given(tmp_path):
    path = export_camera_sequence(TinySequence(), tmp_path / "out", "given")
    assert path == tmp_path / "out" / "given.txt"
    assert sorted(p.name for p in (tmp_path / "out" / "given").iterdir()) == [f"frame_0000{i}.png" for i in range(3)]
    assert CAMERA.exporter is export_camera_sequence


class OddSequence(TinySequence):
    """A camera sequence gone wrong: no frames, a truth of another modality, or images that change size."""

    def __init__(self, fault: str) -> None:
        super().__init__(name="odd/one")
        self.fault = fault

    def frames(self) -> Iterator[Frame]:
        if self.fault == "empty":
            return
        image = np.zeros((6, 10), dtype=np.uint8)
        yield Frame(0, image, CameraTruth(self.cables[0]))
        if self.fault == "truth":
            yield Frame(1, image, "a sonar truth")
        else:
            yield Frame(1, np.zeros((7, 10), dtype=np.uint8), None)


@pytest.mark.parametrize(
    ("fault", "message"),
    [
        ("empty", "odd/one: the sequence has no frames to export"),
        ("truth", "odd/one: frame 1: truth is a str, not a CameraTruth"),
        ("size", "odd/one: frame 1: image is 10x7 px, but the first frame is 10x6 px"),
    ],
)
def test_what_the_camera_exporter_cannot_write_is_a_data_error_naming_the_frame(tmp_path, fault, message):
    with pytest.raises(DataError, match=message):
        export_camera_sequence(OddSequence(fault), tmp_path, "odd")
    assert not (tmp_path / "odd.txt").exists()
