"""Feedback while a run goes: a progress bar on a terminal, plain lines elsewhere.

The harness reports a run's progress to a :class:`Progress`: how many cells
there are, each cell as it finishes with the cells still running, and the
end.  :class:`TerminalProgress` draws it with tqdm on standard error (cells
done of total, failures so far, the cells running, elapsed and remaining
time) and prints the log lines above the bar; when standard error is not a
terminal (a CI log, a file) it draws nothing and the log lines alone tell
the story.
"""

from __future__ import annotations

import sys
from collections.abc import Callable
from typing import IO, Protocol

from benchmark.results import CellResult


class Progress(Protocol):
    """What the harness tells about a run while it goes."""

    def start(self, total: int) -> None:
        """``total`` cells are about to run."""

    def advance(self, result: CellResult, running: Callable[[], list[str]]) -> None:
        """A cell finished with ``result``; ``running()`` gives the labels of the cells still running.

        ``running`` is a call, not a list, so that what nobody shows is never
        asked of the executor (on Dask, a round trip to the scheduler).
        """

    def close(self) -> None:
        """The run ended (finished or interrupted)."""


class SilentProgress:
    """Progress that shows nothing."""

    def start(self, total: int) -> None:
        pass

    def advance(self, result: CellResult, running: Callable[[], list[str]]) -> None:
        pass

    def close(self) -> None:
        pass


class TerminalProgress:
    """A tqdm bar of the run's cells on a terminal; nothing but the log lines elsewhere.

    Parameters
    ----------
    stream : file, optional
        Where to draw (standard error by default).
    enabled : bool, optional
        Draw the bar; by default only when ``stream`` is a terminal.
    refresh_s : float
        Least time between two redraws of the bar.
    """

    def __init__(self, stream: IO[str] | None = None, enabled: bool | None = None, refresh_s: float = 0.1) -> None:
        self._stream = stream or sys.stderr
        self._refresh_s = refresh_s
        self._enabled = self._stream.isatty() if enabled is None else enabled
        self._bar = None
        self._failed = 0

    def start(self, total: int) -> None:
        if not self._enabled or total == 0:
            return
        from tqdm import tqdm

        self._bar = tqdm(
            total=total, unit="cell", file=self._stream, dynamic_ncols=True, leave=False, mininterval=self._refresh_s
        )

    def write(self, line: str) -> None:
        """Print a log line, above the bar while there is one."""
        if self._bar is not None:
            self._bar.write(line, file=self._stream)
        else:
            print(line, file=self._stream, flush=True)

    def advance(self, result: CellResult, running: Callable[[], list[str]]) -> None:
        self._failed += result.status != "ok"
        if self._bar is None:
            return
        labels = running()
        now = f"running {'; '.join(labels)}" if labels else ""
        self._bar.set_postfix_str(f"{self._failed} failed{', ' + now if now else ''}", refresh=False)
        self._bar.update(1)

    def close(self) -> None:
        if self._bar is not None:
            self._bar.close()
            self._bar = None
