"""Progress: a bar on a terminal; elsewhere a line every few seconds with counts and the time left, and failed cells."""

from __future__ import annotations

import io
import math
import types

import pytest

from benchmark.progress import Meter, TerminalProgress, duration
from benchmark.results import CellResult


class Clock:
    """A clock the test moves by hand."""

    def __init__(self) -> None:
        self.now = 100.0

    def __call__(self) -> float:
        return self.now


def result(status: str, tracker: str = "hough") -> CellResult:
    """A finished cell, as far as progress reads one."""
    return types.SimpleNamespace(  # type: ignore[return-value]
        status=status, tracker=tracker, dataset="camera/S6", seed=0, scores=[], elapsed_s=0.5,
        message="" if status == "ok" else "RuntimeError: lost", summary=lambda: {}, real_time="",
    )


def test_on_a_terminal_the_bar_counts_cells_failures_and_names_the_running_ones() -> None:
    stream = io.StringIO()
    progress = TerminalProgress(Meter("cells", stream=stream, enabled=True, refresh_s=0.0))
    progress.start(3)
    progress.advance(result("ok"), lambda: ["condensation on camera/S1, seed 0"])
    progress.write("a log line")
    progress.advance(result("error"), list)
    progress.close()
    text = stream.getvalue()
    assert "1/3" in text and "2/3" in text
    assert "0 failed, running condensation on camera/S1, seed 0" in text and "1 failed" in text
    assert "a log line\n" in text and "hough  camera/S6  seed 0  error" in text


def test_a_plain_log_counts_cells_every_few_seconds_and_names_only_failed_cells() -> None:
    stream, clock = io.StringIO(), Clock()
    progress = TerminalProgress(Meter("cells", stream=stream, every_s=5.0, clock=clock))
    progress.start(6)
    for status in ("ok", "ok", "timeout", "ok", "ok", "ok"):
        clock.now += 2.0
        progress.advance(result(status), lambda: pytest.fail("asked for the running cells with no bar to show"))
    progress.close()
    lines = stream.getvalue().splitlines()
    assert lines[0].startswith("hough  camera/S6  seed 0  timeout")
    assert lines[1:] == [
        "cells 3/6, 1 failed, elapsed 6s, ~6s remaining",
        "cells 6/6, 1 failed, elapsed 12s",
    ]


def test_verbose_names_every_cell() -> None:
    stream = io.StringIO()
    progress = TerminalProgress(Meter("cells", stream=stream, clock=Clock()), verbose=True)
    progress.start(2)
    progress.advance(result("ok", "a"), list)
    progress.advance(result("ok", "b"), list)
    progress.close()
    lines = stream.getvalue().splitlines()
    assert [line.split("  ")[0] for line in lines] == ["a", "b", "cells 2/2, 0 failed, elapsed 0s"]


def test_a_meter_closed_early_writes_where_it_stopped_and_serves_as_a_callback() -> None:
    stream, clock = io.StringIO(), Clock()
    meter = Meter("pages", stream=stream, every_s=60.0, clock=clock)
    meter(0, 40)
    clock.now += 30.0
    meter(10, 40)  # within the minute: no line yet
    assert stream.getvalue() == ""
    meter.close()
    meter.close()
    assert stream.getvalue() == "pages 10/40, elapsed 30s, ~1m30s remaining\n"


@pytest.mark.parametrize(
    ("seconds", "text"), [(0.4, "0s"), (59.4, "59s"), (65, "1m05s"), (3600 * 2 + 7 * 60 + 5, "2h07m"), (math.nan, "?")]
)
def test_durations_read_as_seconds_minutes_or_hours(seconds: float, text: str) -> None:
    assert duration(seconds) == text
