"""The history database: every nightly run, its machine and commit, and each cell's summary, frames and pictures.

A nightly run (``trackbench nightly``) appends one row to ``runs`` and one
row per cell to ``cells``, copied from the run's results database
(:mod:`benchmark.store`) in one transaction.  Tables::

    runs(id, started, finished, version, commit, machine_key, machine JSON, argv JSON, seeds, load JSON)
    cells(id, run_id -> runs, tracker, tracker_version, tracker_key, params JSON, dataset,
          dataset_key, modality, seed, init, training, status, message, frames, elapsed_s,
          metrics JSON, deterministic, real_time)
    cell_frames(cell_id -> cells, frames BLOB)
    cell_pictures(cell_id -> cells, frame, outcome, png BLOB)
    run_boards(run_id -> runs, modality, board JSON)
    run_changes(run_id -> runs, changes JSON)
    cell_replays(cell_id -> cells, state, why, frames, command, size, digest, page BLOB)

These are the tables of :data:`benchmark.schema.HISTORY`, whose cells and
pictures share their columns with the results database's.

``load`` is how busy the machine was while the run ran
(:func:`benchmark.history.machine.LoadMeter`; ``{}`` in runs recorded
before it was kept).

``metrics`` holds the cell's value of every metric of its board
(:func:`benchmark.results.summarise`; a metric added later is empty in
earlier runs); ``cell_frames`` its frame table
(outcome, errors and step time of every frame, compressed JSON) and
``cell_pictures`` the frames it failed on, drawn
(:class:`benchmark.results.Picture`), so that the site can be rebuilt from
the history alone.  ``run_boards`` keeps the run's leaderboards as the nightly published
them, so that a site need not work them out again from every frame table;
``run_changes`` keeps what the nightly said of its run
(:func:`benchmark.history.regressions.find_changes`, after any repeat), so
that the site tells the same story.  ``cell_replays`` keeps what the nightly
did about the replay of each cell it chose to replay
(:mod:`benchmark.history.replays`): the replay page itself (compressed)
where it recorded one, else why not, and the ``trackbench replay`` command
that makes it.  Frames, pictures (about 0.5 MB for a camera cell
that failed often) and replays are kept for the last :data:`DETAILED_RUNS` runs only;
the summaries of every run stay, for the trends.

Runs recorded before the step's CPU time was measured timed the wall
clock only: their ``fps`` is read as ``wall_fps`` and their frames'
``step_ms`` as ``wall_ms`` (with ``step_ms`` empty), so that a trend of
``cpu_fps`` never starts with wall-clock numbers.

A *series* is what nightly runs are compared along: a tracker's name, the
dataset's identity key, the seed and the initialisation.  The tracker's
version and parameters (``tracker_key`` hashes them) are not part of it:
a change of either is exactly what the regression view must catch, and the
report names it beside the change.

The database is SQLite by default; any SQLAlchemy URL (``postgresql://...``)
works too, so a team can share one history.  A URL that names no driver
gets the one of :data:`DEFAULT_DRIVERS` (``postgresql://`` is psycopg's,
which the ``postgres`` extra installs).  Any database error, a missing
driver included, is a :class:`~benchmark.errors.DataError` naming the
database, on one line, with the URL's password masked
(:func:`shown_location`): the messages of a driver may quote the URL.
"""

from __future__ import annotations

import functools
import json
import re
import zlib
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass
from datetime import UTC, datetime
from pathlib import Path
from typing import Any, Concatenate, ParamSpec, TypeVar

import numpy as np
import pandas as pd
import sqlalchemy as sa
from sqlalchemy.exc import ArgumentError, SQLAlchemyError

from benchmark import schema
from benchmark.errors import DataError
from benchmark.files import resolved
from benchmark.leaderboard import board_metrics, error_columns
from benchmark.metrics import CORE, Metrics
from benchmark.modality import Modality
from benchmark.results import Picture, summarise
from benchmark.store import ResultStore

DETAILED_RUNS = 30
"""How many of the latest runs keep their cells' frame tables and pictures."""

SERIES = ["tracker", "dataset_key", "seed", "init"]
"""The columns of :meth:`History.cells` that identify a series of comparable cells."""

ESTIMATED = "estimated_frames"
"""The column of :meth:`History.cells` counting a cell's frames with an estimate and a truth: the frames its RMSEs
average over (empty for runs recorded before it was kept)."""

_metadata = schema.HISTORY
_runs = schema.history_runs
_cells = schema.history_cells
_cell_frames = schema.history_cell_frames
_cell_pictures = schema.history_cell_pictures
_run_changes = schema.history_run_changes
_run_boards = schema.history_run_boards
_cell_replays = schema.history_cell_replays

_P = ParamSpec("_P")
_T = TypeVar("_T")


DEFAULT_DRIVERS = {"postgresql": "psycopg"}
"""The driver of a URL that names a database but no driver (``postgresql://...``), by database.

SQLAlchemy 2.0 would take psycopg2 for ``postgresql://``, 2.1 psycopg;
naming it keeps the one the ``postgres`` extra installs, whatever the
version.  A URL that names its driver (``postgresql+psycopg2://``) keeps it.
"""

DRIVER_INSTALLS = {
    "psycopg": 'pip install "subsea-trackbench[postgres]"',
    "psycopg2": "pip install psycopg2-binary",
}
"""The command that installs a database driver, by the name of the module that could not be imported."""

_MASK = "***"
_URL_PASSWORD = re.compile(r"(?<=://)(?P<user>[^:/@]*):(?P<password>.*)@")
"""The password of a URL found by its form alone, up to the last ``@`` (masking too much rather than too little)."""
_SHORTEST_MASKED_ELSEWHERE = 4
"""A password shorter than this is masked in the URL only, not wherever its letters occur in a driver's message,
which masking a one-letter password would make unreadable (and such a password guards nothing)."""


def _reports_database_errors(method: Callable[Concatenate[History, _P], _T]) -> Callable[Concatenate[History, _P], _T]:
    @functools.wraps(method)
    def wrapper(self: History, /, *args: _P.args, **kwargs: _P.kwargs) -> _T:
        try:
            return method(self, *args, **kwargs)
        except SQLAlchemyError as exc:
            raise self._error(f"{type(exc).__name__}: {exc}") from exc

    return wrapper


def database_url(location: str | Path) -> str:
    """An SQLAlchemy URL as given, or the URL of an SQLite file at a path."""
    text = str(location)
    return text if "://" in text else f"sqlite:///{resolved(Path(text).expanduser())}"


def shown_location(location: str | Path) -> str:
    """A history's location as it may be printed: a URL with its password masked as ``***``, a path as given.

    Examples
    --------
    >>> shown_location("postgresql://ci:s3cret@db.example/history")
    'postgresql://ci:***@db.example/history'
    >>> shown_location("reports/history.sqlite")
    'reports/history.sqlite'
    """
    text = str(location)
    if "://" not in text:
        return text
    try:
        return sa.make_url(text).render_as_string(hide_password=True)
    except (ArgumentError, ValueError):
        return _without_url_passwords(text)


def _without_url_passwords(text: str) -> str:
    """``text`` with the password of every URL in it masked, found by their form alone (no URL is parsed)."""
    return _URL_PASSWORD.sub(rf"\g<user>:{_MASK}@", text)


def _passwords(location: str | Path) -> list[str]:
    """The forms in which a URL's password may appear in a message, longest first: as written and as decoded."""
    text = str(location)
    written = _URL_PASSWORD.search(text)
    forms = {written["password"]} if written else set()
    try:
        decoded = sa.make_url(text).password if "://" in text else None
    except (ArgumentError, ValueError):
        decoded = None
    forms |= {str(decoded)} if decoded else set()
    return sorted((form for form in forms if form), key=len, reverse=True)


def _pack(frames: pd.DataFrame) -> bytes:
    return zlib.compress(frames.to_json(orient="split", index=False, double_precision=15).encode())


def _dump_table(table: pd.DataFrame) -> str:
    """A table as JSON text with its column types, which :func:`_load_table` reads back equal."""
    split = json.loads(table.to_json(orient="split", index=False, double_precision=15))
    return json.dumps({"dtypes": {str(c): str(t) for c, t in table.dtypes.items()}, "table": split})


def _load_table(text: str) -> pd.DataFrame:
    """A table written by :func:`_dump_table`."""
    from io import StringIO

    kept = json.loads(text)
    return pd.read_json(StringIO(json.dumps(kept["table"])), orient="split", dtype=kept["dtypes"])


RECORDED = "recorded"
"""The state of a :class:`CellReplay` whose page was recorded."""


@dataclass(frozen=True)
class CellReplay:
    """What a nightly did about the replay of one of its cells (:mod:`benchmark.history.replays`).

    Attributes
    ----------
    cell_id : int
        The cell, in the history.
    state : str
        :data:`RECORDED`, or why there is no page: ``over budget``,
        ``no view`` (a modality the replay cannot show), ``failed`` (recording
        it raised) or ``no frames`` (the cell failed before its first frame).
    why : str
        The reason, as the cell page shows it; empty when recorded.
    frames : str
        The frames replayed, ``A:B`` (:class:`benchmark.replay.record.FrameRange`).
    command : str
        The ``trackbench replay`` command that makes the replay.
    size : int
        The page's size in bytes; 0 without one.
    digest : str
        A hash of the page; empty without one.
    page : bytes or None
        The page (HTML, UTF-8) when recorded.
    """

    cell_id: int
    state: str
    why: str
    frames: str
    command: str
    size: int = 0
    digest: str = ""
    page: bytes | None = None


REPLAY_COLUMNS = ["cell_id", "state", "why", "frames", "command", "size", "digest"]
"""The columns of :meth:`History.replays`: those of :class:`CellReplay` but its page."""


WALL_TIMED = {"fps": "wall_fps"}
"""Metrics of runs recorded before the CPU timing, by the name they are read under: they timed the wall clock."""


def _unpack(blob: bytes) -> pd.DataFrame:
    """A frame table packed by :func:`_pack`: ``frame`` an integer, ``outcome`` text, every other column a float.

    Read column by column with the table's known types rather than by
    :func:`pandas.read_json`, which guesses each column's type and takes
    four times as long (a site reads every frame table of a run).
    """
    table = json.loads(zlib.decompress(blob))
    names, rows = table["columns"], table["data"]
    values = list(zip(*rows, strict=True)) if rows else [()] * len(names)
    frames = pd.DataFrame(
        {
            name: pd.array(column, dtype="str") if name == "outcome"
            else np.array(column, dtype=float).astype(np.int64 if name == "frame" else float, copy=False)
            for name, column in zip(names, values, strict=True)
        }
    )
    if "step_ms" in frames and "wall_ms" not in frames:  # recorded before the CPU timing: step_ms was wall time
        frames = frames.rename(columns={"step_ms": "wall_ms"})
        frames.insert(list(frames.columns).index("wall_ms"), "step_ms", float("nan"))
    return frames


def _metrics_of(text: str) -> dict[str, Any]:
    """A cell's metrics as stored, those of a run recorded before the CPU timing under their wall-time names."""
    values = json.loads(text)
    for old, new in WALL_TIMED.items():
        if old in values:
            values.setdefault(new, values.pop(old))
    return values


class History:
    """A history database, created on first use.

    Parameters
    ----------
    location : str or path-like
        An SQLite file (its folder is created) or an SQLAlchemy URL.
    must_exist : bool
        Refuse an SQLite file that does not exist yet, instead of creating it.

    Raises
    ------
    DataError
        If the database's driver is not installed (naming how to install
        it), or the database cannot be opened or is not a trackbench
        history; every method raises it, naming the database, for any
        database error.  The password of a URL never appears in it.
    """

    def __init__(self, location: str | Path, *, must_exist: bool = False) -> None:
        self.location = shown_location(location)
        """Where the database is, as it may be printed (its password masked)."""
        self._given = str(location)
        self._engine = self._open(database_url(location), must_exist)
        self._create()

    def after_fork(self) -> None:
        """In a process forked from the one that opened the history: leave the parent's connections to it.

        The forked process then opens connections of its own as it needs
        them, and the parent's stay the parent's (SQLAlchemy's advice for
        engines shared with a child process).
        """
        self._engine.dispose(close=False)

    def _error(self, problem: str) -> DataError:
        """A :class:`DataError` naming the database, on one line, with its password masked wherever it appears."""
        message = " ".join(f"history database {self.location}: {problem}".split())
        message = message.replace(self._given, self.location)
        for password in _passwords(self._given):
            if len(password) >= _SHORTEST_MASKED_ELSEWHERE:
                message = message.replace(password, _MASK)
        return DataError(message)

    def _open(self, url_text: str, must_exist: bool) -> sa.Engine:
        """The engine of the database at ``url_text``, its driver imported; an SQLite file's folder is created.

        Nothing is connected to yet: :meth:`_create` does that.
        """
        try:
            url = sa.make_url(url_text)
        except (ArgumentError, ValueError) as exc:
            raise self._error(f"neither a file nor an SQLAlchemy URL ({exc})") from exc
        if url.get_backend_name() == "sqlite" and url.database and url.database != ":memory:":
            path = Path(url.database)
            if must_exist and not path.is_file():
                raise self._error("no such file (run 'trackbench nightly' first)")
            try:
                path.parent.mkdir(parents=True, exist_ok=True)
            except OSError as exc:
                raise self._error(f"cannot create its folder ({exc.strerror or exc})") from exc
        if url.drivername in DEFAULT_DRIVERS:
            url = url.set(drivername=f"{url.drivername}+{DEFAULT_DRIVERS[url.drivername]}")
        try:
            return sa.create_engine(url)
        except ImportError as exc:
            module = exc.name or url.get_driver_name()
            install = DRIVER_INSTALLS.get(module)
            how = f"install it with: {install}" if install else "install the Python package that provides it"
            raise self._error(f"its driver {module} ({url.drivername}) cannot be imported ({exc}); {how}") from exc
        except (SQLAlchemyError, ValueError) as exc:
            raise self._error(f"{type(exc).__name__}: {exc}") from exc

    @_reports_database_errors
    def _create(self) -> None:
        """Create the tables that are missing, after refusing, untouched, a database that is not a history.

        A database with tables but none of a history's is another
        program's; one whose table of a history's name lacks its columns is
        not ours either.  Only an empty database or a history (perhaps of
        an older trackbench, missing newer tables, or newer columns that
        have a default, which are added) gets tables.
        """
        inspector = sa.inspect(self._engine)
        existing = set(inspector.get_table_names())
        ours = {table.name for table in _metadata.sorted_tables}
        if existing and not existing & ours:
            raise self._error(
                f"holds other tables ({', '.join(sorted(existing)[:5])}) and "
                "none of a trackbench history's; the database was left unchanged"
            )
        for table in _metadata.sorted_tables:
            if table.name not in existing:
                continue
            found = {column["name"] for column in inspector.get_columns(table.name)}
            if any(column.server_default is None for column in table.columns if column.name not in found):
                raise self._error(
                    f"its table {table.name!r} is not a trackbench history's "
                    "(columns missing); the database was left unchanged"
                )
        with self._engine.begin() as connection:
            schema.add_missing_columns(connection, _metadata)
        _metadata.create_all(self._engine)

    def close(self) -> None:
        """Release the database's connections."""
        self._engine.dispose()

    def __enter__(self) -> History:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    @_reports_database_errors
    def record(
        self,
        results: ResultStore,
        run_id: int,
        modalities: Mapping[str, Modality],
        *,
        started: str,
        version: str,
        commit: str,
        machine: Mapping[str, Any],
        machine_key: str,
        argv: Sequence[str],
        seeds: int,
        metrics: Metrics = CORE,
        load: Mapping[str, Any] | None = None,
        boards: Mapping[str, pd.DataFrame] | None = None,
    ) -> int:
        """Copy a finished run of a results database into the history and return its history id.

        Parameters
        ----------
        results : ResultStore
            The run's results database.
        run_id : int
            The run in ``results`` (its cells, run or resumed).
        modalities : Mapping
            The registered modalities, whose scorers name the error columns.
        started, version, commit, machine, machine_key, argv, seeds
            When the nightly started (ISO 8601), trackbench's version and git
            commit, the machine (:mod:`benchmark.history.machine`), the
            command line (kept with the password of any URL in it masked)
            and the number of seeds.
        metrics : Metrics
            The catalogue of metrics each cell's summary holds (the registry's).
        load : Mapping, optional
            How busy the machine was during the run
            (:meth:`benchmark.history.machine.LoadMeter.stop`), JSON values.
        boards : Mapping, optional
            The run's leaderboards by modality, as published
            (:attr:`benchmark.harness.Publication.boards`), kept as they are.
        """
        cells = results.cells(run_id)
        frames = results.frame_tables(cells["id"])
        pictures = results.pictures(cells["id"])
        by_cell = {int(cell_id): group.drop(columns="cell_id") for cell_id, group in frames.groupby("cell_id")}
        with self._engine.begin() as connection:
            history_run = connection.execute(
                _runs.insert().values(
                    started=started,
                    finished=datetime.now(UTC).isoformat(timespec="seconds"),
                    version=version,
                    commit=commit,
                    machine_key=machine_key,
                    machine=json.dumps(dict(machine)),
                    argv=json.dumps([_without_url_passwords(argument) for argument in argv]),
                    seeds=seeds,
                    load=json.dumps(dict(load or {})),
                )
            ).inserted_primary_key[0]
            for cell in cells.itertuples(index=False):
                table = by_cell.get(int(cell.id), frames.iloc[0:0].drop(columns="cell_id"))
                modality = modalities.get(cell.modality)
                of_board = board_metrics(metrics, cell.modality, modality, table)
                summary = summarise(table, of_board) | {ESTIMATED: _estimated(table, error_columns(modality, table))}
                cell_id = connection.execute(
                    _cells.insert().values(
                        run_id=history_run,
                        **{name: getattr(cell, name) for name in _COPIED},
                        seed=int(cell.seed),
                        frames=int(cell.frames),
                        elapsed_s=float(cell.elapsed_s),
                        metrics=json.dumps(summary),
                    )
                ).inserted_primary_key[0]
                connection.execute(_cell_frames.insert().values(cell_id=cell_id, frames=_pack(table)))
                rows = [
                    {"cell_id": cell_id, "frame": p.frame, "outcome": p.outcome, "png": p.png}
                    for p in pictures.get(int(cell.id), [])
                ]
                if rows:
                    connection.execute(_cell_pictures.insert(), rows)
            kept_boards = [
                {"run_id": history_run, "modality": modality, "board": _dump_table(board)}
                for modality, board in (boards or {}).items()
            ]
            if kept_boards:
                connection.execute(_run_boards.insert(), kept_boards)
            self._forget_details(connection)
        return int(history_run)

    @staticmethod
    def _forget_details(connection: sa.Connection) -> None:
        """Drop the frame tables, pictures and replays of the runs older than the last :data:`DETAILED_RUNS`."""
        kept = sa.select(_runs.c.id).order_by(_runs.c.id.desc()).limit(DETAILED_RUNS)
        old_cells = sa.select(_cells.c.id).where(_cells.c.run_id.not_in(kept.scalar_subquery()))
        for table in (_cell_frames, _cell_pictures, _cell_replays):
            connection.execute(table.delete().where(table.c.cell_id.in_(old_cells.scalar_subquery())))

    @_reports_database_errors
    def record_changes(self, run_id: int, changes: pd.DataFrame) -> None:
        """Keep what the nightly said of run ``run_id``: its table of changes, replacing any kept before."""
        text = _dump_table(changes)
        with self._engine.begin() as connection:
            connection.execute(_run_changes.delete().where(_run_changes.c.run_id == int(run_id)))
            connection.execute(_run_changes.insert().values(run_id=int(run_id), changes=text))

    @_reports_database_errors
    def record_replays(self, replays: Iterable[CellReplay]) -> None:
        """Keep what a nightly did about its cells' replays, replacing what was kept for the same cells."""
        rows = [
            {**{name: getattr(replay, name) for name in REPLAY_COLUMNS},
             "page": None if replay.page is None else zlib.compress(replay.page)}
            for replay in replays
        ]
        if not rows:
            return
        with self._engine.begin() as connection:
            connection.execute(_cell_replays.delete().where(_cell_replays.c.cell_id.in_([r["cell_id"] for r in rows])))
            connection.execute(_cell_replays.insert(), rows)

    @_reports_database_errors
    def replays(self) -> pd.DataFrame:
        """What the nightlies did about their cells' replays, one row per cell, without pages: :data:`REPLAY_COLUMNS`."""
        columns = [_cell_replays.c[name] for name in REPLAY_COLUMNS]
        with self._engine.connect() as connection:
            rows = connection.execute(sa.select(*columns).order_by(_cell_replays.c.cell_id)).all()
        return pd.DataFrame([tuple(row) for row in rows], columns=REPLAY_COLUMNS)

    @_reports_database_errors
    def replay_page(self, cell_id: int) -> bytes:
        """The replay page recorded for cell ``cell_id`` (HTML, UTF-8)."""
        with self._engine.connect() as connection:
            blob = connection.execute(
                sa.select(_cell_replays.c.page).where(_cell_replays.c.cell_id == int(cell_id))
            ).scalar_one_or_none()
        if blob is None:
            raise self._error(f"no replay page of cell {cell_id} (only the last {DETAILED_RUNS} runs keep theirs)")
        try:
            return zlib.decompress(blob)
        except zlib.error as exc:
            raise self._error(f"the replay page of cell {cell_id} cannot be read ({exc})") from None

    @_reports_database_errors
    def changes(self, run_id: int) -> pd.DataFrame | None:
        """The changes the nightly of run ``run_id`` kept (:meth:`record_changes`); None where it kept none."""
        with self._engine.connect() as connection:
            text = connection.execute(
                sa.select(_run_changes.c.changes).where(_run_changes.c.run_id == int(run_id))
            ).scalar_one_or_none()
        return None if text is None else self._kept_table(text, f"the changes of run {run_id}")

    @_reports_database_errors
    def boards(self, run_id: int) -> dict[str, pd.DataFrame] | None:
        """The leaderboards of run ``run_id`` by modality as its nightly published them; None where none were kept."""
        query = sa.select(_run_boards.c.modality, _run_boards.c.board).where(_run_boards.c.run_id == int(run_id))
        with self._engine.connect() as connection:
            rows = connection.execute(query.order_by(_run_boards.c.modality)).all()
        return {str(modality): self._kept_table(text, f"the {modality} board of run {run_id}") for modality, text in rows} or None

    def _kept_table(self, text: str, what: str) -> pd.DataFrame:
        """A table kept by :func:`_dump_table`; a :class:`DataError` naming it and the database if it is unreadable."""
        try:
            return _load_table(text)
        except (KeyError, TypeError, ValueError) as exc:
            raise DataError(f"history database {self.location}: {what} cannot be read ({type(exc).__name__}: {exc})") from None

    @_reports_database_errors
    def runs(self) -> pd.DataFrame:
        """Every run, oldest first: ``id``, ``started``, ``finished``, ``version``, ``commit``, ``machine_key``,
        ``machine`` (a dict), ``argv`` (a list), ``seeds`` and ``load`` (a dict, empty for older runs)."""
        with self._engine.connect() as connection:
            table = pd.DataFrame(connection.execute(sa.select(_runs).order_by(_runs.c.id)).mappings().all())
        if table.empty:
            return pd.DataFrame(columns=[column.name for column in _runs.columns])
        return table.assign(**{column: table[column].map(json.loads) for column in ("machine", "argv", "load")})

    @_reports_database_errors
    def cells(self, run_ids: Iterable[int] | None = None) -> pd.DataFrame:
        """The cells of some runs (default: all), one row each, their metrics as columns.

        Returns
        -------
        pandas.DataFrame
            The columns of ``cells`` (``params`` as a dict) with ``metrics``
            spread into a column per metric (``correct_pct``, ``rmse_*``,
            ``cpu_fps``, ``wall_fps``, ...; empty where a cell's run did not
            have it; the ``fps`` of older runs is ``wall_fps``) and
            :data:`ESTIMATED` (frames with an estimate and a truth), plus the
            run's ``started`` and ``machine_key``; ordered by run, then cell.
        """
        query = sa.select(_cells, _runs.c.started, _runs.c.machine_key).join(_runs).order_by(_cells.c.id)
        if run_ids is not None:
            query = query.where(_cells.c.run_id.in_([int(run) for run in run_ids]))
        with self._engine.connect() as connection:
            table = pd.DataFrame(connection.execute(query).mappings().all())
        if table.empty:
            return pd.DataFrame(columns=[*(column.name for column in _cells.columns), "started", "machine_key"])
        metrics = pd.DataFrame([_metrics_of(text) for text in table["metrics"]], index=table.index)
        table = table.drop(columns="metrics").assign(params=table["params"].map(json.loads))
        return pd.concat([table, metrics.drop(columns=["frames"], errors="ignore")], axis=1)

    @_reports_database_errors
    def frames(self, cell_id: int) -> pd.DataFrame:
        """The frame table of a cell: ``frame``, ``outcome``, the error columns, ``step_ms`` (CPU) and ``wall_ms``.

        A cell recorded before the CPU timing has its time as ``wall_ms`` and an empty ``step_ms``.
        """
        with self._engine.connect() as connection:
            blob = connection.execute(
                sa.select(_cell_frames.c.frames).where(_cell_frames.c.cell_id == int(cell_id))
            ).scalar_one_or_none()
        if blob is None:
            raise self._error(
                f"no frame table of cell {cell_id} (only the last {DETAILED_RUNS} runs keep theirs)"
            )
        return _unpack(blob)

    @_reports_database_errors
    def pictures(self, cell_id: int) -> list[Picture]:
        """The pictures of the frames a cell failed on, in frame order."""
        query = sa.select(_cell_pictures).where(_cell_pictures.c.cell_id == int(cell_id)).order_by("frame")
        with self._engine.connect() as connection:
            rows = connection.execute(query).mappings().all()
        return [Picture(int(row["frame"]), str(row["outcome"]), bytes(row["png"])) for row in rows]


def _estimated(frames: pd.DataFrame, errors: Sequence[str]) -> int:
    """The frames of a frame table with a finite error: those with an estimate and a truth."""
    present = [column for column in errors if column in frames]
    if not present:
        return 0
    values = frames[present].apply(pd.to_numeric, errors="coerce").to_numpy(dtype=float)
    return int(np.isfinite(values).any(axis=1).sum())


_COPIED = (
    "tracker",
    "tracker_version",
    "tracker_key",
    "params",
    "dataset",
    "dataset_key",
    "modality",
    "init",
    "training",
    "status",
    "message",
    "deterministic",
    "real_time",
)
"""Columns of a results database's cells copied as they are."""
