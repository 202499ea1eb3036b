"""The ``trackbench`` command line.

::

    trackbench [--disable PLUGIN]... COMMAND

    list          trackers: name, version, modality, origin and parameters
    datasets      suites and their sequences
    run           run cells, store them and publish the leaderboard
    leaderboard   re-publish the leaderboard of an existing results database
    tables        a suite's results of the latest run as one table per case (stereo: Tables 6-8 of seeds/002)
    diagnose      the likelihood ceiling of a tracker's observation model on camera sequences
    pose-table    a camera tracker's pose estimates beside the truth, frame by frame (seeds/004)
    make-dataset  write a suite's sequences to disk (PNG frames plus sequence files, or swath files)
    cache         the frame cache: info (what it holds) and clear
    nightly       run, add the run to the history database, report its changes, rewrite the site
    compare       what changed between two runs of the history
    report        rebuild the site from the history without running anything
    check         the conformance checks of benchmark.testing on installed trackers
    new-tracker   write the skeleton of a tracker plugin package (pyproject, tracker, one-line test)

``run`` forms a cell for every selected tracker, sequence and seed whose
modalities match, and runs the cells on an executor (``--executor local``:
a pool of ``--jobs`` worker processes; ``--executor dask``: a Dask cluster,
``--scheduler ADDRESS`` or a local one).  Simulated sequences are rendered
once into the frame cache (``--cache DIR``, ``$TRACKBENCH_CACHE``, or the
platform's cache folder; ``--no-cache`` renders in every cell) and read
back by every other cell and run.  Each finished cell is stored in
``DIR/results.sqlite``, and ``leaderboard.csv``, ``leaderboard.md`` and
``leaderboard.html`` are written into ``DIR``.  One line per finished cell
goes to stderr, under a progress bar on a terminal, and one line sums the
run up at the end; the board goes to stdout.

Exit status, as pytest's:

* 0: done, every cell ``ok``;
* 1: done, the board written, but some cell ended in ``error`` or
  ``timeout``, or a plugin could not be loaded (its trackers are
  unavailable; ``--strict-plugins`` makes that an error instead);
* 2: nothing ran: a usage or data error (an unknown name, a bad parameter,
  an unreadable file, a broken plugin, a results folder in use), reported
  as one line ``Error: ...`` without a traceback;
* 3: ``nightly`` found a regression (the run is kept in the history and
  the site written);
* 130: the user's Ctrl-C; finished cells are kept and published.
"""

from __future__ import annotations

import dataclasses
import math
import sys
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING, Any

import click

from benchmark import plugins
from benchmark.errors import TrackbenchError
from benchmark.executors import executor_names
from benchmark.frame_cache import CACHE_ENV
from benchmark.registry import Registry
from benchmark.report.display import one_line, printable
from benchmark.runner import DEFAULT_TIMEOUT_S

if TYPE_CHECKING:
    from benchmark.metrics import Metrics
    from benchmark.harness import Publication, RunSummary
    from benchmark.history.regressions import Thresholds
    from benchmark.store import ResultStore

DEFAULT_OUT = Path("reports") / "latest"


class ReportedError(click.ClickException):
    """A :class:`~benchmark.errors.TrackbenchError` shown as ``Error: ...``, exit status 2."""

    exit_code = 2


EXIT_FAILED = 1
"""A cell failed or a plugin was left out; everything else was done."""
EXIT_INTERRUPTED = 130
"""The user's Ctrl-C (128 + SIGINT)."""


class TrackbenchGroup(click.Group):
    """A command group that reports trackbench's own errors without a traceback.

    It also sets the exit status for the user's Ctrl-C, and for plugins that
    were left out while the command otherwise succeeded.
    """

    def invoke(self, ctx: click.Context) -> Any:
        try:
            result = super().invoke(ctx)
        except TrackbenchError as exc:
            raise ReportedError(printable(str(exc))) from exc
        except KeyboardInterrupt:
            click.echo("Interrupted.", err=True)
            ctx.exit(EXIT_INTERRUPTED)
        session = ctx.obj
        if isinstance(session, Session) and session.problems:
            ctx.exit(EXIT_FAILED)
        return result


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


@dataclasses.dataclass
class Session:
    """State shared by the commands of one invocation: plugin options and the registry."""

    disable: tuple[str, ...] = ()
    strict_plugins: bool = False
    _registry: Registry | None = None

    @property
    def registry(self) -> Registry:
        """Trackers and suites of every plugin not disabled, loaded on first use.

        Plugins left out are reported on stderr when the registry is loaded.
        """
        if self._registry is None:
            self._registry = plugins.load_registry(disable=self.disable, strict=self.strict_plugins)
            for problem in self._registry.problems:
                click.echo(f"Warning: {one_line(problem)}", err=True)
        return self._registry

    @property
    def problems(self) -> list[str]:
        """Plugins left out, if the registry was loaded."""
        return self._registry.problems if self._registry is not None else []


@click.group(cls=TrackbenchGroup)
@click.option(
    "--disable",
    "disable",
    multiple=True,
    metavar="NAME",
    help="Block the plugin with this entry-point name (repeatable).",
)
@click.option(
    "--strict-plugins",
    is_flag=True,
    help="A plugin that fails to import is an error (exit 2), not a warning that leaves its trackers out.",
)
@click.version_option(package_name="subsea-trackbench", prog_name="trackbench")
@click.pass_context
def main(ctx: click.Context, disable: tuple[str, ...], strict_plugins: bool) -> None:
    """trackbench: a benchmark for subsea cable and pipeline trackers."""
    ctx.obj = Session(disable, strict_plugins)


@main.command("list")
@click.pass_obj
def list_trackers(session: Session) -> None:
    """List the trackers with their origin and parameters."""
    trackers = session.registry.trackers
    if not trackers:
        click.echo("No trackers registered.")
    for problem in session.problems:
        click.echo(f"unavailable: {one_line(problem)}")
    for entry in trackers.values():
        click.echo(
            f"{entry.name} {entry.version}  modality {entry.modality}  "
            f"from {entry.origin.distribution} (plugin {entry.origin.plugin})"
        )
        values = dataclasses.asdict(entry.params)
        if not values:
            click.echo("    (no parameters)")
        for key, value in values.items():
            click.echo(f"    {key} = {value!r}")


@main.command("datasets")
@click.pass_obj
def list_datasets(session: Session) -> None:
    """List the suites and their sequences, with the conditions each drawn sequence was drawn under."""
    from benchmark.scenes.draws import condition_label

    suites = session.registry.suites
    if not suites:
        click.echo("No suites registered.")
    for suite in suites.values():
        roles = ([] if suite.scored else ["training split, not scored unless named"]) + (
            [f"trains on {suite.training}"] if suite.training else []
        )
        role = f"  [{'; '.join(roles)}]" if roles else ""
        click.echo(f"{suite.name}  from {suite.origin.distribution} (plugin {suite.origin.plugin}){role}")
        for sequence in suite.sequences:
            info = sequence.info
            frames = "?" if info.n_frames is None else str(info.n_frames)
            description = str(info.extra.get("description", "")).strip()
            drawn = info.extra.get("conditions") or {}
            if drawn:
                described = ", ".join(f"{name} {condition_label(value)}" for name, value in drawn.items())
                description = f"{description} Drawn: {described}.".strip()
            line = f"    {info.name}  {info.modality}  {frames} frames"
            click.echo(f"{line}  {description}" if description else line)


def _show(publication: Publication, metrics: Metrics) -> None:
    from benchmark.report import to_text

    click.echo(to_text(publication.boards, problems=publication.problems, metrics=metrics))
    for path in publication.files:
        click.echo(f"wrote {path}", err=True)


cache_option = click.option(
    "--cache",
    type=click.Path(file_okay=False, path_type=Path),
    envvar=CACHE_ENV,
    default=None,
    help=f"Folder of the frame cache (default: ${CACHE_ENV}, else the platform's user cache folder).",
)


@main.group("cache")
def cache_group() -> None:
    """The frame cache: simulated sequences rendered once, read by every run."""


@cache_group.command("info")
@cache_option
def cache_info(cache: Path | None) -> None:
    """List the cached sequences, their sizes and the cache's folder."""
    from benchmark.frame_cache import FrameCache

    frames = FrameCache(cache)
    entries = frames.entries()
    for entry in entries:
        count = "?" if entry.frames is None else entry.frames
        size = f"{entry.size_bytes / 1e6:.1f} MB"
        click.echo(f"{entry.name}  {entry.modality}  {count} frames  {size}  {entry.path.name}")
    total = sum(entry.size_bytes for entry in entries)
    leftovers = frames.leftovers()
    extra = f", {len(leftovers)} leftover files" if leftovers else ""
    click.echo(f"{frames.folder}: {len(entries)} sequences, {total / 1e6:.1f} MB{extra}")


@cache_group.command("clear")
@cache_option
def cache_clear(cache: Path | None) -> None:
    """Remove every cached sequence; the next run renders them again."""
    from benchmark.frame_cache import FrameCache

    frames = FrameCache(cache)
    removed, freed = frames.clear()
    click.echo(f"{frames.folder}: removed {removed} sequences, {freed / 1e6:.1f} MB")


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
    click.option(
        "--init",
        type=click.Choice(["truth", "none"]),
        default="truth",
        show_default=True,
        help="Initialise trackers from the first frame's ground truth, or not.",
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
]
"""The options of ``run`` that choose and run the cells, shared by ``nightly``; ``--out`` is each command's own."""


def run_options(command: Callable[..., Any]) -> Callable[..., Any]:
    """Add the options of :data:`_RUN_OPTIONS` to a command, in the order ``--help`` lists them."""
    for option in reversed(_RUN_OPTIONS):
        command = option(command)
    return command


@main.command("run")
@run_options
@click.option(
    "--out",
    type=click.Path(file_okay=False, path_type=Path),
    default=DEFAULT_OUT,
    show_default=True,
    help="Folder for results.sqlite and the leaderboards.",
)
@click.pass_context
def run(ctx: click.Context, out: Path, **options: Any) -> None:
    """Run trackers on datasets, store the cells and publish the leaderboard.

    Exits with 1 after publishing if a cell ended in error or timeout.
    """
    summary = _run_benchmark(ctx, out, **options)
    if not summary.clean:
        ctx.exit(EXIT_FAILED)


def _run_benchmark(
    ctx: click.Context,
    out: Path,
    *,
    suites: tuple[str, ...],
    trackers: tuple[str, ...],
    datasets: tuple[str, ...],
    seeds: int,
    jobs: int | None,
    in_process: bool,
    init: str,
    resume: bool,
    timeout: float,
    params: tuple[str, ...],
    train: tuple[str, ...],
    executor: str,
    scheduler: str | None,
    cache: Path | None,
    no_cache: bool,
) -> RunSummary:
    """Run the cells the options of :func:`run_options` select into ``out``, show the board and say how it went.

    Exits with 130 on the user's Ctrl-C, after publishing the cells finished.
    """
    from benchmark.executors import ExecutorOptions, open_executor
    from benchmark.frame_cache import FrameCache
    from benchmark.harness import run_benchmark
    from benchmark.progress import TerminalProgress
    from benchmark.selection import Selection, select_cells

    session: Session = ctx.obj
    registry = session.registry
    cells = select_cells(registry, Selection(trackers, suites, datasets, params, seeds, init, train))
    options = {key: list(value) if isinstance(value, tuple) else value for key, value in ctx.params.items()}
    progress = TerminalProgress()
    runner = open_executor(executor, ExecutorOptions(jobs, in_process, scheduler))
    try:
        summary = run_benchmark(
            cells,
            registry.modalities,
            out,
            executor=runner,
            frame_cache=None if no_cache else FrameCache(cache),
            timeout_s=timeout,
            resume=resume,
            argv=sys.argv,
            options={**options, "out": str(out), "disable": list(session.disable)},
            problems=registry.problems,
            log=progress.write,
            progress=progress,
            metrics=registry.metrics,
        )
    finally:
        runner.close()
    _show(summary.publication, registry.metrics)
    click.echo(summary.describe(), err=True)
    if summary.interrupted:
        ctx.exit(128 + summary.interrupted)  # 130 for Ctrl-C, 143 for SIGTERM
    failed = summary.statuses.total() - summary.statuses["ok"]
    if failed:
        click.echo(f"{failed} of {summary.statuses.total()} cells did not end ok.", err=True)
    return summary


DEFAULT_HISTORY = Path("reports") / "history.sqlite"
DEFAULT_SITE = Path("reports") / "site"
EXIT_REGRESSION = 3
"""``nightly`` found a regression (after storing the run and writing the site)."""

history_option = click.option(
    "--history",
    default=str(DEFAULT_HISTORY),
    show_default=True,
    metavar="FILE|URL",
    help="The history database: an SQLite file or an SQLAlchemy URL (postgresql://...).",
)
site_option = click.option(
    "--site",
    type=click.Path(file_okay=False, path_type=Path),
    default=DEFAULT_SITE,
    show_default=True,
    help="Folder the static HTML report is written to.",
)


def threshold_options(command: Callable[..., Any]) -> Callable[..., Any]:
    """Add ``--min-effect METRIC=VALUE`` and ``--window N``, the thresholds of a regression."""
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
        "or fps (default 0.1) (repeatable).",
    )(command)


def _thresholds(min_effects: tuple[str, ...], window: int) -> Thresholds:
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
    return Thresholds(window=window, overrides=overrides)


@main.command("nightly")
@run_options
@click.option(
    "--out",
    type=click.Path(file_okay=False, path_type=Path),
    default=Path("reports") / "nightly",
    show_default=True,
    help="Folder for the run's results.sqlite and leaderboards.",
)
@history_option
@site_option
@threshold_options
@click.pass_context
def nightly(
    ctx: click.Context,
    out: Path,
    history: str,
    site: Path,
    min_effects: tuple[str, ...],
    window: int,
    **options: Any,
) -> None:
    """Run the benchmark, add the run to the history, report its changes and rewrite the site.

    Takes every option of run.  Exits with 3 when a regression was found,
    else with 1 when a cell failed, as run does.
    """
    from datetime import UTC, datetime

    from benchmark.history.database import History
    from benchmark.history.nightly import describe_changes, record_nightly
    from benchmark.history.regressions import find_changes
    from benchmark.site import build_site

    thresholds = _thresholds(min_effects, window)
    started = datetime.now(UTC).isoformat(timespec="seconds")
    summary = _run_benchmark(ctx, out, **options)
    registry = ctx.obj.registry
    with History(history) as database:
        run_id = record_nightly(
            database,
            out,
            summary.publication.run_id,
            registry.modalities,
            started=started,
            argv=sys.argv,
            seeds=options["seeds"],
            metrics=registry.metrics,
        )
        changes = find_changes(database.cells(), run_id, thresholds, metrics=registry.metrics)
        index = build_site(database, site, registry.modalities, thresholds=thresholds, metrics=registry.metrics)
    click.echo(describe_changes(changes, f"Changes of nightly run {run_id}"))
    click.echo(f"history {history}: run {run_id}; site {index}", err=True)
    if (changes["verdict"] == "regression").any():
        ctx.exit(EXIT_REGRESSION)
    if not summary.clean:
        ctx.exit(EXIT_FAILED)


@main.command("compare")
@click.argument("run_a", type=int)
@click.argument("run_b", type=int)
@history_option
@threshold_options
@click.pass_obj
def compare(session: Session, run_a: int, run_b: int, history: str, min_effects: tuple[str, ...], window: int) -> None:
    """Print what changed from nightly run RUN_A to RUN_B of the history.

    Speeds are compared only when both ran on the same machine.
    """
    from benchmark.errors import DataError
    from benchmark.history.database import History
    from benchmark.history.nightly import describe_changes
    from benchmark.history.regressions import find_changes

    thresholds = _thresholds(min_effects, window)
    with History(history, must_exist=True) as database:
        cells = database.cells([run_a, run_b])
    missing = sorted({run_a, run_b} - set(cells["run_id"]))
    if missing:
        raise DataError(f"history database {history}: no run {', '.join(map(str, missing))}")
    changes = find_changes(cells, run_b, thresholds, against=[run_a], metrics=session.registry.metrics)
    click.echo(describe_changes(changes, f"Run {run_a} -> {run_b}"))


@main.command("report")
@history_option
@site_option
@threshold_options
@click.pass_obj
def report_command(session: Session, history: str, site: Path, min_effects: tuple[str, ...], window: int) -> None:
    """Rebuild the static HTML report from the history database, without running anything."""
    from benchmark.errors import DataError
    from benchmark.history.database import History
    from benchmark.site import build_site

    with History(history, must_exist=True) as database:
        if database.runs().empty:
            raise DataError(f"history database {history}: no runs yet (run 'trackbench nightly' first)")
        index = build_site(
            database,
            site,
            session.registry.modalities,
            thresholds=_thresholds(min_effects, window),
            metrics=session.registry.metrics,
        )
    click.echo(f"wrote {index}")


def _results_store(out: Path) -> ResultStore:
    """The results database in ``out``, which must hold at least one run."""
    from benchmark.errors import DataError
    from benchmark.store import DATABASE_NAME, ResultStore

    database = out / DATABASE_NAME
    if not database.is_file():
        raise DataError(f"{database}: no results database (run 'trackbench run --out {out}' first)")
    store = ResultStore(database)
    if store.latest_run() is None:
        store.close()
        raise DataError(f"{database}: no finished cells yet")
    return store


OUT_OPTION = click.option(
    "--out",
    type=click.Path(file_okay=False, path_type=Path),
    default=DEFAULT_OUT,
    show_default=True,
    help="Folder holding results.sqlite; reports are written there.",
)


@main.command("leaderboard")
@OUT_OPTION
@click.option("--all-runs", is_flag=True, help="Take the latest cell of every run, not only the latest run.")
@click.pass_obj
def leaderboard_command(session: Session, out: Path, all_runs: bool) -> None:
    """Print and export the leaderboard of an existing results database.

    The leaderboard of a run holds the cells it ran and those it resumed;
    for each tracker, dataset, seed and initialisation the latest cell.
    """
    from benchmark.harness import publish

    with _results_store(out) as store:
        metrics = session.registry.metrics
        _show(publish(store, session.registry.modalities, out, all_runs=all_runs, metrics=metrics), metrics)


@main.command("tables")
@click.argument("suite")
@OUT_OPTION
@click.option("--metric", "metrics", multiple=True, help="Board column to show (repeatable; default: every RMSE).")
@click.pass_obj
def tables_command(session: Session, suite: str, out: Path, metrics: tuple[str, ...]) -> None:
    """Print SUITE's results of the latest run as one table per case.

    For suites whose sequences are named SUITE/CASE-CONDITION, such as
    stereo/case1-slow: rows are metric and tracker, columns the conditions,
    as in Tables 6-8 of Sinisterra et al.  Also written to
    OUT/tables_SUITE.md.
    """
    from benchmark.files import write_text_atomically
    from benchmark.leaderboard import load_leaderboards
    from benchmark.report.grid import grid_markdown, grid_tables
    from benchmark.selection import SelectionError

    suites = session.registry.suites
    if suite not in suites:
        raise SelectionError(f"unknown suite {suite!r} (known: {', '.join(sorted(suites)) or 'none'})")
    order = [sequence.identity.name for sequence in suites[suite].sequences]
    with _results_store(out) as store:
        boards = load_leaderboards(
            store, session.registry.modalities, store.latest_run(), metrics=session.registry.metrics
        )
    rows = [board[board["dataset"].isin(order)] for board in boards.values()]
    board = next((part for part in rows if not part.empty), None)
    if board is None:
        raise SelectionError(f"the latest run in {out} has no results for suite {suite!r}")
    shown = list(metrics) or [column for column in board.columns if column.startswith("rmse_")]
    unknown = [metric for metric in shown if metric not in board.columns]
    if unknown:
        raise SelectionError(f"no column {', '.join(unknown)} (known: {', '.join(board.columns)})")
    text = grid_markdown(grid_tables(board, shown, order), f"{suite}: results per case")
    click.echo(text)
    path = write_text_atomically(out / f"tables_{suite}.md", text, "tables")
    click.echo(f"wrote {path}", err=True)


@main.command("diagnose")
@click.option("--tracker", required=True, metavar="NAME", help="The tracker whose observation model to test.")
@click.option("--suite", "suites", multiple=True, metavar="SUITE", help="Every sequence of a suite (repeatable).")
@click.option(
    "--dataset",
    "datasets",
    multiple=True,
    metavar="NAME|PATH",
    help="A registered sequence (suite/name) or a sequence file (repeatable).",
)
@OUT_OPTION
@click.pass_obj
def diagnose_command(
    session: Session, tracker: str, suites: tuple[str, ...], datasets: tuple[str, ...], out: Path
) -> None:
    """Print the likelihood ceiling of a tracker on each selected camera sequence.

    On every labelled frame, the states in a window around the true cable
    are scored with the tracker's own observation model; the ceiling is the
    share of frames whose best-scoring state is correct (Foresti's rule),
    the most a tracker reporting that model's best state can reach.  Beside
    it: the tracker's correct_pct in its latest run in OUT/results.sqlite
    with the same parameters, if any.  Also written to OUT/diagnose_NAME.md.
    """
    from contextlib import nullcontext

    from benchmark.files import make_folder, write_text_atomically
    from benchmark.modalities.camera.diagnostics import ceiling_markdown, ceiling_report
    from benchmark.selection import select_sequences, select_trackers
    from benchmark.store import DATABASE_NAME, ResultStore

    registry = session.registry
    (entry,) = select_trackers(registry, [tracker])
    sequences = select_sequences(registry, suites, datasets)
    database = out / DATABASE_NAME
    with ResultStore(database) if database.is_file() else nullcontext() as store:
        table, skipped = ceiling_report(entry, sequences, registry.modalities, store)
    for line in skipped:
        click.echo(line, err=True)
    text = ceiling_markdown(table, entry.name)
    click.echo(text)
    path = write_text_atomically(make_folder(out) / f"diagnose_{entry.name}.md", text, "diagnosis")
    click.echo(f"wrote {path}", err=True)


@main.command("pose-table")
@click.option("--tracker", required=True, metavar="NAME", help="A camera tracker that reports the camera pose.")
@click.option("--dataset", required=True, metavar="NAME|PATH", help="A camera sequence whose truth has the pose.")
@click.option("--first", type=click.IntRange(min=0), default=0, show_default=True, help="First frame shown.")
@click.option("--frames", type=click.IntRange(min=1), default=12, show_default=True, help="Number of frames shown.")
@click.option(
    "--init",
    type=click.Choice(["truth", "none"]),
    default="none",
    show_default=True,
    help="Start from the first frame's truth, or from the tracker's own prior (the paper's x_0).",
)
@OUT_OPTION
@click.pass_obj
def pose_table_command(
    session: Session, tracker: str, dataset: str, first: int, frames: int, init: str, out: Path
) -> None:
    """Print a pose tracker's measurement, state, error and covariance per frame, as Foresti's Tables III-IV.

    The tracker runs in this process from frame 0; frames FIRST to
    FIRST+FRAMES-1 are shown.  Also written to OUT/pose_NAME.md.
    """
    from benchmark.files import make_folder, write_text_atomically
    from benchmark.modalities.camera.pose_table import pose_table
    from benchmark.report.markdown import titled_table
    from benchmark.selection import select_sequences, select_trackers

    (entry,) = select_trackers(session.registry, [tracker])
    (sequence,) = select_sequences(session.registry, (), (dataset,))
    table = pose_table(entry.create(), sequence, first, frames, init == "truth")
    text = titled_table(table, f"{entry.name} on {sequence.info.name}, frames {first}-{first + len(table) - 1}")
    click.echo(text)
    path = write_text_atomically(make_folder(out) / f"pose_{entry.name}.md", text, "pose table")
    click.echo(f"wrote {path}", err=True)


@main.command("make-dataset")
@click.argument("suite")
@click.option(
    "--out", type=click.Path(file_okay=False, path_type=Path), required=True, help="Folder to write the sequences to."
)
@click.pass_obj
def make_dataset(session: Session, suite: str, out: Path) -> None:
    """Write every sequence of SUITE to disk in its modality's form.

    Camera sequences become PNG frames plus an image sequence file, sonar
    sequences a swath file.
    """
    from benchmark.io import export_sequence
    from benchmark.selection import SelectionError

    registry = session.registry
    if suite not in registry.suites:
        raise SelectionError(f"unknown suite {suite!r} (known: {', '.join(sorted(registry.suites)) or 'none'})")
    for sequence in registry.suites[suite].sequences:
        click.echo(export_sequence(sequence, out, registry.modalities))


@main.command("check")
@click.argument("names", nargs=-1, metavar="[NAME]...")
@click.option(
    "--frames", type=click.IntRange(min=1), default=60, show_default=True, help="Frames each run of a check reads."
)
@click.option(
    "--random-frames",
    type=click.IntRange(min=1),
    default=5,
    show_default=True,
    help="Frames of each random sequence the random_sequences check draws.",
)
@click.option(
    "--time-limit",
    "time_limit_s",
    type=Seconds(),
    default=60.0,
    show_default=True,
    help="Seconds of CPU time one check may use (and ten times as long of waiting) before it fails as a hang.",
)
@click.option(
    "--in-process",
    is_flag=True,
    help="Run the checks in this process (for a debugger); a tracker that ends the process ends the command.",
)
@click.pass_context
def check_command(
    ctx: click.Context,
    names: tuple[str, ...],
    frames: int,
    random_frames: int,
    time_limit_s: float,
    in_process: bool,
) -> None:
    """Run the conformance kit (benchmark.testing) on installed trackers: all of them, or those NAMEd.

    Each check runs in a worker process, so a tracker that crashes or hangs
    fails that check only. Prints one row per tracker and check, a tracker's
    failures first and those that follow from an earlier one marked so;
    `skip` for a check about a capability the tracker declares it lacks,
    `xfail` for one it lists in expected_failed_checks. Exit status 1 if any
    check failed (or passed while listed as expected to fail).
    """
    from benchmark.selection import select_trackers
    from benchmark.testing import check_tracker, checks
    from benchmark.testing.isolated import check_in_workers

    session: Session = ctx.obj
    registry = session.registry
    entries = select_trackers(registry, names)
    if in_process:
        results = (
            result
            for entry in entries
            for result in check_tracker(
                entry, registry=registry, n_frames=frames, random_frames=random_frames, time_limit_s=time_limit_s
            )
        )
    else:
        results = check_in_workers([entry.name for entry in entries], registry, frames, time_limit_s, random_frames)
    header = ("tracker", "check", "result")
    widths = [
        max(len(header[0]), *(len(entry.name) for entry in entries)),
        max(len(header[1]), *(len(check.name) for check in checks())),
        len("xpass "),
    ]

    def row(*cells: str) -> str:
        return "  ".join(cell.ljust(width) for cell, width in zip(cells, widths)) + "  " + cells[-1]

    click.echo(row(*header, "message"))
    counts = dict.fromkeys(CHECK_VERDICTS, 0)
    for result in results:
        counts[result.outcome] += 1
        verdict = CHECK_VERDICTS[result.outcome]
        click.echo(row(result.tracker, result.check, verdict, result.message or result.detail))
    summary = ", ".join(f"{count} {outcome}" for outcome, count in counts.items() if count or outcome == "failed")
    click.echo(f"{summary} ({len(entries)} trackers)")
    if counts["failed"] or counts["xpassed"]:
        ctx.exit(EXIT_FAILED)


CHECK_VERDICTS = {"passed": "ok", "failed": "FAIL", "skipped": "skip", "xfailed": "xfail", "xpassed": "XPASS"}
"""How ``trackbench check`` shows each outcome of a check."""


@main.command("new-tracker")
@click.argument("name")
@click.option(
    "--modality", default="camera", show_default=True, help="The registered modality the tracker reads."
)
@click.option(
    "--out",
    type=click.Path(file_okay=False, path_type=Path),
    default=Path("."),
    show_default=True,
    help="Folder in which the plugin folder NAME is made.",
)
@click.pass_context
def new_tracker_command(ctx: click.Context, name: str, modality: str, out: Path) -> None:
    """Write a minimal tracker plugin package into OUT/NAME: pyproject.toml, trackbench_NAME and a test.

    Then `pip install -e OUT/NAME`, `trackbench check NAME` and `pytest OUT/NAME/tests`.
    """
    from benchmark.scaffold import ScaffoldError, new_tracker

    modalities = ctx.obj.registry.modalities
    if modality not in modalities:
        raise ScaffoldError(f"unknown modality {modality!r} (registered: {', '.join(sorted(modalities)) or 'none'})")
    folder = new_tracker(name, modalities[modality], out)
    for path in sorted(p for p in folder.rglob("*") if p.is_file()):
        click.echo(path)
