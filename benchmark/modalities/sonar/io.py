"""Swath files: multibeam echo-sounder pings as plain text, one ping per line.

A researcher's own sonar data reach trackbench in this format, and
``trackbench make-dataset sonar`` writes the simulated suite in it.  A file
starts with ``key = value`` comments that describe the sonar and the pipe,
then holds one data row per ping::

    # trackbench swath file: one multibeam ping per line (seeds/003)
    # n_beams = 4
    # swath_angle_deg = 120
    # range_sigma_m = 0.05
    # pipe_diameter_m = 0.9
    # ping_interval_s = 0.25
    # time_s pipe_across_m pipe_depth_m burial resolution_m across_m[n_beams] depth_m[n_beams]
    0.00 1.20 14.55 0.0 0.27 -25.9 -4.1 4.0 25.8 15.1 15.0 14.9 15.2
    0.25 nan nan nan nan -25.8 nan 4.1 25.9 15.0 nan 14.9 15.1

A row holds ``5 + 2 n_beams`` whitespace-separated numbers: the ping's time
in s, the ground truth of :class:`~benchmark.modalities.sonar.model.SonarTruth` (the pipe
axis' across-track position and depth in m, its burial from 0 to 1, the
across-track beam spacing at the pipe in m), then the across-track
positions and the depths of the beams' returns, port to starboard (m from
nadir, starboard positive; m below the transducer).  A beam without a
return is ``nan`` in both lists; an unlabelled ping is ``nan`` in all five
truth fields.

``n_beams``, ``swath_angle_deg`` and ``pipe_diameter_m`` are required;
``range_sigma_m`` defaults to 0 and ``ping_interval_s`` to the difference
of the first two times.  Other comment lines and blank lines are skipped.
Every error names the file and the line.
"""

from __future__ import annotations

import math
import os
from collections.abc import Iterable, Iterator
from pathlib import Path
from typing import TextIO

from benchmark.errors import DataError
from benchmark.modalities.sonar.model import SonarCalibration, SonarTruth, Swath
from benchmark.model import Frame, Sequence, SequenceInfo

SWATH_SUFFIX = ".swaths"
"""File name ending by which :func:`benchmark.io.open_sequence` recognises a swath file."""

MAGIC = "# trackbench swath file: one multibeam ping per line (seeds/003)"
"""First line the writer puts in every file."""

COLUMNS = "# time_s pipe_across_m pipe_depth_m burial resolution_m across_m[n_beams] depth_m[n_beams]"
"""Comment line naming the columns of a data row."""

REQUIRED_KEYS = ("n_beams", "swath_angle_deg", "pipe_diameter_m")
OPTIONAL_KEYS = ("range_sigma_m", "ping_interval_s")
TRUTH_FIELDS = 4


def _open(path: Path) -> TextIO:
    try:
        return path.open(encoding="utf-8")
    except OSError as exc:
        raise DataError(f"{path}: cannot read swath file: {exc.strerror or exc}") from None


def _header_value(text: str) -> tuple[str, str] | None:
    """``(key, value)`` of a ``# key = value`` comment, None for any other comment."""
    key, equals, value = text.lstrip("#").partition("=")
    key = key.strip()
    if not equals or key not in REQUIRED_KEYS + OPTIONAL_KEYS:
        return None
    return key, value.strip()


def _number(token: str, where: str, what: str) -> float:
    try:
        return float(token)
    except ValueError:
        raise DataError(f"{where}{what} is not a number: {token!r}") from None


class SwathFile(Sequence):
    """A swath file as a lazy, picklable sonar :class:`~benchmark.model.Sequence`.

    The header is read when the object is made; pings are parsed one line
    at a time while the sequence is iterated.

    Parameters
    ----------
    path : str or path-like
        The swath file.

    Raises
    ------
    DataError
        If the file cannot be read, or its header lacks a required key or
        has a value that is not a positive number.

    References
    ----------
    seeds/003, sections 2 and 4.
    """

    def __init__(self, path: str | os.PathLike[str]) -> None:
        self.path = Path(path)
        header: dict[str, float] = {}
        n_pings = 0
        first_times: list[float] = []
        with _open(self.path) as stream:
            for line, text in enumerate(stream, start=1):
                stripped = text.strip()
                if not stripped:
                    continue
                if stripped.startswith("#"):
                    entry = _header_value(stripped) if n_pings == 0 else None
                    if entry is not None:
                        header[entry[0]] = _number(entry[1], f"{self.path}:{line}: ", entry[0])
                    continue
                n_pings += 1
                if len(first_times) < 2:
                    first_times.append(_number(stripped.split(maxsplit=1)[0], f"{self.path}:{line}: ", "time_s"))
        missing = [key for key in REQUIRED_KEYS if key not in header]
        if missing:
            raise DataError(f"{self.path}: header lacks {', '.join(missing)} (lines '# key = value' before the data)")
        for key in REQUIRED_KEYS:
            if not header[key] > 0:
                raise DataError(f"{self.path}: header value {key} must be positive, got {header[key]}")
        n_beams = header["n_beams"]
        if n_beams != int(n_beams):
            raise DataError(f"{self.path}: header value n_beams must be a whole number, got {n_beams}")
        interval = header.get("ping_interval_s")
        if interval is None and len(first_times) == 2:
            interval = first_times[1] - first_times[0]
        self._calibration = SonarCalibration(
            n_beams=int(n_beams),
            swath_angle=math.radians(header["swath_angle_deg"]),
            range_sigma_m=header.get("range_sigma_m", 0.0),
            pipe_diameter_m=header["pipe_diameter_m"],
        )
        self._n_pings = n_pings
        self._interval = interval

    @property
    def info(self) -> SequenceInfo:
        return SequenceInfo(
            name=str(self.path),
            modality="sonar",
            n_frames=self._n_pings,
            frame_interval_s=self._interval,
            calibration=self._calibration,
            extra={"source": str(self.path)},
        )

    def frames(self) -> Iterator[Frame]:
        """Yield one frame per data row.

        Raises
        ------
        DataError
            For a row with the wrong number of fields, a field that is not
            a number, or a truth that is neither all numbers nor all ``nan``.
        """
        n_beams = self._calibration.n_beams
        expected = 1 + TRUTH_FIELDS + 2 * n_beams
        index = 0
        with _open(self.path) as stream:
            for line, text in enumerate(stream, start=1):
                stripped = text.strip()
                if not stripped or stripped.startswith("#"):
                    continue
                where = f"{self.path}:{line}: "
                tokens = stripped.split()
                if len(tokens) != expected:
                    raise DataError(
                        f"{where}expected {expected} numbers (time, 4 truth fields, {n_beams} across-track "
                        f"positions and {n_beams} depths), got {len(tokens)}"
                    )
                values = [_number(token, where, f"field {column + 1}") for column, token in enumerate(tokens)]
                yield Frame(
                    index=index,
                    observation=Swath(values[5 : 5 + n_beams], values[5 + n_beams :]),
                    truth=_truth(values[1:5], where),
                    time_s=values[0],
                )
                index += 1


def _truth(fields: list[float], where: str) -> SonarTruth | None:
    known = [math.isfinite(value) for value in fields]
    if not any(known):
        return None
    if not all(known):
        raise DataError(f"{where}the four truth fields must all be numbers or all be nan, got {fields}")
    return SonarTruth(*fields)


def _format(value: float) -> str:
    return "nan" if not math.isfinite(value) else f"{value:.6g}"


def _row(frame: Frame, n_beams: int, where: str) -> str:
    swath = frame.observation
    if not isinstance(swath, Swath):
        raise DataError(f"{where}observation is a {type(swath).__name__}, not a Swath")
    if swath.across_m.size != n_beams:
        raise DataError(f"{where}swath has {swath.across_m.size} beams, the sequence {n_beams}")
    truth = frame.truth
    if truth is None:
        fields = [math.nan] * TRUTH_FIELDS
    elif isinstance(truth, SonarTruth):
        fields = [truth.across_m, truth.depth_m, truth.burial, truth.resolution_m]
    else:
        raise DataError(f"{where}truth is a {type(truth).__name__}, not a SonarTruth")
    numbers: Iterable[float] = (frame.time_s, *fields, *swath.across_m, *swath.depth_m)
    return " ".join(_format(float(value)) for value in numbers)


def write_swath_file(sequence: Sequence, path: str | os.PathLike[str]) -> Path:
    """Write a sonar sequence as a swath file, one ping at a time.

    The file is written under a temporary name and renamed when complete,
    so a failure never leaves a truncated swath file behind.

    Parameters
    ----------
    sequence : Sequence
        A sonar sequence with a :class:`~benchmark.modalities.sonar.model.SonarCalibration`.
    path : str or path-like
        The file to write; its folder is created if missing.

    Returns
    -------
    pathlib.Path
        ``path``.

    Raises
    ------
    DataError
        If the sequence is not a calibrated sonar sequence, a frame's
        observation is not a Swath of ``n_beams`` beams or its truth is not
        a SonarTruth, or the file cannot be written.
    """
    info = sequence.info
    calibration = info.calibration
    if info.modality != "sonar" or not isinstance(calibration, SonarCalibration):
        raise DataError(f"{info.name}: only sonar sequences with a SonarCalibration can be written as swath files")
    target = Path(path)
    partial = target.with_name(target.name + ".partial")
    header = [
        MAGIC,
        f"# n_beams = {calibration.n_beams}",
        f"# swath_angle_deg = {math.degrees(calibration.swath_angle):.10g}",
        f"# range_sigma_m = {calibration.range_sigma_m:.10g}",
        f"# pipe_diameter_m = {calibration.pipe_diameter_m:.10g}",
    ]
    if info.frame_interval_s is not None:
        header.append(f"# ping_interval_s = {info.frame_interval_s:.10g}")
    header.append(COLUMNS)
    try:
        target.parent.mkdir(parents=True, exist_ok=True)
        with partial.open("w", encoding="utf-8") as stream:
            stream.write("\n".join(header) + "\n")
            for frame in sequence.frames():
                stream.write(_row(frame, calibration.n_beams, f"{info.name}: ping {frame.index}: ") + "\n")
        partial.replace(target)
    except OSError as exc:
        partial.unlink(missing_ok=True)
        raise DataError(f"{target}: cannot write swath file: {exc.strerror or exc}") from None
    except BaseException:
        partial.unlink(missing_ok=True)
        raise
    return target


def export_swath_file(sequence: Sequence, out: Path, stem: str) -> Path:
    """Write a sonar sequence as the swath file ``out/<stem>.swaths`` (the sonar modality's exporter)."""
    return write_swath_file(sequence, out / f"{stem}{SWATH_SUFFIX}")
