"""Options and defaults that several commands share: the cells a run selects, folders, the regression thresholds."""

from __future__ import annotations

import math
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING, Any

import click

from benchmark.executors import executor_names
from benchmark.frame_cache import CACHE_ENV
from benchmark.runner import DEFAULT_TIMEOUT_S

if TYPE_CHECKING:
    from benchmark.history.regressions import Thresholds

DEFAULT_OUT = Path("reports") / "latest"
DEFAULT_HISTORY = Path("reports") / "history.sqlite"
DEFAULT_SITE = Path("reports") / "site"


class Seconds(click.FloatRange):
    """A positive, finite number of seconds (``nan`` and ``inf`` would lift a time limit)."""

    name = "seconds"

    def __init__(self) -> None:
        super().__init__(min=0.0, min_open=True)

    def convert(self, value: Any, param: click.Parameter | None, ctx: click.Context | None) -> float:
        seconds = super().convert(value, param, ctx)
        if not math.isfinite(seconds):
            self.fail(f"{value!r} is not a finite number of seconds.", param, ctx)
        return seconds


cache_option = click.option(
    "--cache",
    type=click.Path(file_okay=False, path_type=Path),
    envvar=CACHE_ENV,
    default=None,
    help=f"Folder of the frame cache (default: ${CACHE_ENV}, else the platform's user cache folder).",
)

def init_option(
    default: str = "truth", help: str = "Initialise trackers from the first frame's ground truth, or not."
) -> Any:
    """``--init truth|none``: whether a cell's tracker starts from the first frame's truth."""
    return click.option("--init", type=click.Choice(["truth", "none"]), default=default, show_default=True, help=help)


_RUN_OPTIONS = [
    click.option(
        "--suite", "suites", multiple=True, metavar="SUITE", help="Run every sequence of a suite (repeatable)."
    ),
    click.option(
        "--tracker", "trackers", multiple=True, metavar="NAME", help="Run this tracker (repeatable; default all)."
    ),
    click.option(
        "--dataset",
        "datasets",
        multiple=True,
        metavar="NAME|PATH",
        help="A registered sequence (suite/name) or a sequence file, image folder or video (repeatable).",
    ),
    click.option("--seeds", type=click.IntRange(min=1), default=1, show_default=True, help="Run seeds 0..N-1."),
    click.option(
        "--jobs",
        type=click.IntRange(min=0),
        default=None,
        help="Worker processes (default: all cores; 0 or 1: one worker, one cell at a time).",
    ),
    click.option(
        "--in-process",
        is_flag=True,
        help="Run cells in this process, for debuggers and profilers: no time limit inside a step, "
        "and a tracker that exits or crashes ends the run.",
    ),
    init_option(),
    click.option(
        "--real-time",
        is_flag=True,
        help="Run closed-loop sequences in real time: frames arrive at the route's frame rate and a tracker busy "
        "longer than a frame interval skips the frames that arrive meanwhile.",
    ),
    click.option(
        "--step-time",
        "step_times",
        multiple=True,
        metavar="TRACKER=MS",
        help="With --real-time: the tracker's declared step time in ms (repeatable); without it a tracker's step "
        "time is the running median of its measured steps, a figure of this machine.",
    ),
    click.option("--resume", is_flag=True, help="Skip cells this database already finished with status ok."),
    click.option(
        "--timeout",
        type=Seconds(),
        default=DEFAULT_TIMEOUT_S,
        show_default=True,
        metavar="SECONDS",
        help="Time limit of each cell.",
    ),
    click.option("--param", "params", multiple=True, metavar="TRACKER.KEY=VALUE", help="Override a tracker parameter."),
    click.option(
        "--train",
        "train",
        multiple=True,
        metavar="SUITE|NAME|PATH",
        help="Train the trackers that learn on this suite, sequence or sequence file (repeatable), instead of the "
        "training suite each scored suite names.",
    ),
    click.option(
        "--executor",
        type=click.Choice(executor_names()),
        default="local",
        show_default=True,
        help="Run the cells in worker processes of this machine, or as tasks of a Dask cluster.",
    ),
    click.option(
        "--scheduler",
        metavar="ADDRESS",
        help="The Dask scheduler to send the cells to (tcp://host:8786); without it --executor dask starts a local "
        "cluster of --jobs workers.",
    ),
    cache_option,
    click.option("--no-cache", is_flag=True, help="Render every simulated sequence in every cell that reads it."),
    click.option(
        "-v",
        "--verbose",
        is_flag=True,
        help="A line on stderr for every finished cell, not only for the failed ones.",
    ),
]
"""The options of ``run`` that choose and run the cells, shared by ``nightly``; ``--out`` is each command's own."""


def run_options(command: Callable[..., Any]) -> Callable[..., Any]:
    """Add the options of :data:`_RUN_OPTIONS` to a command, in the order ``--help`` lists them."""
    for option in reversed(_RUN_OPTIONS):
        command = option(command)
    return command


OUT_OPTION = click.option(
    "--out",
    type=click.Path(file_okay=False, path_type=Path),
    default=DEFAULT_OUT,
    show_default=True,
    help="Folder holding results.sqlite; reports are written there.",
)
"""``--out`` of the commands that read a results database and write their reports beside it."""

class HistoryDatabase(click.ParamType):
    """A history database, opened and checked as the option is read, before the command runs anything.

    Its driver must import and the database must be a trackbench history
    (or empty, or, for an SQLite file and unless ``must_exist``, creatable:
    it is created with its tables), so that ``nightly`` reports a missing
    driver, an unreachable server or a foreign database before its first
    cell rather than after its last.  The location is returned as given
    (:class:`~benchmark.history.database.History` opens it again); a
    problem is the :class:`~benchmark.errors.DataError` of ``History``,
    shown as one line ``Error: ...`` with the password masked, exit status 2.

    Parameters
    ----------
    must_exist : bool
        Refuse an SQLite file that does not exist yet (``compare``,
        ``report``) instead of creating it (``nightly``).
    """

    name = "history"

    def __init__(self, *, must_exist: bool) -> None:
        self.must_exist = must_exist

    def convert(self, value: Any, param: click.Parameter | None, ctx: click.Context | None) -> str:
        from benchmark.history.database import History

        if ctx is None or not ctx.resilient_parsing:  # shell completion opens nothing
            History(value, must_exist=self.must_exist).close()
        return str(value)


def _history_option(*, must_exist: bool) -> Callable[[Callable[..., Any]], Callable[..., Any]]:
    return click.option(
        "--history",
        type=HistoryDatabase(must_exist=must_exist),
        default=str(DEFAULT_HISTORY),
        show_default=True,
        metavar="FILE|URL",
        help="The history database: an SQLite file or an SQLAlchemy URL (postgresql://user:password@host/db, "
        'its driver from pip install "subsea-trackbench[postgres]").',
    )


history_option = _history_option(must_exist=False)
"""``--history`` of ``nightly``: a history, or an empty database or SQLite file to start one in."""
existing_history_option = _history_option(must_exist=True)
"""``--history`` of the commands that read a history: ``compare``, ``report``."""
site_option = click.option(
    "--site",
    type=click.Path(file_okay=False, path_type=Path),
    default=DEFAULT_SITE,
    show_default=True,
    help="Folder the static HTML report is written to.",
)


def threshold_options(command: Callable[..., Any]) -> Callable[..., Any]:
    """Add ``--min-effect METRIC=VALUE``, ``--window N`` and ``--min-step-time SECONDS``: a regression's thresholds."""
    command = click.option(
        "--min-step-time",
        "min_step_s",
        type=click.FloatRange(min=0.0),
        default=2.0,
        show_default=True,
        metavar="SECONDS",
        help="Judge speed only where the cells of a tracker and dataset spent this much CPU time in their steps.",
    )(command)
    command = click.option(
        "--window",
        type=click.IntRange(min=1),
        default=5,
        show_default=True,
        help="Compare with this many earlier runs (for speed: on the same machine).",
    )(command)
    return click.option(
        "--min-effect",
        "min_effects",
        multiple=True,
        metavar="METRIC=VALUE",
        help="Smallest change that counts for a metric: points for a rate (default 2), a share for an RMSE "
        "or cpu_fps (default 0.1) (repeatable).",
    )(command)


def thresholds(min_effects: tuple[str, ...], window: int, min_step_s: float = 2.0) -> Thresholds:
    """The thresholds of a regression that the options of :func:`threshold_options` give."""
    from benchmark.history.regressions import Thresholds

    overrides = {}
    for text in min_effects:
        metric, sep, value = text.partition("=")
        try:
            overrides[metric.strip()] = float(value)
        except ValueError:
            sep = ""
        if not sep or not metric.strip():
            raise click.BadParameter(f"expected METRIC=NUMBER, got {text!r}", param_hint="--min-effect")
    return Thresholds(window=window, min_step_s=min_step_s, overrides=overrides)
