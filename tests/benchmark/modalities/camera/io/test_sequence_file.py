"""Image sequence files (conventions.md section 2): parsing, writing, and the lazy sequence."""

from __future__ import annotations

import math
import pickle
import tempfile
from pathlib import Path

import cv2
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from benchmark.errors import DataError
from benchmark.modalities.camera.io import image_list as image_list_module
from benchmark.modalities.camera.io.sequence_file import (
    HEADER,
    ImageSequenceFile,
    read_sequence_file,
    write_sequence_file,
)
from benchmark.modalities.camera.model import UNKNOWN_CABLE, CableState, CameraTruth


def _bits(cable: CableState) -> list[str]:
    """Exact, nan- and sign-aware view of a state for equality checks."""
    return [repr(v) for v in (cable.d, cable.alpha, cable.w, cable.beta)]


finite = st.floats(allow_nan=False, allow_infinity=False)
cables = st.one_of(st.just(UNKNOWN_CABLE), st.builds(CableState, finite, finite, finite, finite))
name_chars = st.sampled_from("abcXYZ019 _-#.()äé")
names = st.text(name_chars, min_size=1, max_size=12).map(lambda s: f"f{s}x.png")
places = st.sampled_from(["relative", "sub", "absolute_inside", "absolute_outside"])


@settings(max_examples=60, deadline=None)
@given(st.lists(st.tuples(cables, names, places), min_size=1, max_size=6))
def test_write_then_read_round_trips_states_and_paths(entries):
    with tempfile.TemporaryDirectory() as tmp:
        root = Path(tmp)
        folder = root / "data set"
        folder.mkdir()
        rows, expected_images = [], []
        for cable, name, place in entries:
            if place == "relative":
                given_path, expected = name, folder / name
            elif place == "sub":
                given_path, expected = f"sub dir/{name}", folder / "sub dir" / name
            elif place == "absolute_inside":
                given_path = expected = folder / "abs" / name
            else:
                given_path = expected = root / "elsewhere" / name
            rows.append((cable, given_path))
            expected_images.append(expected.resolve())
        path = folder / "seq.txt"
        write_sequence_file(path, rows)
        read = read_sequence_file(path)
    assert [_bits(r.cable) for r in read] == [_bits(c) for c, _, _ in entries]
    assert [r.image for r in read] == expected_images
    assert [r.line for r in read] == list(range(2, len(entries) + 2))


def test_writer_starts_with_the_thesis_header_and_writes_nan(tmp_path):
    path = tmp_path / "seq.txt"
    write_sequence_file(path, [(CableState(3.5, -0.082, 21.5, 0.043), "a.png"), (UNKNOWN_CABLE, "b.png")])
    lines = path.read_text(encoding="utf-8").splitlines()
    assert lines[0] == "# CableDistance CableAngle CableWidth CableSkew # Filename"
    assert lines[0] == HEADER
    assert lines[1].split() == ["3.5", "-0.082", "21.5", "0.043", "#", "a.png"]
    assert lines[2].split() == ["nan", "nan", "nan", "nan", "#", "b.png"]


def test_writer_makes_paths_inside_the_folder_relative_and_keeps_others_absolute(tmp_path):
    folder = tmp_path / "out"
    folder.mkdir()
    inside = folder / "frames" / "x 1.png"
    outside = tmp_path / "other" / "y.png"
    write_sequence_file(folder / "seq.txt", [(UNKNOWN_CABLE, inside), (UNKNOWN_CABLE, outside)])
    text = (folder / "seq.txt").read_text(encoding="utf-8").splitlines()
    assert text[1].endswith("# frames/x 1.png")
    assert text[2].endswith(f"# {outside.as_posix()}")


def test_relative_paths_resolve_against_the_sequence_file_folder(tmp_path, monkeypatch, make_image):
    data = tmp_path / "data"
    pixels = make_image(data / "img" / "x.png")
    (data / "seq.txt").write_text("1 0.1 20 0.01 # img/x.png\n", encoding="utf-8")
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    monkeypatch.chdir(elsewhere)
    for given_path in (data / "seq.txt", Path("../data/seq.txt")):
        (row,) = read_sequence_file(given_path)
        assert row.image == (data / "img" / "x.png").resolve()
        assert row.image.is_absolute()
    sequence = ImageSequenceFile(Path("../data/seq.txt"))
    monkeypatch.chdir(tmp_path)
    (frame,) = sequence.frames()
    assert np.array_equal(frame.observation, pixels)


def test_absolute_paths_are_kept(tmp_path):
    image = (tmp_path / "somewhere" / "S1_000.DIB").resolve()
    (tmp_path / "labels").mkdir()
    path = tmp_path / "labels" / "seq.seq"
    path.write_text(f"3.5 -0.082 21.5 0.043 # {image}\n", encoding="utf-8")
    (row,) = read_sequence_file(path)
    assert row.image == image


def test_comments_blank_lines_and_crlf_are_skipped(tmp_path):
    path = tmp_path / "seq.txt"
    path.write_bytes(
        b"# CableDistance CableAngle CableWidth CableSkew # Filename\r\n"
        b"\r\n"
        b"   # an indented comment 1 2 3 4 # not_a_row.png\r\n"
        b"3.5 -0.082 21.5 0.043 # a.png\r\n"
        b"   \t \r\n"
        b"\t5.2 -0.078 24.5 0.052   #   b.png  \r\n"
    )
    rows = read_sequence_file(path)
    assert [r.line for r in rows] == [4, 6]
    assert [r.image.name for r in rows] == ["a.png", "b.png"]
    assert rows[1].cable == CableState(5.2, -0.078, 24.5, 0.052)


def test_text_after_the_first_hash_is_the_path_with_spaces_and_hashes(tmp_path):
    path = tmp_path / "seq.txt"
    path.write_text("1 2 3 4 #  my dir/frame #1 # b.png  \n", encoding="utf-8")
    (row,) = read_sequence_file(path)
    assert row.image == (tmp_path / "my dir" / "frame #1 # b.png").resolve()


def test_nan_rows_in_any_letter_case_are_unknown_truth(tmp_path):
    path = tmp_path / "seq.txt"
    path.write_text("NaN nan NAN -nan # a.png\n", encoding="utf-8")
    (row,) = read_sequence_file(path)
    assert not row.cable.is_known
    assert all(math.isnan(v) for v in row.cable.as_array())


def test_values_other_tools_write_are_not_over_validated(tmp_path):
    path = tmp_path / "seq.txt"
    path.write_text("-400 7.0 0 -0.3 # a.png\n1e3 -1E-3 -5 0 # b.png\n", encoding="utf-8")
    rows = read_sequence_file(path)
    assert rows[0].cable == CableState(-400.0, 7.0, 0.0, -0.3)
    assert rows[1].cable == CableState(1000.0, -0.001, -5.0, 0.0)


@pytest.mark.parametrize(
    ("row", "reason"),
    [
        ("1 2 3 # a.png", "4 numbers"),
        ("1 2 3 4 5 # a.png", "4 numbers"),
        ("1 two 3 4 # a.png", "not a number"),
        ("1 2 3 4 a.png", "'#'"),
        ("1 2 3 4", "'#'"),
        ("1 2 3 4 #", "file name"),
        ("1 2 3 4 #   ", "file name"),
        ("nan 2 3 4 # a.png", "nan"),
        ("1 2 nan nan # a.png", "nan"),
        ("inf 2 3 4 # a.png", "infinite"),
        ("1 2 3 -Infinity # a.png", "infinite"),
    ],
)
def test_malformed_rows_name_file_and_line(tmp_path, row, reason):
    path = tmp_path / "labels.txt"
    path.write_text(f"{HEADER}\n0 0 10 0 # ok.png\n\n{row}\n0 0 10 0 # ok2.png\n", encoding="utf-8")
    with pytest.raises(DataError) as error:
        read_sequence_file(path)
    message = str(error.value)
    assert f"{path}:4:" in message
    assert reason in message
    with pytest.raises(DataError, match="labels.txt:4:"):
        ImageSequenceFile(path)


def test_missing_sequence_file_is_named(tmp_path):
    path = tmp_path / "nope.txt"
    with pytest.raises(DataError, match="nope.txt"):
        read_sequence_file(path)
    with pytest.raises(DataError, match="nope.txt"):
        ImageSequenceFile(path)


@pytest.mark.parametrize("text", ["", "\n\n", f"{HEADER}\n# only comments\n"])
def test_file_without_data_rows_is_an_error(tmp_path, text):
    path = tmp_path / "empty.txt"
    path.write_text(text, encoding="utf-8")
    with pytest.raises(DataError, match="empty.txt.*no data rows"):
        read_sequence_file(path)


def test_a_file_of_more_lines_than_a_sequence_may_hold_is_refused_before_any_row_is_parsed(tmp_path, monkeypatch):
    monkeypatch.setattr("benchmark.modalities.camera.io.sequence_file.MAX_LINES", 100)
    path = tmp_path / "huge.txt"
    path.write_text("1 0 6 0 # frame.png\n" * 101, encoding="utf-8")
    monkeypatch.setattr("benchmark.modalities.camera.io.sequence_file._parse_row", None)  # never reached
    with pytest.raises(DataError, match="huge.txt: 101 lines, more than the 100 an image sequence file may hold"):
        read_sequence_file(path)


def test_an_image_path_that_is_a_loop_of_links_is_named_with_its_line(tmp_path):
    (tmp_path / "loop.png").symlink_to(tmp_path / "loop.png")
    path = tmp_path / "seq.txt"
    path.write_text("1 0 6 0 # loop.png\n", encoding="utf-8")
    with pytest.raises(DataError, match="seq.txt:1: invalid image path 'loop.png': .*a loop of symbolic links"):
        read_sequence_file(path)


def test_non_text_file_is_an_error_naming_it(tmp_path):
    path = tmp_path / "binary.seq"
    path.write_bytes(b"\xff\xfe\x00\x81" * 10)
    with pytest.raises(DataError, match="binary.seq"):
        read_sequence_file(path)


@pytest.mark.parametrize(
    ("cable", "image", "reason"),
    [
        (CableState(1.0, math.nan, 3.0, 4.0), "a.png", "nan"),
        (CableState(1.0, math.inf, 3.0, 4.0), "a.png", "infinite"),
        (UNKNOWN_CABLE, "a\nb.png", "line break"),
        (UNKNOWN_CABLE, "a.png ", "white space"),
    ],
)
def test_writer_rejects_rows_the_format_cannot_hold_and_leaves_no_file(tmp_path, cable, image, reason):
    path = tmp_path / "seq.txt"
    with pytest.raises(DataError, match=reason) as error:
        write_sequence_file(path, [(UNKNOWN_CABLE, "first.png"), (cable, image)])
    assert "row 2" in str(error.value)
    assert list(tmp_path.iterdir()) == []


def test_writer_keeps_an_old_file_when_the_rows_fail(tmp_path):
    path = tmp_path / "seq.txt"
    write_sequence_file(path, [(UNKNOWN_CABLE, "old.png")])

    def rows():
        yield UNKNOWN_CABLE, "new.png"
        raise RuntimeError("renderer crashed")

    with pytest.raises(RuntimeError):
        write_sequence_file(path, rows())
    assert [r.image.name for r in read_sequence_file(path)] == ["old.png"]
    assert [p.name for p in tmp_path.iterdir()] == ["seq.txt"]


# --- ImageSequenceFile --------------------------------------------------------------------------


def _labelled(tmp_path: Path, make_image, n: int = 3, width: int = 12, height: int = 8):
    cables = [CableState(1.5 * i, -0.1 * i, 20.0 + i, 0.01 * i) for i in range(n)]
    cables[1] = UNKNOWN_CABLE
    images = [make_image(tmp_path / "frames" / f"im {i}.png", width, height) for i in range(n)]
    path = tmp_path / "seq.txt"
    write_sequence_file(path, [(c, f"frames/im {i}.png") for i, c in enumerate(cables)])
    return path, cables, images


def test_frames_carry_grey_images_and_truth(tmp_path, make_image):
    path, cables, images = _labelled(tmp_path, make_image, width=12, height=8)
    sequence = ImageSequenceFile(str(path))
    info = sequence.info
    assert info.name == str(path)
    assert info.modality == "camera"
    assert info.n_frames == 3
    assert info.frame_size == (12, 8)
    assert info.frame_interval_s is None
    assert info.extra["source"] == str(path)
    frames = list(sequence.frames())
    assert [f.index for f in frames] == [0, 1, 2]
    assert [f.time_s for f in frames] == [0.0, 1.0, 2.0]
    for frame, cable, image in zip(frames, cables, images, strict=True):
        assert frame.observation.dtype == np.uint8
        assert np.array_equal(frame.observation, image)
        assert isinstance(frame.truth, CameraTruth)
        assert _bits(frame.truth.cable) == _bits(cable)
        assert frame.navigation is None
    assert frames[1].truth.cable.is_known is False


def test_frame_interval_sets_time_stamps(tmp_path, make_image):
    path, _, _ = _labelled(tmp_path, make_image)
    sequence = ImageSequenceFile(path, frame_interval_s=0.04)
    assert sequence.info.frame_interval_s == 0.04
    assert [f.time_s for f in sequence] == [0.0, 0.04, 0.08]
    with pytest.raises(ValueError, match="frame_interval_s"):
        ImageSequenceFile(path, frame_interval_s=0.0)


def test_colour_images_are_read_as_grey(tmp_path):
    grey = np.arange(6 * 10, dtype=np.uint8).reshape(6, 10) * 4
    assert cv2.imwrite(str(tmp_path / "c.bmp"), np.dstack([grey, grey, grey]))
    (tmp_path / "seq.txt").write_text("0 0 1 0 # c.bmp\n", encoding="utf-8")
    (frame,) = ImageSequenceFile(tmp_path / "seq.txt").frames()
    assert frame.observation.shape == (6, 10)
    assert np.array_equal(frame.observation, grey)


def test_missing_image_fails_on_iteration_naming_image_and_line(tmp_path, make_image):
    make_image(tmp_path / "a.png")
    path = tmp_path / "seq.txt"
    path.write_text(f"{HEADER}\n0 0 1 0 # a.png\n# gap\n0 0 1 0 # missing one.png\n", encoding="utf-8")
    sequence = ImageSequenceFile(path)
    frames = sequence.frames()
    next(frames)
    with pytest.raises(DataError) as error:
        next(frames)
    assert f"{path}:4:" in str(error.value)
    assert "missing one.png" in str(error.value)


@pytest.mark.parametrize("content", [b"not an image at all" * 5, b"", b"\x89PNG\r\n\x1a\n" + b"\x00" * 40])
def test_corrupt_image_fails_on_iteration_naming_it(tmp_path, make_image, content):
    make_image(tmp_path / "good.png")
    (tmp_path / "bad.png").write_bytes(content)
    path = tmp_path / "seq.txt"
    path.write_text("0 0 1 0 # good.png\n0 0 1 0 # bad.png\n", encoding="utf-8")
    with pytest.raises(DataError, match=r"seq.txt:2:.*bad.png"):
        list(ImageSequenceFile(path))


def test_image_of_another_size_fails_naming_it(tmp_path, make_image):
    make_image(tmp_path / "a.png", 12, 8)
    make_image(tmp_path / "b.png", 8, 12)
    path = tmp_path / "seq.txt"
    path.write_text("0 0 1 0 # a.png\n0 0 1 0 # b.png\n", encoding="utf-8")
    with pytest.raises(DataError, match=r"seq.txt:2:.*b.png.*8x12.*12x8"):
        list(ImageSequenceFile(path))


def test_info_names_a_missing_first_image(tmp_path):
    path = tmp_path / "seq.txt"
    path.write_text("0 0 1 0 # first.png\n", encoding="utf-8")
    sequence = ImageSequenceFile(path)
    assert "seq.txt" in repr(sequence)
    with pytest.raises(DataError, match=r"seq.txt:1:.*first.png"):
        _ = sequence.info


def test_construction_reads_no_image_and_info_reads_one(tmp_path, make_image, monkeypatch):
    path, _, _ = _labelled(tmp_path, make_image)
    calls = []
    real = image_list_module.read_grey

    def counting(image_path, **kwargs):
        calls.append(image_path)
        return real(image_path, **kwargs)

    monkeypatch.setattr(image_list_module, "read_grey", counting)
    sequence = ImageSequenceFile(path)
    assert calls == []
    _ = sequence.info
    _ = sequence.info
    assert len(calls) == 1
    list(sequence.frames())
    assert len(calls) == 4


def test_construction_succeeds_before_the_images_exist(tmp_path, make_image):
    path = tmp_path / "seq.txt"
    write_sequence_file(path, [(UNKNOWN_CABLE, "later.png")])
    sequence = ImageSequenceFile(path)
    with pytest.raises(DataError, match="later.png"):
        list(sequence)
    pixels = make_image(tmp_path / "later.png")
    (frame,) = sequence.frames()
    assert np.array_equal(frame.observation, pixels)


def test_pickles_without_images_and_frames_still_work(tmp_path, make_image):
    path, cables, images = _labelled(tmp_path, make_image, width=60, height=40)
    sequence = ImageSequenceFile(path)
    _ = sequence.info
    data = pickle.dumps(sequence)
    assert len(data) < images[0].nbytes
    copy = pickle.loads(data)
    assert copy.info == sequence.info
    frames = list(copy.frames())
    assert all(np.array_equal(f.observation, i) for f, i in zip(frames, images, strict=True))
    assert [_bits(f.truth.cable) for f in frames] == [_bits(c) for c in cables]
    assert [r.line for r in copy.rows] == [2, 3, 4]

