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
    # beam_width_deg = 1.5
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
return is ``nan`` in both lists; an unlabelled ping is ``nan`` in all four
truth fields.  The time is a finite number, and no field is infinite:
``inf``, ``-inf`` or a number too large for a float (``1e400``) is an
error, not a missing value.

The header is the ``# key = value`` lines before the first ping, each key at
most once.  ``n_beams`` (a whole number >= 1), ``swath_angle_deg`` and
``pipe_diameter_m`` (finite, > 0) are required; ``range_sigma_m`` (finite,
>= 0) defaults to 0, ``beam_width_deg`` (the across-track width of one
beam, finite, >= 0) to 0 for "not known", and ``ping_interval_s`` (finite,
> 0) to the difference of the first two times where that is positive.  Other comment
lines and blank lines are skipped.

The file must be UTF-8 text and hold at least one ping.  The whole file is
read and checked when it is opened, so that a malformed header or row fails
there, once, rather than in every run of the sequence; the pings are parsed
again, one line at a time, while the sequence is iterated.  Every error
names the file, and the line where there is one.
"""

from __future__ import annotations

import io
import math
import os
from collections.abc import Callable, Iterable, Iterator
from pathlib import Path

from benchmark.errors import DataError
from benchmark.files import atomic_writer, make_folder
from benchmark.identity import DatasetIdentity, file_fingerprint, resolved_source
from benchmark.io import open_regular_file, read_regular_file
from benchmark.modalities.sonar.model import SonarCalibration, SonarTruth, Swath
from benchmark.model import Frame, Sequence, SequenceInfo

SWATH_SUFFIX = ".swaths"
"""File name ending by which :func:`benchmark.io.open_sequence` recognises a swath file."""

MAGIC = "# trackbench swath file: one multibeam ping per line (seeds/003)"
"""First line the writer puts in every file."""

COLUMNS = "# time_s pipe_across_m pipe_depth_m burial resolution_m across_m[n_beams] depth_m[n_beams]"
"""Comment line naming the columns of a data row."""

REQUIRED_KEYS = ("n_beams", "swath_angle_deg", "pipe_diameter_m")
OPTIONAL_KEYS = ("range_sigma_m", "beam_width_deg", "ping_interval_s")
TRUTH_FIELDS = 4

_HEADER_RULES: dict[str, tuple[Callable[[float], bool], str]] = {
    "n_beams": (lambda value: value >= 1 and value.is_integer(), "a whole number >= 1"),
    "swath_angle_deg": (lambda value: value > 0, "a finite number > 0"),
    "pipe_diameter_m": (lambda value: value > 0, "a finite number > 0"),
    "range_sigma_m": (lambda value: value >= 0, "a finite number >= 0"),
    "beam_width_deg": (lambda value: value >= 0, "a finite number >= 0"),
    "ping_interval_s": (lambda value: value > 0, "a finite number > 0"),
}
"""Per header key: the condition its (finite) value meets, and how messages state it."""

Ping = tuple[float, Swath, SonarTruth | None]
"""A parsed data row: time in s, the swath, the truth or None."""


def _lines(path: Path, stream: Iterable[bytes]) -> Iterator[tuple[int, str]]:
    """Number (from 1) and stripped text of each non-blank line of a swath file's bytes."""
    for number, raw in enumerate(stream, start=1):
        try:
            text = raw.decode("utf-8").strip()
        except UnicodeDecodeError as exc:
            raise DataError(f"{path}:{number}: not UTF-8 text ({exc.reason} at byte {exc.start} of the line)") from None
        if text:
            yield number, text


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


def _read_header(path: Path, stream: Iterable[bytes]) -> tuple[SonarCalibration, float | None]:
    """The calibration and the ``ping_interval_s`` (None if not given) of the header before the first ping."""
    values: dict[str, float] = {}
    lines: dict[str, int] = {}
    for number, text in _lines(path, stream):
        if not text.startswith("#"):
            break
        entry = _header_value(text)
        if entry is None:
            continue
        key, token = entry
        where = f"{path}:{number}: "
        if key in lines:
            raise DataError(f"{where}header value {key} is given twice (also on line {lines[key]})")
        value = _number(token, where, key)
        condition, description = _HEADER_RULES[key]
        if not (math.isfinite(value) and condition(value)):
            raise DataError(f"{where}header value {key} must be {description}, got {token!r}")
        values[key], lines[key] = value, number
    missing = [key for key in REQUIRED_KEYS if key not in values]
    if missing:
        raise DataError(f"{path}: header lacks {', '.join(missing)} (lines '# key = value' before the data)")
    calibration = SonarCalibration(
        n_beams=int(values["n_beams"]),
        swath_angle=math.radians(values["swath_angle_deg"]),
        range_sigma_m=values.get("range_sigma_m", 0.0),
        pipe_diameter_m=values["pipe_diameter_m"],
        beam_width=math.radians(values.get("beam_width_deg", 0.0)),
    )
    return calibration, values.get("ping_interval_s")


def _ping(text: str, where: str, n_beams: int) -> Ping:
    """Parse one data row."""
    tokens = text.split()
    expected = 1 + TRUTH_FIELDS + 2 * n_beams
    if len(tokens) != expected:
        raise DataError(
            f"{where}expected {expected} numbers (time, 4 truth fields, {n_beams} across-track "
            f"positions and {n_beams} depths), got {len(tokens)}"
        )
    values = [_number(token, where, f"field {column}") for column, token in enumerate(tokens, start=1)]
    for column, value in enumerate(values, start=1):
        if math.isinf(value):
            raise DataError(f"{where}field {column} is infinite ({tokens[column - 1]!r}); write nan for no value")
    if math.isnan(values[0]):
        raise DataError(f"{where}the time (field 1) is nan; every ping needs a time")
    swath = Swath(values[1 + TRUTH_FIELDS : 1 + TRUTH_FIELDS + n_beams], values[1 + TRUTH_FIELDS + n_beams :])
    return values[0], swath, _truth(values[1 : 1 + TRUTH_FIELDS], where)


def _pings(path: Path, stream: Iterable[bytes], n_beams: int) -> Iterator[Ping]:
    """Parse the data rows of a swath file's bytes, in order."""
    for number, text in _lines(path, stream):
        if not text.startswith("#"):
            yield _ping(text, f"{path}:{number}: ", n_beams)


class SwathFile(Sequence):
    """A swath file as a lazy, picklable sonar :class:`~benchmark.model.Sequence`.

    The whole file is read and checked when the object is made; pings are
    parsed one line at a time while the sequence is iterated.  Its identity
    is the file's resolved path and a hash of the bytes read then.

    Parameters
    ----------
    path : str or path-like
        The swath file.

    Raises
    ------
    DataError
        If the file is missing, not a regular file (a FIFO or a device is
        refused unopened) or unreadable, is not UTF-8 text, its header lacks
        a required key or has a value out of range, it holds no ping, or a
        row is malformed (see the module); naming the file and the line.

    References
    ----------
    seeds/003, sections 2 and 4.
    """

    def __init__(self, path: str | os.PathLike[str]) -> None:
        self.path = Path(path)
        content = read_regular_file(self.path, "swath file")
        self._calibration, interval = _read_header(self.path, io.BytesIO(content))
        times = [time_s for time_s, _, _ in _pings(self.path, io.BytesIO(content), self._calibration.n_beams)]
        if not times:
            raise DataError(f"{self.path}: no pings (expected a row of numbers per ping after the header)")
        if interval is None and len(times) >= 2 and times[1] > times[0]:
            interval = times[1] - times[0]
        self._n_pings = len(times)
        self._interval = interval
        self._identity = DatasetIdentity(
            str(self.path),
            "sonar",
            source=resolved_source(self.path),
            fingerprint=file_fingerprint(self.path, content=content),
        )

    @property
    def identity(self) -> DatasetIdentity:
        """The file's resolved path and the hash of its bytes, as when it was opened."""
        return self._identity

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
            If the file has become unreadable or malformed since it was opened.
        """
        with open_regular_file(self.path, "swath file") as stream:
            for index, (time_s, swath, truth) in enumerate(_pings(self.path, stream, self._calibration.n_beams)):
                yield Frame(index=index, observation=swath, truth=truth, time_s=time_s)


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
    if not math.isfinite(frame.time_s):
        raise DataError(f"{where}time {frame.time_s} s is not a finite number")
    truth = frame.truth
    if truth is None:
        fields = [math.nan] * TRUTH_FIELDS
    elif isinstance(truth, SonarTruth):
        fields = [truth.across_m, truth.depth_m, truth.burial, truth.resolution_m]
        if not all(math.isfinite(value) for value in fields):
            raise DataError(f"{where}truth {fields} is not all finite; an unlabelled ping has truth None")
    else:
        raise DataError(f"{where}truth is a {type(truth).__name__}, not a SonarTruth")
    numbers: Iterable[float] = (frame.time_s, *fields, *swath.across_m, *swath.depth_m)
    return " ".join(_format(float(value)) for value in numbers)


def write_swath_file(sequence: Sequence, path: str | os.PathLike[str]) -> Path:
    """Write a sonar sequence as a swath file, one ping at a time.

    The file is written through :func:`benchmark.files.atomic_writer`: a
    failure never leaves a truncated swath file behind.  A beam without a
    finite return is written ``nan``.

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
        If the sequence is not a calibrated sonar sequence or has no ping,
        a frame's observation is not a Swath of ``n_beams`` beams, its time
        is not finite or its truth is neither None nor a finite SonarTruth
        (what the reader would refuse), or the folder or the file cannot be
        created or written, naming it.
    """
    info = sequence.info
    calibration = info.calibration
    if info.modality != "sonar" or not isinstance(calibration, SonarCalibration):
        raise DataError(f"{info.name}: only sonar sequences with a SonarCalibration can be written as swath files")
    target = Path(path)
    header = [
        MAGIC,
        f"# n_beams = {calibration.n_beams}",
        f"# swath_angle_deg = {math.degrees(calibration.swath_angle):.10g}",
        f"# range_sigma_m = {calibration.range_sigma_m:.10g}",
        f"# pipe_diameter_m = {calibration.pipe_diameter_m:.10g}",
    ]
    if calibration.beam_width > 0:
        header.append(f"# beam_width_deg = {math.degrees(calibration.beam_width):.10g}")
    if info.frame_interval_s is not None:
        header.append(f"# ping_interval_s = {info.frame_interval_s:.10g}")
    header.append(COLUMNS)
    make_folder(target.parent)
    with atomic_writer(target, "swath file") as stream:
        stream.write("\n".join(header) + "\n")
        n_pings = 0
        for n_pings, frame in enumerate(sequence.frames(), start=1):
            stream.write(_row(frame, calibration.n_beams, f"{info.name}: ping {frame.index}: ") + "\n")
        if not n_pings:
            raise DataError(f"{info.name}: the sequence has no pings to write")
    return target


def export_swath_file(sequence: Sequence, out: Path, stem: str) -> Path:
    """Write a sonar sequence as the swath file ``out/<stem>.swaths`` (the sonar modality's exporter)."""
    return write_swath_file(sequence, out / f"{stem}{SWATH_SUFFIX}")
