"""Malformed dataset files end in a DataError, never in another exception.

The camera's image sequence files and the sonar's swath files are fed to
:func:`benchmark.io.open_sequence` as arbitrary bytes, and as valid files
(written by the project's own writers) with mutations: tokens deleted,
duplicated or replaced by ``inf``, ``nan``, ``1e400``, huge numbers, empty
text or bytes that are not UTF-8; lines dropped or duplicated; header values
changed.  Whatever is opened is named (``identity``), described (``info``)
and iterated to its last frame.
"""

from __future__ import annotations

import functools
import math
import tempfile
from collections.abc import Iterator
from pathlib import Path

import cv2
import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from benchmark.errors import DataError
from benchmark.io import open_sequence
from benchmark.modalities.camera.io.sequence_file import write_sequence_file
from benchmark.modalities.camera.modality import CAMERA
from benchmark.modalities.camera.model import UNKNOWN_CABLE, CableState
from benchmark.modalities.sonar.io import write_swath_file
from benchmark.modalities.sonar.modality import SONAR
from benchmark.modalities.sonar.model import SonarCalibration, SonarTruth, Swath
from benchmark.model import Frame, Sequence, SequenceInfo

N_FRAMES = 4
IMAGE_NAMES = [f"frames/f{index}.png" for index in range(N_FRAMES)]
CALIBRATION = SonarCalibration(n_beams=3, swath_angle=math.radians(120.0), range_sigma_m=0.05, pipe_diameter_m=0.9)

REPLACEMENTS = [
    b"inf", b"-inf", b"+inf", b"nan", b"-nan", b"1e400", b"-1e400", b"9" * 400, b"1e12", b"0", b"-1", b"2.5",
    b"", b"#", b"=", b"x", b"\xff", b"\xc3", b"\x80abc", b"\x00", b"1_0", b"0x10", b"..", b"/",
]  # fmt: skip
"""What a mutated token may become."""

SETTINGS = settings(max_examples=150, deadline=None)


class SmallPings(Sequence):
    """Three pings of a three-beam sonar, one unlabelled, one beam without a return."""

    @property
    def info(self) -> SequenceInfo:
        return SequenceInfo("fuzz/pings", "sonar", 3, frame_interval_s=0.25, calibration=CALIBRATION)

    def frames(self) -> Iterator[Frame]:
        for index in range(3):
            across = np.array([-5.0, 0.1 * index, 5.0])
            depth = np.array([15.0, math.nan if index == 1 else 14.5, 15.2])
            truth = None if index == 2 else SonarTruth(0.1 * index, 14.6, 0.2, 0.3)
            yield Frame(index, Swath(across, depth), truth, time_s=0.25 * index)


@functools.cache
def base_files() -> tuple[bytes, bytes, tuple[bytes, ...]]:
    """A valid image sequence file, a valid swath file and the PNG images the sequence file names."""
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        (folder / "frames").mkdir()
        rng = np.random.default_rng(5)
        for name in IMAGE_NAMES:
            assert cv2.imwrite(str(folder / name), rng.integers(0, 256, size=(12, 16), dtype=np.uint8))
        cables = [CableState(1.5 * index, -0.05 * index, 9.0, 0.02) for index in range(N_FRAMES)]
        cables[2] = UNKNOWN_CABLE
        write_sequence_file(folder / "seq.txt", zip(cables, IMAGE_NAMES, strict=True))
        write_swath_file(SmallPings(), folder / "pings.swaths")
        images = tuple((folder / name).read_bytes() for name in IMAGE_NAMES)
        return (folder / "seq.txt").read_bytes(), (folder / "pings.swaths").read_bytes(), images


def read_everything(content: bytes, name: str) -> None:
    """Open ``content`` as the file ``name`` beside the base images and read all of it; DataError is fine."""
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        (folder / "frames").mkdir()
        for image_name, image in zip(IMAGE_NAMES, base_files()[2], strict=True):
            (folder / image_name).write_bytes(image)
        path = folder / name
        path.write_bytes(content)
        try:
            sequence = open_sequence(path, [CAMERA, SONAR])
            assert sequence.identity.name == str(path)
            _ = sequence.info
            n_frames = sum(1 for _ in sequence.frames())
        except DataError as error:
            assert str(error)
        else:
            assert n_frames == sequence.info.n_frames


Mutation = tuple[str, int, int, bytes]
"""What to do, which line, which token (both taken modulo the counts), and the new token."""

mutations = st.lists(
    st.tuples(
        st.sampled_from(["delete", "duplicate", "replace", "header value", "drop line", "duplicate line", "insert"]),
        st.integers(0, 1000),
        st.integers(0, 1000),
        st.sampled_from(REPLACEMENTS),
    ),
    min_size=1,
    max_size=4,
)


def mutated(content: bytes, changes: list[Mutation]) -> bytes:
    """``content`` with each change applied in turn to its lines and their space-separated tokens."""
    lines = content.split(b"\n")
    for action, line_at, token_at, new in changes:
        if not lines:
            break
        line = line_at % len(lines)
        if action == "drop line":
            del lines[line]
            continue
        if action == "duplicate line":
            lines.insert(line, lines[line])
            continue
        if action == "header value":
            headers = [index for index, text in enumerate(lines) if b"=" in text]
            line = headers[line_at % len(headers)] if headers else line
        tokens = lines[line].split(b" ")
        token = token_at % len(tokens)
        if action == "delete":
            del tokens[token]
        elif action == "duplicate":
            tokens.insert(token, tokens[token])
        elif action == "insert":
            tokens.insert(token, new)
        else:
            tokens[-1 if action == "header value" else token] = new
        lines[line] = b" ".join(tokens)
    return b"\n".join(lines)


def test_the_base_files_are_valid():
    sequence_file, swath_file, _ = base_files()
    for content, name, n_frames in ((sequence_file, "seq.txt", N_FRAMES), (swath_file, "pings.swaths", 3)):
        with tempfile.TemporaryDirectory() as tmp:
            folder = Path(tmp)
            (folder / "frames").mkdir()
            for image_name, image in zip(IMAGE_NAMES, base_files()[2], strict=True):
                (folder / image_name).write_bytes(image)
            (folder / name).write_bytes(content)
            assert len(list(open_sequence(folder / name, [CAMERA, SONAR]).frames())) == n_frames


@SETTINGS
@given(content=st.binary(max_size=600), name=st.sampled_from(["seq.txt", "pings.swaths", "labels"]))
def test_arbitrary_bytes_open_or_fail_with_a_data_error(content, name):
    read_everything(content, name)


@SETTINGS
@given(changes=mutations)
def test_mutated_image_sequence_files_open_or_fail_with_a_data_error(changes):
    read_everything(mutated(base_files()[0], changes), "seq.txt")


@SETTINGS
@given(changes=mutations)
def test_mutated_swath_files_open_or_fail_with_a_data_error(changes):
    read_everything(mutated(base_files()[1], changes), "pings.swaths")
