"""The results database: runs, cells and per-frame scores in SQLite.

Every ``trackbench run`` is a row of ``runs``; every finished cell is a row
of ``cells`` together with its frame rows and its pictures, written in one
transaction, so a run that is killed keeps every cell it finished and loses
only those in flight.  Only the main process writes; worker processes hand their results
back to it.

The tables are those of :data:`benchmark.schema.RESULTS`, whose cells and
pictures share their columns with the nightly history's
(:mod:`benchmark.schema`); the file stays a plain SQLite file.  Schema
(``PRAGMA user_version`` = :data:`SCHEMA_VERSION`)::

    runs(id, started, finished, argv JSON, options JSON, version, problems JSON)
    cells(id, run_id -> runs, tracker, tracker_version, tracker_key, params JSON,
          dataset, dataset_key, modality, seed, init, status, message, detail,
          frames, elapsed_s, finished, training, deterministic, real_time)
    run_cells(run_id -> runs, cell_id -> cells)
    frames(cell_id -> cells, position, frame, outcome, step_ms, wall_ms)
    frame_errors(cell_id, position, name, value)
    pictures(cell_id -> cells, frame, outcome, png BLOB)
    conditions(dataset_key, name, value JSON)

``frame_errors`` holds a frame's values by name: the scorer's error
columns, and on a closed-loop cell its ``loop_*`` values
(:class:`benchmark.results.LoopValues`); a value that is not finite is not
stored and reads back as NaN.  ``training`` names the training set of a tracker that learns (empty for
the others; :mod:`benchmark.training`); ``deterministic`` is 1 when the
tracker declares that it draws no random numbers; ``real_time`` is the
step time's source of a cell run in real time, empty for the others
(:mod:`benchmark.closedloop.real_time`; the mode is also in its
``tracker_key``, so that the two modes are never taken for one cell).
``problems`` lists, one line each, what went wrong in a run outside any
cell, such as a plugin that failed to import.  A cell is identified by
``(tracker_key, dataset_key, seed, init)`` (:class:`benchmark.results.CellKey`):
``dataset_key`` is the key of the dataset's identity
(:mod:`benchmark.identity`), ``dataset`` only the name it was shown under.
``status`` is ``ok``, ``error`` or ``timeout``; ``message`` is the one-line
reason and ``detail`` the traceback.  ``position`` numbers a cell's frames
in the order they were processed (``frame`` is the sequence's own index).
``outcome`` is ``correct``, ``false``, ``missed`` or NULL for an unscored
frame (seeds/004, Table V).  Errors are stored long, one row per frame and
error column (``err_d_px``, ``err_alpha_deg``, ... for cameras; the names
carry units, ``conventions.md`` section 4), so that every modality's columns
fit the same table; a non-finite error is simply not stored.

``pictures`` holds, per cell, the PNG pictures of the first frame of each
run of false or missed frames (:class:`benchmark.results.Picture`), keyed
by the sequence's frame index; a cell whose modality draws nothing has none.

``conditions`` holds, per dataset identity, the conditions its sequence
was made under (:meth:`benchmark.model.Sequence.conditions`: water type,
altitude, cable contrast, ...), for the boards by condition
(:mod:`benchmark.by_condition`); a dataset without conditions has no rows.

``run_cells`` lists the cells that make up a run's results: those it ran
and those it took over from earlier runs with ``--resume``.

``step_ms`` is the CPU time of the thread that ran the tracker's ``step``
and ``wall_ms`` its wall time (:mod:`benchmark.runner`).

A database of schema version 1 (no ``problems``, no ``dataset_key``), 2
(no ``training``), 3 (no ``pictures``), 4 (no ``conditions``), 5 (no
``deterministic``), 6 (``step_ms`` was the wall time, no ``wall_ms``) or
7 (no ``real_time``)
is upgraded in place when opened, its cells keeping no pictures and
declaring nothing; version 1's cells get their ``dataset`` as
``dataset_key``, which no identity's key equals, so they are shown but
never resumed.  The frames of versions 1 to 6 keep their time as
``wall_ms``, and their ``step_ms`` is NULL: the CPU time was not
measured, so their ``cpu_fps`` is empty rather than a wall time under a
CPU time's name.  Any database error, such as a file damaged on disk, is
reported as a :class:`~benchmark.errors.DataError` naming the file.
"""

from __future__ import annotations

import functools
import json
import math
import os
import sqlite3
from collections.abc import Callable, Iterable, Iterator, Mapping, Sequence
from contextlib import contextmanager
from datetime import UTC, datetime
from pathlib import Path
from typing import TYPE_CHECKING, Any, Concatenate, ParamSpec, TypeVar

import pandas as pd
import sqlalchemy as sa
from sqlalchemy.dialects import sqlite
from sqlalchemy.exc import DBAPIError, SQLAlchemyError

from benchmark import schema
from benchmark.errors import DataError
from benchmark.results import Picture

if TYPE_CHECKING:
    from benchmark.results import CellKey, CellResult

SCHEMA_VERSION = 8
DATABASE_NAME = "results.sqlite"

_runs = schema.results_runs
_cells = schema.results_cells
_run_cells = schema.results_run_cells
_frames = schema.results_frames
_frame_errors = schema.results_frame_errors
_pictures = schema.results_pictures
_conditions = schema.results_conditions
_ROWID = sa.literal_column("rowid")
_ADD_FRAMES = _frames.insert()
_ADD_FRAME_ERRORS = _frame_errors.insert()
_ADD_PICTURES = _pictures.insert().prefix_with("OR IGNORE")
_ADD_RUN_CELLS = _run_cells.insert()

_UPGRADED = range(1, SCHEMA_VERSION)
"""The schema versions that :func:`_upgrade` brings to :data:`SCHEMA_VERSION`."""

_FROM_VERSION_1 = (
    # Version 2 keyed cells by their dataset's identity and its index by that key.
    "ALTER TABLE cells ADD COLUMN dataset_key VARCHAR(200) NOT NULL DEFAULT ''",
    "UPDATE cells SET dataset_key = dataset",
    "DROP INDEX cells_by_key",
)

_BEFORE_VERSION_7 = (
    # Version 7 times a step by its thread's CPU time in step_ms; the wall time step_ms held moves to wall_ms.
    "ALTER TABLE frames RENAME COLUMN step_ms TO wall_ms",
)

CELL_COLUMNS = (
    "id",
    "run_id",
    "tracker",
    "tracker_version",
    "tracker_key",
    "params",
    "dataset",
    "dataset_key",
    "modality",
    "seed",
    "init",
    "status",
    "message",
    "detail",
    "frames",
    "elapsed_s",
    "finished",
    "training",
    "deterministic",
    "real_time",
)
"""Columns of the table :meth:`ResultStore.cells` returns."""


def _now() -> str:
    return datetime.now(UTC).isoformat(timespec="seconds")


def _database_error(path: Path, exc: BaseException) -> DataError:
    """The error to report for the database error ``exc`` (SQLAlchemy's, or the driver's it wraps) on ``path``."""
    code = (getattr(exc, "sqlite_errorcode", None) or 0) & 0xFF  # the primary code of an extended one
    if code in (sqlite3.SQLITE_CORRUPT, sqlite3.SQLITE_NOTADB):
        return DataError(f"{path}: the results database is damaged ({exc}); move it aside to start a new one")
    if code == sqlite3.SQLITE_CANTOPEN:
        return DataError(
            f"{path}: cannot open the results database ({exc}); check that its folder exists and is writable"
        )
    return DataError(f"{path}: cannot use the results database ({exc})")


_P = ParamSpec("_P")
_T = TypeVar("_T")


def _reports_database_errors(
    method: Callable[Concatenate[ResultStore, _P], _T],
) -> Callable[Concatenate[ResultStore, _P], _T]:
    """``method`` with any database error raised as a :class:`DataError` naming the file.

    The driver's own error, when SQLAlchemy wraps one, is the cause.
    """

    @functools.wraps(method)
    def wrapper(self: ResultStore, /, *args: _P.args, **kwargs: _P.kwargs) -> _T:
        try:
            return method(self, *args, **kwargs)
        except (SQLAlchemyError, sqlite3.DatabaseError) as exc:
            cause = exc.orig if isinstance(exc, DBAPIError) else exc
            raise _database_error(self.path, cause) from cause

    return wrapper


def _chunks(values: Sequence[_T], size: int = 500) -> Iterable[Sequence[_T]]:
    for start in range(0, len(values), size):
        yield values[start : start + size]


@functools.cache
def _driver_sql(statement: sa.Insert) -> str:
    """``statement`` as SQLite's driver reads it, taking a tuple of values in the order of the table's columns."""
    return str(statement.compile(dialect=sqlite.dialect()))


def _insert_rows(connection: sa.Connection, statement: sa.Insert, rows: list[tuple[Any, ...]]) -> None:
    """Insert ``rows``, tuples of values the driver takes as they are, in one ``executemany``.

    A cell's frame and error rows go to the driver without SQLAlchemy's
    handling of each row's parameters, which costs about as much as
    SQLite's insert itself; the statement is still the table's own.
    """
    if rows:
        connection.exec_driver_sql(_driver_sql(statement), rows)


def _rows(result: sa.Result[Any]) -> list[tuple[Any, ...]]:
    """The rows of ``result`` as plain tuples, which pandas reads many times faster than SQLAlchemy's rows."""
    return list(map(tuple, result))


def _sqlite_engine(path: Path) -> sa.Engine:
    """An engine on the SQLite file ``path`` that enforces foreign keys and begins every transaction itself.

    The driver's own transaction handling is switched off, so that a
    transaction holds schema changes too and the store's reads see one
    snapshot (SQLAlchemy's recipe for pysqlite).
    """
    engine = sa.create_engine(sa.URL.create("sqlite", database=str(path)))

    @sa.event.listens_for(engine, "connect")
    def connect(dbapi_connection: sqlite3.Connection, _record: object) -> None:
        dbapi_connection.isolation_level = None
        dbapi_connection.execute("PRAGMA foreign_keys = ON")

    @sa.event.listens_for(engine, "begin")
    def begin(connection: sa.Connection) -> None:
        connection.exec_driver_sql("BEGIN")

    return engine


def _upgrade(connection: sa.Connection, version: int) -> None:
    """Bring a database of schema ``version`` (0: empty) to :data:`SCHEMA_VERSION`, within the caller's transaction."""
    if version == 1:
        for statement in _FROM_VERSION_1:
            connection.exec_driver_sql(statement)
    if 1 <= version < 7:
        for statement in _BEFORE_VERSION_7:
            connection.exec_driver_sql(statement)
    schema.add_missing_columns(connection, schema.RESULTS)
    schema.RESULTS.create_all(connection)
    schema.cells_by_key.create(connection, checkfirst=True)
    connection.exec_driver_sql(f"PRAGMA user_version = {SCHEMA_VERSION}")


class ResultStore:
    """A results database on disk, created on first use.

    Parameters
    ----------
    path : str or path-like
        The SQLite file; its folder must exist.

    Raises
    ------
    DataError
        If the file cannot be opened, is damaged, is another program's
        database, or has a schema version this trackbench does not know;
        every method raises it, naming the file, for any database error.

    Examples
    --------
    >>> with ResultStore("reports/latest/results.sqlite") as store:    # doctest: +SKIP
    ...     run = store.start_run(sys.argv, {})
    ...     store.add_cell(run, result)
    """

    @_reports_database_errors
    def __init__(self, path: str | os.PathLike[str]) -> None:
        self.path = Path(path)
        self._engine = _sqlite_engine(self.path)
        connection = self._engine.connect()
        try:
            self._prepare(connection)
        except BaseException:
            connection.close()
            self._engine.dispose()
            raise
        self._connection = connection

    def _prepare(self, connection: sa.Connection) -> None:
        """Refuse a file that is not ours, then upgrade or create the schema in one transaction."""
        with connection.begin():
            version = connection.exec_driver_sql("PRAGMA user_version").scalar_one()
            if version == 0:
                tables = sa.inspect(connection).get_table_names()
                if tables:
                    raise DataError(
                        f"{self.path}: not a trackbench results database (it holds the tables "
                        f"{', '.join(tables)}) and was left unchanged; move it or write the results elsewhere"
                    )
            elif version != SCHEMA_VERSION and version not in _UPGRADED:
                raise DataError(
                    f"{self.path}: results database of schema version {version}; "
                    f"this trackbench reads versions up to {SCHEMA_VERSION}"
                )
        # The journal mode changes outside any transaction, on the driver's connection.
        connection.connection.driver_connection.execute("PRAGMA journal_mode = WAL")  # type: ignore[union-attr]
        if version != SCHEMA_VERSION:
            with connection.begin():
                _upgrade(connection, version)

    @contextmanager
    def _transaction(self) -> Iterator[sa.Connection]:
        """The store's connection inside one transaction, committed at the end (rolled back on an error)."""
        with self._connection.begin():
            yield self._connection

    @_reports_database_errors
    def close(self) -> None:
        """Close the connection; everything written is already committed."""
        self._connection.close()
        self._engine.dispose()

    def __enter__(self) -> ResultStore:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    @_reports_database_errors
    def start_run(
        self,
        argv: Sequence[str],
        options: Mapping[str, Any],
        version: str | None = None,
        problems: Sequence[str] = (),
    ) -> int:
        """Record the start of a run and return its id.

        Parameters
        ----------
        argv : sequence of str
            The command line.
        options : mapping
            The parsed options, stored as JSON (non-JSON values as their repr).
        version : str, optional
            trackbench's version; defaults to the installed one.
        problems : sequence of str
            What went wrong outside any cell, one line each (a plugin that
            failed to import); :meth:`run_problems` returns them.
        """
        if version is None:
            from benchmark import __version__ as version
        row = {
            "started": _now(),
            "argv": json.dumps(list(argv)),
            "options": json.dumps(dict(options), default=repr),
            "version": version,
            "problems": json.dumps([str(problem) for problem in problems]),
        }
        with self._transaction() as connection:
            inserted = connection.execute(_runs.insert(), row).inserted_primary_key
        return int(inserted[0])

    @_reports_database_errors
    def finish_run(self, run_id: int) -> None:
        """Mark a run as finished (a run killed early keeps ``finished`` NULL)."""
        with self._transaction() as connection:
            connection.execute(_runs.update().where(_runs.c.id == run_id).values(finished=_now()))

    @_reports_database_errors
    def add_cell(self, run_id: int, result: CellResult) -> int:
        """Store a cell and all its frames in one transaction; return the cell id."""
        cell = {
            "run_id": run_id,
            "tracker": result.tracker,
            "tracker_version": result.tracker_version,
            "tracker_key": result.tracker_key,
            "params": json.dumps(result.params, sort_keys=True, default=repr),
            "dataset": result.dataset,
            "dataset_key": result.dataset_key,
            "modality": result.modality,
            "seed": int(result.seed),
            "init": result.init,
            "status": result.status,
            "message": result.message,
            "detail": result.detail,
            "frames": len(result.scores),
            "elapsed_s": float(result.elapsed_s),
            "finished": _now(),
            "training": result.training,
            "deterministic": bool(result.deterministic),
            "real_time": result.real_time,
        }
        with self._transaction() as connection:
            cell_id = int(connection.execute(_cells.insert(), cell).inserted_primary_key[0])
            frames = [
                (cell_id, position, int(score.index), None if score.outcome is None else str(score.outcome),
                 1000.0 * float(score.step_s), 1000.0 * float(score.wall_s))
                for position, score in enumerate(result.scores)
            ]
            errors = [
                (cell_id, position, name, float(value))
                for position, score in enumerate(result.scores)
                for name, value in {**score.errors, **({} if score.loop is None else score.loop.columns())}.items()
                if math.isfinite(float(value))
            ]
            pictures = [(cell_id, int(shot.frame), str(shot.outcome), bytes(shot.png)) for shot in result.pictures]
            _insert_rows(connection, _ADD_FRAMES, frames)
            _insert_rows(connection, _ADD_FRAME_ERRORS, errors)
            _insert_rows(connection, _ADD_PICTURES, pictures)
            _insert_rows(connection, _ADD_RUN_CELLS, [(run_id, cell_id)])
        return cell_id

    @_reports_database_errors
    def pictures(self, cell_ids: Iterable[int]) -> dict[int, list[Picture]]:
        """The pictures of failed frames of the given cells (see :attr:`benchmark.results.CellResult.pictures`).

        Parameters
        ----------
        cell_ids : iterable of int
            The cells.

        Returns
        -------
        dict
            Cell id to its pictures in frame order, for the cells that have any.
        """
        ids = sorted({int(cell_id) for cell_id in cell_ids})
        found: dict[int, list[Picture]] = {}
        with self._transaction() as connection:
            for chunk in _chunks(ids):
                query = (
                    sa.select(_pictures.c.cell_id, _pictures.c.frame, _pictures.c.outcome, _pictures.c.png)
                    .where(_pictures.c.cell_id.in_(chunk))
                    .order_by(_pictures.c.cell_id, _pictures.c.frame)
                )
                for cell_id, frame, outcome, png in connection.execute(query):
                    found.setdefault(int(cell_id), []).append(Picture(int(frame), str(outcome), bytes(png)))
        return found

    @_reports_database_errors
    def add_conditions(self, conditions: Mapping[str, Mapping[str, Any]]) -> None:
        """Keep the conditions of datasets, replacing what was kept for the same dataset and name.

        Parameters
        ----------
        conditions : Mapping
            Dataset key to its conditions by name; values must be JSON
            (numbers, strings, lists, tables).
        """
        rows = [
            {"dataset_key": key, "name": str(name), "value": json.dumps(value, allow_nan=False)}
            for key, found in conditions.items()
            for name, value in found.items()
        ]
        if rows:
            with self._transaction() as connection:
                connection.execute(_conditions.insert().prefix_with("OR REPLACE"), rows)

    @_reports_database_errors
    def conditions(self, dataset_keys: Iterable[str]) -> dict[str, dict[str, Any]]:
        """The conditions kept for the given datasets (see :meth:`add_conditions`).

        Returns
        -------
        dict
            Dataset key to its conditions by name, in the order they were
            added, for the datasets that have any.
        """
        keys = sorted(set(dataset_keys))
        found: dict[str, dict[str, Any]] = {}
        with self._transaction() as connection:
            for chunk in _chunks(keys):
                query = (
                    sa.select(_conditions.c.dataset_key, _conditions.c.name, _conditions.c.value)
                    .where(_conditions.c.dataset_key.in_(chunk))
                    .order_by(_ROWID)
                )
                for key, name, value in connection.execute(query):
                    found.setdefault(str(key), {})[str(name)] = json.loads(value)
        return found

    @_reports_database_errors
    def find_ok_cells(self, keys: Iterable[CellKey]) -> dict[CellKey, int]:
        """The latest cell with status ``ok`` for each key that has one.

        Parameters
        ----------
        keys : iterable of CellKey
            ``(tracker_key, dataset_key, seed, init)`` of the wanted cells.

        Returns
        -------
        dict
            Key to cell id, for the keys already computed successfully.
        """
        wanted = list(keys)
        key_columns = (_cells.c.tracker_key, _cells.c.dataset_key, _cells.c.seed, _cells.c.init)
        latest: dict[tuple[str, str, int, str], int] = {}
        with self._transaction() as connection:
            for chunk in _chunks(sorted({key.tracker_key for key in wanted})):
                query = (
                    sa.select(*key_columns, sa.func.max(_cells.c.id))
                    .where(_cells.c.status == "ok", _cells.c.tracker_key.in_(chunk))
                    .group_by(*key_columns)
                )
                latest.update({(tracker, dataset, seed, init): cell_id
                               for tracker, dataset, seed, init, cell_id in connection.execute(query)})
        found: dict[CellKey, int] = {}
        for key in wanted:
            cell_id = latest.get((key.tracker_key, key.dataset_key, int(key.seed), key.init))
            if cell_id is not None:
                found[key] = int(cell_id)
        return found

    @_reports_database_errors
    def reuse_cells(self, run_id: int, cell_ids: Iterable[int]) -> None:
        """Make earlier cells part of a run's results (``--resume``)."""
        rows = [{"run_id": run_id, "cell_id": int(cell_id)} for cell_id in cell_ids]
        if rows:
            with self._transaction() as connection:
                connection.execute(_run_cells.insert().prefix_with("OR IGNORE"), rows)

    @_reports_database_errors
    def runs(self) -> pd.DataFrame:
        """All runs, oldest first, with the number of cells in each (``problems`` as stored, JSON)."""
        query = (
            sa.select(
                _runs.c.id, _runs.c.started, _runs.c.finished, _runs.c.argv, _runs.c.options, _runs.c.version,
                _runs.c.problems, sa.func.count(_run_cells.c.cell_id),
            )
            .select_from(_runs.outerjoin(_run_cells, _run_cells.c.run_id == _runs.c.id))
            .group_by(_runs.c.id)
            .order_by(_runs.c.id)
        )
        with self._transaction() as connection:
            rows = _rows(connection.execute(query))
        return pd.DataFrame.from_records(
            rows, columns=["id", "started", "finished", "argv", "options", "version", "problems", "cells"]
        )

    @_reports_database_errors
    def latest_run(self) -> int | None:
        """Id of the latest run that has at least one cell, or None."""
        with self._transaction() as connection:
            latest = connection.execute(sa.select(sa.func.max(_run_cells.c.run_id))).scalar_one()
        return None if latest is None else int(latest)

    @_reports_database_errors
    def run_problems(self, run_id: int | None = None) -> list[str]:
        """The problems recorded with a run (see :meth:`start_run`).

        Parameters
        ----------
        run_id : int, optional
            The run; defaults to :meth:`latest_run`.

        Returns
        -------
        list of str
            One line each; empty for a run without problems or no run at all.
        """
        run_id = self.latest_run() if run_id is None else run_id
        with self._transaction() as connection:
            problems = connection.execute(sa.select(_runs.c.problems).where(_runs.c.id == run_id)).scalar()
        return [] if problems is None else [str(problem) for problem in json.loads(problems)]

    @_reports_database_errors
    def cells(self, run_id: int | None = None, *, all_runs: bool = False) -> pd.DataFrame:
        """The cells that make up a leaderboard.

        Parameters
        ----------
        run_id : int, optional
            The run whose cells (run or resumed) to take; defaults to
            :meth:`latest_run`.
        all_runs : bool
            Take cells from every run instead.

        Returns
        -------
        pandas.DataFrame
            Columns :data:`CELL_COLUMNS`; for each ``(tracker_key,
            dataset_key, seed, init)`` only the latest cell, whatever its status.
        """
        query = sa.select(*(_cells.c[column] for column in CELL_COLUMNS)).order_by(_cells.c.id)
        if not all_runs:
            run_id = self.latest_run() if run_id is None else run_id
            query = query.join(_run_cells, _run_cells.c.cell_id == _cells.c.id).where(_run_cells.c.run_id == run_id)
        with self._transaction() as connection:
            rows = _rows(connection.execute(query))
        table = pd.DataFrame.from_records(rows, columns=list(CELL_COLUMNS))
        table["deterministic"] = table["deterministic"].astype(bool)
        return table.drop_duplicates(["tracker_key", "dataset_key", "seed", "init"], keep="last").reset_index(drop=True)

    @_reports_database_errors
    def frame_tables(self, cell_ids: Iterable[int]) -> pd.DataFrame:
        """Frame scores of the given cells, one row per frame.

        Returns
        -------
        pandas.DataFrame
            ``cell_id``, ``frame``, ``outcome``, ``step_ms`` (thread CPU time;
            ``nan`` in frames stored before version 7), ``wall_ms`` and one
            column per error name found, in the order they were written
            (``nan`` where not stored); rows in processing order.
        """
        ids = sorted({int(cell_id) for cell_id in cell_ids})
        frame_rows: list[tuple[Any, ...]] = []
        error_rows: list[tuple[Any, ...]] = []
        frame_names = ["cell_id", "position", "frame", "outcome", "step_ms", "wall_ms"]
        frame_columns = [_frames.c[name] for name in frame_names]
        error_columns = (_frame_errors.c.cell_id, _frame_errors.c.position, _frame_errors.c.name, _frame_errors.c.value)
        with self._transaction() as connection:
            for chunk in _chunks(ids):
                frame_rows += _rows(connection.execute(sa.select(*frame_columns).where(_frames.c.cell_id.in_(chunk))))
                error_rows += _rows(
                    connection.execute(sa.select(*error_columns).where(_frame_errors.c.cell_id.in_(chunk)).order_by(_ROWID))
                )
        frames = pd.DataFrame.from_records(frame_rows, columns=frame_names).astype(
            {"cell_id": "int64", "position": "int64", "frame": "int64", "step_ms": "float64", "wall_ms": "float64"}
        )
        if error_rows:
            errors = pd.DataFrame.from_records(error_rows, columns=["cell_id", "position", "name", "value"])
            wide = errors.pivot(index=["cell_id", "position"], columns="name", values="value")
            wide = wide[list(dict.fromkeys(errors["name"]))]  # the scorer's order, as the columns were written
            wide.columns = [str(name) for name in wide.columns]
            frames = frames.merge(wide.reset_index(), on=["cell_id", "position"], how="left")
        frames = frames.sort_values(["cell_id", "position"], kind="stable")
        return frames.drop(columns="position").reset_index(drop=True)
