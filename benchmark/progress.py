"""Feedback while long work goes: a progress bar on a terminal, a plain line every few seconds elsewhere.

:class:`Meter` is the one helper every long command uses (a run's cells,
``diagnose``, ``pose-table``, the site build, ``make-dataset``): told how
much there is and how much is done, it draws a tqdm bar when its stream is
a terminal, and elsewhere (a CI log, a file) writes a line such as::

    cells 12/40, 1 failed, elapsed 1m02s, ~2m25s remaining

at most every few seconds, and once more at the end, so that a log shows
that the work moves and when it will end without a line per item.  It is
also a ``report(done, total)`` callback, for code that counts its own work
(:func:`benchmark.site.build_site`).

A run tells its progress to a :class:`Progress`: how many cells there are,
each cell as it finishes, and the end.  :class:`TerminalProgress` shows it
with a :class:`Meter` of the cells; a failed cell gets a line of its own
(tracker, dataset, seed, status and message), a cell that ended ``ok`` only
when asked (``-v``): a log of hundreds of ``ok`` lines hides the failures
and the count it needs, and the boards hold every cell's numbers anyway.
"""

from __future__ import annotations

import math
import sys
import time
from collections.abc import Callable
from typing import IO, TYPE_CHECKING, Any, Protocol

if TYPE_CHECKING:
    from benchmark.results import CellResult

PLAIN_EVERY_S = 5.0
"""Least time between two plain progress lines."""

Report = Callable[[int, int], None]
"""A progress callback: ``report(done, total)`` (a :class:`Meter` is one)."""


def duration(seconds: float) -> str:
    """``seconds`` for a reader: ``42s``, ``3m05s``, ``2h07m``; ``?`` when unknown."""
    if not math.isfinite(seconds) or seconds < 0:
        return "?"
    whole = round(seconds)
    if whole < 60:
        return f"{whole}s"
    if whole < 3600:
        return f"{whole // 60}m{whole % 60:02d}s"
    return f"{whole // 3600}h{whole % 3600 // 60:02d}m"


class Meter:
    """How much of some work is done: a tqdm bar on a terminal, a plain line every few seconds elsewhere.

    Parameters
    ----------
    label : str
        What is counted, first on every line (``cells``, ``frames``, ``pages``).
    total : int, optional
        How much there is; may be given later (:meth:`start`, :meth:`report`).
    stream : file, optional
        Where to write (standard error by default).
    enabled : bool, optional
        Draw a bar; by default when ``stream`` is a terminal.  Without a bar,
        plain lines are written.
    every_s : float
        Least time between two plain lines.
    refresh_s : float
        Least time between two redraws of the bar.
    clock : callable
        Seconds of a monotonic clock (for tests).
    """

    def __init__(
        self,
        label: str,
        total: int | None = None,
        *,
        stream: IO[str] | None = None,
        enabled: bool | None = None,
        every_s: float = PLAIN_EVERY_S,
        refresh_s: float = 0.1,
        clock: Callable[[], float] = time.monotonic,
    ) -> None:
        self.label = label
        self.total = total
        self.done = 0
        self.note = ""
        self._stream = stream or sys.stderr
        self._bar_wanted = self._stream.isatty() if enabled is None else enabled
        self._every_s = every_s
        self._refresh_s = refresh_s
        self._clock = clock
        self._started: float | None = None
        self._last_line: float | None = None
        self._written: int | None = None
        self._bar: Any = None
        self._closed = False
        if total is not None:
            self.start(total)

    @property
    def draws_bar(self) -> bool:
        """Whether it draws a bar (on a terminal) rather than plain lines."""
        return self._bar_wanted

    def start(self, total: int) -> None:
        """There are ``total`` items; the clock of elapsed and remaining time starts now."""
        self.total, self.done, self._closed, self._written = total, 0, False, None
        self._started = self._last_line = self._clock()
        if self._bar_wanted and total > 0:
            from tqdm import tqdm

            self._bar = tqdm(
                total=total,
                desc=self.label,
                unit="",
                file=self._stream,
                dynamic_ncols=True,
                leave=False,
                mininterval=self._refresh_s,
            )

    def advance(self, count: int = 1, note: str | None = None) -> None:
        """``count`` more items are done; ``note`` (failures, say) is shown beside the count from now on."""
        self.report(self.done + count, self.total, note)

    def report(self, done: int, total: int | None = None, note: str | None = None) -> None:
        """``done`` of ``total`` items are done (the callback form: ``report(done, total)``)."""
        if self._started is None or (total is not None and total != self.total):
            self.start(self.total if total is None else total)
        if note is not None:
            self.note = note
        step, self.done = done - self.done, done
        if self._bar is not None:
            if note is not None:
                self._bar.set_postfix_str(note, refresh=False)
            self._bar.update(step)
            return
        now = self._clock()
        finished = self.total is not None and done >= self.total
        since = now - self._last_line if self._last_line is not None else 0.0
        if not self._bar_wanted and (finished or since >= self._every_s):
            self._write_line(now)

    def line(self, now: float | None = None) -> str:
        """The plain line: ``label done/total, note, elapsed E, ~R remaining``."""
        now = self._clock() if now is None else now
        elapsed = now - (self._started if self._started is not None else now)
        total = self.total or 0
        parts = [f"{self.label} {self.done}/{total if self.total is not None else '?'}"]
        if self.note:
            parts.append(self.note)
        parts.append(f"elapsed {duration(elapsed)}")
        if self.done < total:
            remaining = elapsed / self.done * (total - self.done) if self.done else math.nan
            parts.append(f"~{duration(remaining)} remaining")
        return ", ".join(parts)

    def _write_line(self, now: float) -> None:
        self._last_line, self._written = now, self.done
        print(self.line(now), file=self._stream, flush=True)

    def write(self, line: str, stream: IO[str] | None = None) -> None:
        """Print a line to ``stream`` (by default the meter's own), above the bar while there is one."""
        if self._bar is not None:
            self._bar.write(line, file=stream or self._stream)
        else:
            print(line, file=stream or self._stream, flush=True)

    def close(self, *, quiet: bool = False) -> None:
        """The work ended (finished or interrupted): remove the bar, or write the last plain line unless ``quiet``."""
        if self._closed:
            return
        self._closed = True
        if self._bar is not None:
            self._bar.close()
            self._bar = None
        elif not (quiet or self._bar_wanted) and self._started is not None and self.done != self._written:
            self._write_line(self._clock())

    def __call__(self, done: int, total: int) -> None:
        """``report(done, total)``, for code that takes a progress callback."""
        self.report(done, total)

    def __enter__(self) -> Meter:
        return self

    def __exit__(self, kind: type[BaseException] | None, *exc: object) -> None:
        self.close(quiet=kind is not None)  # the error says where the work stopped


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
    """A run's cells on a :class:`Meter`, with a line for each failed cell (and each cell, when ``verbose``).

    On a terminal the bar names the cells still running; elsewhere the
    plain lines count the cells done, failed and left, every few seconds.

    Parameters
    ----------
    meter : Meter, optional
        Where the cells are counted; by default a meter of ``cells`` on
        standard error.
    verbose : bool
        Also write a line for every cell that ended ``ok``.
    """

    def __init__(self, meter: Meter | None = None, *, verbose: bool = False) -> None:
        self._meter = meter or Meter("cells")
        self._verbose = verbose
        self._failed = 0

    def start(self, total: int) -> None:
        self._meter.start(total)

    def write(self, line: str) -> None:
        """Print a log line, above the bar while there is one."""
        self._meter.write(line)

    def advance(self, result: CellResult, running: Callable[[], list[str]]) -> None:
        failed = result.status != "ok"
        self._failed += failed
        if failed or self._verbose:
            from benchmark.harness import describe_result

            self._meter.write(describe_result(result))
        note = f"{self._failed} failed"
        if self._meter.draws_bar:
            labels = running()
            note += f", running {'; '.join(labels)}" if labels else ""
        self._meter.advance(1, note)

    def close(self) -> None:
        self._meter.close()
