"""The progress bar: drawn on a terminal with failures and running cells, silent elsewhere."""

from __future__ import annotations

import io
import types

import pytest

from benchmark.progress import TerminalProgress
from benchmark.results import CellResult


def result(status: str) -> CellResult:
    """A finished cell, as far as progress reads one: its status."""
    return types.SimpleNamespace(status=status)  # type: ignore[return-value]


def test_on_a_terminal_the_bar_counts_cells_failures_and_names_the_running_ones() -> None:
    stream = io.StringIO()
    progress = TerminalProgress(stream, enabled=True, refresh_s=0.0)
    progress.start(3)
    progress.advance(result("ok"), lambda: ["condensation on camera/S1, seed 0"])
    progress.write("hough  camera/S6  seed 0  ok")
    progress.advance(result("error"), list)
    progress.close()
    text = stream.getvalue()
    assert "1/3" in text and "2/3" in text
    assert "0 failed, running condensation on camera/S1, seed 0" in text and "1 failed" in text
    assert "hough  camera/S6  seed 0  ok\n" in text


def test_elsewhere_only_the_log_lines_are_written() -> None:
    stream = io.StringIO()  # not a terminal
    progress = TerminalProgress(stream)
    progress.start(2)
    progress.write("a finished cell")
    progress.advance(result("timeout"), lambda: pytest.fail("asked for the running cells with no bar to show"))
    progress.close()
    assert stream.getvalue() == "a finished cell\n"
