"""Swath files: writing a sonar sequence ping by ping and reading it back."""

from __future__ import annotations

import dataclasses
import math
import pickle
import re
from collections.abc import Iterator

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from benchmark.errors import DataError
from benchmark.io import export_sequence, open_sequence
from benchmark.modalities.camera.modality import CAMERA
from benchmark.modalities.sonar.io import SWATH_SUFFIX, SwathFile, export_swath_file, write_swath_file
from benchmark.modalities.sonar.modality import SONAR
from benchmark.modalities.sonar.model import SonarCalibration, SonarTruth, Swath
from benchmark.model import Frame, Sequence, SequenceInfo

MODALITIES = {"camera": CAMERA, "sonar": SONAR}

CALIBRATION = SonarCalibration(n_beams=5, swath_angle=math.radians(120.0), range_sigma_m=0.05, pipe_diameter_m=0.9)


class PingSequence(Sequence):
    """A few pings of random returns, some beams missing, one ping unlabelled."""

    def __init__(self, pings: list[tuple[np.ndarray, np.ndarray, SonarTruth | None]], modality: str = "sonar") -> None:
        self.pings, self.modality = pings, modality

    @property
    def info(self) -> SequenceInfo:
        n_pings = len(self.pings)
        return SequenceInfo("sonar/tiny", self.modality, n_pings, frame_interval_s=0.25, calibration=CALIBRATION)

    def frames(self) -> Iterator[Frame]:
        for index, (across, depth, truth) in enumerate(self.pings):
            yield Frame(index, Swath(across, depth), truth, time_s=0.25 * index)


def random_pings(seed: int, n: int = 3) -> list[tuple[np.ndarray, np.ndarray, SonarTruth | None]]:
    rng = np.random.default_rng(seed)
    pings = []
    for k in range(n):
        across = np.sort(rng.uniform(-30.0, 30.0, CALIBRATION.n_beams))
        depth = rng.uniform(10.0, 20.0, CALIBRATION.n_beams)
        missing = rng.random(CALIBRATION.n_beams) < 0.3
        across[missing] = depth[missing] = math.nan
        truth = None if k == 1 else SonarTruth(*rng.uniform(0.1, 15.0, 4))
        pings.append((across, depth, truth))
    return pings


def assert_same_frames(read: Sequence, written: Sequence) -> None:
    pairs = list(zip(read.frames(), written.frames(), strict=True))
    for got, want in pairs:
        np.testing.assert_allclose(got.observation.across_m, want.observation.across_m, rtol=1e-5, equal_nan=True)
        np.testing.assert_allclose(got.observation.depth_m, want.observation.depth_m, rtol=1e-5, equal_nan=True)
        if want.truth is None:
            assert got.truth is None
        else:
            np.testing.assert_allclose(
                [got.truth.across_m, got.truth.depth_m, got.truth.burial, got.truth.resolution_m],
                [want.truth.across_m, want.truth.depth_m, want.truth.burial, want.truth.resolution_m],
                rtol=1e-5,
            )
        assert got.time_s == pytest.approx(want.time_s)


@settings(max_examples=20, deadline=None)
@given(seed=st.integers(0, 2**32 - 1))
def test_a_written_sequence_reads_back_with_its_calibration(tmp_path_factory, seed):
    path = tmp_path_factory.mktemp("swaths") / "tiny.swaths"
    written = PingSequence(random_pings(seed))
    write_swath_file(written, path)
    read = open_sequence(path, MODALITIES.values())
    assert isinstance(read, SwathFile)
    info = read.info
    assert (info.modality, info.n_frames, info.frame_interval_s) == ("sonar", 3, 0.25)
    assert info.calibration.n_beams == CALIBRATION.n_beams
    assert info.calibration.swath_angle == pytest.approx(CALIBRATION.swath_angle)
    assert info.calibration.pipe_diameter_m == pytest.approx(0.9)
    assert_same_frames(read, written)
    assert_same_frames(pickle.loads(pickle.dumps(read)), written)


def test_export_writes_a_sonar_sequence_as_one_swath_file(tmp_path):
    path = export_sequence(PingSequence(random_pings(1)), tmp_path, MODALITIES)
    assert path == tmp_path / "sonar_tiny.swaths" and path.is_file()
    assert [item.name for item in tmp_path.iterdir()] == ["sonar_tiny.swaths"]
    assert isinstance(open_sequence(path, [SONAR]), SwathFile)


def test_the_sonar_exporter_writes_stem_dot_swaths_into_a_new_folder(tmp_path):
    path = export_swath_file(PingSequence(random_pings(1)), tmp_path / "new" / "folder", "mine")
    assert path == tmp_path / "new" / "folder" / f"mine{SWATH_SUFFIX}" and path.is_file()
    assert SONAR.exporter is export_swath_file
    assert_same_frames(SwathFile(path), PingSequence(random_pings(1)))


HEADER = "# n_beams = 2\n# swath_angle_deg = 90\n# pipe_diameter_m = 0.5\n"
ROW = "0.0 nan nan nan nan -1 1 10 10\n"


def write(tmp_path, body: str | bytes, header: str | bytes = HEADER) -> SwathFile:
    """Open ``data.swaths`` made of ``header`` and ``body`` (text, or bytes taken as they are)."""
    path = tmp_path / "data.swaths"
    path.write_bytes(b"".join(part.encode() if isinstance(part, str) else part for part in (header, body)))
    return SwathFile(path)


def test_the_beam_width_is_optional_and_read_in_degrees(tmp_path):
    assert write(tmp_path, ROW).info.calibration.beam_width == 0.0
    wide = write(tmp_path, ROW, header=HEADER + "# beam_width_deg = 1.5\n")
    assert wide.info.calibration.beam_width == pytest.approx(math.radians(1.5))


def test_a_known_beam_width_is_written_and_read_back(tmp_path):
    class WideBeams(PingSequence):
        @property
        def info(self):
            info = super().info
            return dataclasses.replace(info, calibration=dataclasses.replace(CALIBRATION, beam_width=0.02))

    path = write_swath_file(WideBeams(random_pings(2)), tmp_path / "wide.swaths")
    assert "# beam_width_deg = " in path.read_text()
    assert SwathFile(path).info.calibration.beam_width == pytest.approx(0.02)
    plain = write_swath_file(PingSequence(random_pings(2)), tmp_path / "plain.swaths")
    assert "beam_width_deg" not in plain.read_text()


def test_the_ping_interval_defaults_to_the_first_time_step(tmp_path):
    sequence = write(tmp_path, "0.0 nan nan nan nan -1 1 10 10\n0.5 1 10 0 0.1 -1 nan 10 nan\n")
    assert sequence.info.frame_interval_s == pytest.approx(0.5)
    frames = list(sequence.frames())
    assert frames[0].truth is None and frames[1].truth.across_m == 1.0
    assert frames[1].observation.valid.tolist() == [True, False]


@pytest.mark.parametrize(
    ("body", "message"),
    [
        ("0.0 nan nan nan nan -1 1 10\n", r"data.swaths:4: expected 9 numbers"),
        ("0.0 nan nan nan nan -1 1 ten 10\n", r"data.swaths:4: field 8 is not a number: 'ten'"),
        ("0.0 1.0 nan nan nan -1 1 10 10\n", r"data.swaths:4: the four truth fields must all be numbers or all be nan"),
        ("0.0 nan nan nan nan -1 inf 10 10\n", r"data.swaths:4: field 7 is infinite \('inf'\)"),
        ("0.0 nan nan nan nan -1 1 10 -inf\n", r"data.swaths:4: field 9 is infinite \('-inf'\)"),
        ("0.0 inf 1 1 1 -1 1 10 10\n", r"data.swaths:4: field 2 is infinite"),
        ("0.0 nan nan nan nan 1e400 1 10 10\n", r"data.swaths:4: field 6 is infinite \('1e400'\)"),
        ("nan nan nan nan nan -1 1 10 10\n", r"data.swaths:4: the time \(field 1\) is nan"),
    ],
)
def test_malformed_rows_are_refused_when_the_file_is_opened_naming_file_and_line(tmp_path, body, message):
    with pytest.raises(DataError, match=message):
        write(tmp_path, body)


def test_a_row_that_does_not_match_n_beams_is_refused_at_open_wherever_it_is(tmp_path):
    with pytest.raises(DataError, match=r"data.swaths:7: expected 9 numbers.*got 11"):
        write(tmp_path, ROW + ROW + "# a comment\n" + "0.0 nan nan nan nan -1 0 1 10 10 10\n" + ROW)


@pytest.mark.parametrize(
    ("header", "body", "message"),
    [
        (HEADER.encode() + b"# made by \xe9quipe 3\n", ROW.encode(), r"data.swaths:4: not UTF-8 text"),
        (HEADER.encode(), b"0.0 nan nan nan nan -1 1 10 1\xff0\n", r"data.swaths:4: not UTF-8 text"),
        (HEADER.encode(), (ROW + ROW).encode() + b"# end \x80\n", r"data.swaths:6: not UTF-8 text"),
    ],
)
def test_a_byte_that_is_not_utf8_anywhere_is_named_by_file_and_line(tmp_path, header, body, message):
    with pytest.raises(DataError, match=message):
        write(tmp_path, body, header=header)


@pytest.mark.parametrize(
    ("header", "message"),
    [
        ("# n_beams = 2\n# swath_angle_deg = 90\n", "header lacks pipe_diameter_m"),
        ("# n_beams = 2.5\n", r"data.swaths:1: header value n_beams must be a whole number >= 1, got '2.5'"),
        ("# n_beams = inf\n", r"data.swaths:1: header value n_beams must be a whole number >= 1, got 'inf'"),
        ("# n_beams = nan\n", r"data.swaths:1: header value n_beams must be a whole number"),
        ("# n_beams = -2\n", r"data.swaths:1: header value n_beams must be a whole number"),
        ("# n_beams = 0\n", r"data.swaths:1: header value n_beams must be a whole number"),
        ("# n_beams = 1e400\n", r"data.swaths:1: header value n_beams must be a whole number"),
        ("# n_beams = two\n", r"data.swaths:1: n_beams is not a number"),
        ("# n_beams = 2\n# swath_angle_deg = -90\n", r"data.swaths:2: header value swath_angle_deg must be a finite"),
        ("# n_beams = 2\n# swath_angle_deg = inf\n", r"data.swaths:2: header value swath_angle_deg must be a finite"),
        (HEADER + "# range_sigma_m = nan\n", r"data.swaths:4: header value range_sigma_m must be a finite .* >= 0"),
        (HEADER + "# ping_interval_s = 0\n", r"data.swaths:4: header value ping_interval_s must be a finite .* > 0"),
        (HEADER + "# beam_width_deg = -1\n", r"data.swaths:4: header value beam_width_deg must be a finite .* >= 0"),
        (HEADER + "# n_beams = 2\n", r"data.swaths:4: header value n_beams is given twice \(also on line 1\)"),
    ],
)
def test_bad_headers_are_named_by_file_and_line(tmp_path, header, message):
    with pytest.raises(DataError, match=message):
        write(tmp_path, ROW, header=header)


def test_a_huge_n_beams_is_refused_by_the_first_row(tmp_path):
    with pytest.raises(DataError, match=r"data.swaths:4: expected 2000000000005 numbers"):
        write(tmp_path, ROW, header=HEADER.replace("n_beams = 2", "n_beams = 1e12"))


def test_a_file_without_pings_is_refused(tmp_path):
    with pytest.raises(DataError, match=r"data.swaths: no pings"):
        write(tmp_path, "# only a comment\n")


def test_a_missing_file_is_named(tmp_path):
    with pytest.raises(DataError, match="nothing.swaths"):
        open_sequence(tmp_path / "nothing.swaths", MODALITIES.values())


def test_exporting_under_a_file_is_a_data_error_naming_the_output_folder(tmp_path):
    blocker = tmp_path / "blocker"
    blocker.write_text("mine", encoding="utf-8")
    for out in (blocker / "sub", blocker):
        with pytest.raises(DataError, match=rf"^{re.escape(str(out))}: cannot create folder"):
            export_sequence(PingSequence(random_pings(1)), out, MODALITIES)
    assert [item.name for item in tmp_path.iterdir()] == ["blocker"]
    assert blocker.read_text(encoding="utf-8") == "mine"


@pytest.mark.parametrize(
    ("pings", "message"),
    [
        ([], "sonar/tiny: the sequence has no pings to write"),
        ([(np.zeros(5), np.ones(5), SonarTruth(1.0, math.inf, 0.0, 0.1))], "ping 0: truth .* is not all finite"),
    ],
)
def test_writing_refuses_what_the_reader_would_refuse(tmp_path, pings, message):
    with pytest.raises(DataError, match=message):
        write_swath_file(PingSequence(pings), tmp_path / "x.swaths")
    assert not list(tmp_path.iterdir())


def test_writing_refuses_other_modalities_and_leaves_no_partial_file(tmp_path):
    with pytest.raises(DataError, match="only sonar sequences"):
        write_swath_file(PingSequence(random_pings(2), modality="camera"), tmp_path / "x.swaths")
    pings = random_pings(3)
    pings[2] = (np.zeros(4), np.zeros(4), None)
    with pytest.raises(DataError, match="ping 2: swath has 4 beams, the sequence 5"):
        write_swath_file(PingSequence(pings), tmp_path / "y.swaths")
    assert not list(tmp_path.iterdir())
