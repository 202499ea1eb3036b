"""The results database: runs, cells and per-frame scores in SQLite.

Every ``trackbench run`` is a row of ``runs``; every finished cell is a row
of ``cells`` together with its frame rows and its pictures, written in one
transaction, so a run that is killed keeps every cell it finished and loses
only those in flight.  Only the main process writes; worker processes hand their results
back to it.

Schema (``PRAGMA user_version`` = :data:`SCHEMA_VERSION`)::

    runs(id, started, finished, argv JSON, options JSON, version, problems JSON)
    cells(id, run_id -> runs, tracker, tracker_version, tracker_key, params JSON,
          dataset, dataset_key, modality, seed, init, status, message, detail,
          frames, elapsed_s, finished, training, deterministic)
    run_cells(run_id -> runs, cell_id -> cells)
    frames(cell_id -> cells, position, frame, outcome, step_ms)
    frame_errors(cell_id, position, name, value)
    pictures(cell_id -> cells, frame, outcome, png BLOB)
    conditions(dataset_key, name, value JSON)

``training`` names the training set of a tracker that learns (empty for
the others; :mod:`benchmark.training`); ``deterministic`` is 1 when the
tracker declares that it draws no random numbers.  ``problems`` lists, one line each, what went wrong in a run outside any
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

A database of schema version 1 (no ``problems``, no ``dataset_key``), 2
(no ``training``), 3 (no ``pictures``), 4 (no ``conditions``) or 5 (no
``deterministic``) is upgraded in place when opened, its cells keeping no
pictures and declaring nothing; version 1's cells get their ``dataset`` as
``dataset_key``, which no identity's key equals, so they are shown but
never resumed.  Any SQLite error, such as a file damaged on disk, is
reported as a :class:`~benchmark.errors.DataError` naming the file.
"""

from __future__ import annotations

import functools
import json
import math
import os
import sqlite3
from collections.abc import Callable, Iterable, Mapping, Sequence
from datetime import UTC, datetime
from pathlib import Path
from typing import TYPE_CHECKING, Any, Concatenate, ParamSpec, TypeVar

import pandas as pd

from benchmark.errors import DataError
from benchmark.results import Picture

if TYPE_CHECKING:
    from benchmark.results import CellKey, CellResult

SCHEMA_VERSION = 6
DATABASE_NAME = "results.sqlite"

_SCHEMA = """
CREATE TABLE IF NOT EXISTS runs (
    id INTEGER PRIMARY KEY,
    started TEXT NOT NULL,
    finished TEXT,
    argv TEXT NOT NULL,
    options TEXT NOT NULL,
    version TEXT NOT NULL,
    problems TEXT NOT NULL DEFAULT '[]'
);
CREATE TABLE IF NOT EXISTS cells (
    id INTEGER PRIMARY KEY,
    run_id INTEGER NOT NULL REFERENCES runs(id),
    tracker TEXT NOT NULL,
    tracker_version TEXT NOT NULL,
    tracker_key TEXT NOT NULL,
    params TEXT NOT NULL,
    dataset TEXT NOT NULL,
    dataset_key TEXT NOT NULL,
    modality TEXT NOT NULL,
    seed INTEGER NOT NULL,
    init TEXT NOT NULL,
    status TEXT NOT NULL CHECK (status IN ('ok', 'error', 'timeout')),
    message TEXT NOT NULL,
    detail TEXT NOT NULL,
    frames INTEGER NOT NULL,
    elapsed_s REAL NOT NULL,
    finished TEXT NOT NULL,
    training TEXT NOT NULL DEFAULT '',
    deterministic INTEGER NOT NULL DEFAULT 0
);
CREATE INDEX IF NOT EXISTS cells_by_key ON cells (tracker_key, dataset_key, seed, init);
CREATE TABLE IF NOT EXISTS run_cells (
    run_id INTEGER NOT NULL REFERENCES runs(id),
    cell_id INTEGER NOT NULL REFERENCES cells(id),
    PRIMARY KEY (run_id, cell_id)
);
CREATE TABLE IF NOT EXISTS frames (
    cell_id INTEGER NOT NULL REFERENCES cells(id),
    position INTEGER NOT NULL,
    frame INTEGER NOT NULL,
    outcome TEXT,
    step_ms REAL NOT NULL,
    PRIMARY KEY (cell_id, position)
);
CREATE TABLE IF NOT EXISTS frame_errors (
    cell_id INTEGER NOT NULL,
    position INTEGER NOT NULL,
    name TEXT NOT NULL,
    value REAL NOT NULL,
    PRIMARY KEY (cell_id, position, name),
    FOREIGN KEY (cell_id, position) REFERENCES frames(cell_id, position)
);
CREATE TABLE IF NOT EXISTS pictures (
    cell_id INTEGER NOT NULL REFERENCES cells(id),
    frame INTEGER NOT NULL,
    outcome TEXT NOT NULL,
    png BLOB NOT NULL,
    PRIMARY KEY (cell_id, frame)
);
CREATE TABLE IF NOT EXISTS conditions (
    dataset_key TEXT NOT NULL,
    name TEXT NOT NULL,
    value TEXT NOT NULL,
    PRIMARY KEY (dataset_key, name)
);
"""

_UPGRADES = {
    1: """
ALTER TABLE runs ADD COLUMN problems TEXT NOT NULL DEFAULT '[]';
ALTER TABLE cells ADD COLUMN dataset_key TEXT NOT NULL DEFAULT '';
UPDATE cells SET dataset_key = dataset;
DROP INDEX cells_by_key;
ALTER TABLE cells ADD COLUMN training TEXT NOT NULL DEFAULT '';
ALTER TABLE cells ADD COLUMN deterministic INTEGER NOT NULL DEFAULT 0;
""",
    2: """
ALTER TABLE cells ADD COLUMN training TEXT NOT NULL DEFAULT '';
ALTER TABLE cells ADD COLUMN deterministic INTEGER NOT NULL DEFAULT 0;
""",
    3: "ALTER TABLE cells ADD COLUMN deterministic INTEGER NOT NULL DEFAULT 0;",
    4: "ALTER TABLE cells ADD COLUMN deterministic INTEGER NOT NULL DEFAULT 0;",
    5: "ALTER TABLE cells ADD COLUMN deterministic INTEGER NOT NULL DEFAULT 0;",
}
"""Schema version to the SQL that brings it to :data:`SCHEMA_VERSION` (``_SCHEMA`` then adds what is missing)."""

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
)
"""Columns of the table :meth:`ResultStore.cells` returns."""


def _now() -> str:
    return datetime.now(UTC).isoformat(timespec="seconds")


def _database_error(path: Path, exc: sqlite3.DatabaseError) -> DataError:
    """The error to report for an SQLite error on the database ``path``."""
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
    """``method`` with any :class:`sqlite3.DatabaseError` raised as a :class:`DataError` naming the file."""

    @functools.wraps(method)
    def wrapper(self: ResultStore, /, *args: _P.args, **kwargs: _P.kwargs) -> _T:
        try:
            return method(self, *args, **kwargs)
        except sqlite3.DatabaseError as exc:
            raise _database_error(self.path, exc) from exc

    return wrapper


def _chunks(values: Sequence[_T], size: int = 500) -> Iterable[Sequence[_T]]:
    for start in range(0, len(values), size):
        yield values[start : start + size]


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
        every method raises it, naming the file, for any SQLite error.

    Examples
    --------
    >>> with ResultStore("reports/latest/results.sqlite") as store:    # doctest: +SKIP
    ...     run = store.start_run(sys.argv, {})
    ...     store.add_cell(run, result)
    """

    @_reports_database_errors
    def __init__(self, path: str | os.PathLike[str]) -> None:
        self.path = Path(path)
        self._db = sqlite3.connect(self.path)
        try:
            self._prepare()
        except BaseException:
            self._db.close()
            raise

    def _prepare(self) -> None:
        """Refuse a file that is not ours, then upgrade or create the schema in one transaction."""
        self._db.execute("PRAGMA foreign_keys = ON")
        version = self._db.execute("PRAGMA user_version").fetchone()[0]
        if version == 0:
            tables = [row[0] for row in self._db.execute("SELECT name FROM sqlite_master WHERE type = 'table'")]
            if tables:
                raise DataError(
                    f"{self.path}: not a trackbench results database (it holds the tables {', '.join(tables)}) "
                    "and was left unchanged; move it or write the results elsewhere"
                )
        elif version != SCHEMA_VERSION and version not in _UPGRADES:
            raise DataError(
                f"{self.path}: results database of schema version {version}; "
                f"this trackbench reads versions up to {SCHEMA_VERSION}"
            )
        self._db.execute("PRAGMA journal_mode = WAL")
        self._db.executescript(
            f"BEGIN; {_UPGRADES.get(version, '')} {_SCHEMA} PRAGMA user_version = {SCHEMA_VERSION}; COMMIT;"
        )

    @_reports_database_errors
    def close(self) -> None:
        """Close the connection; everything written is already committed."""
        self._db.close()

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
        with self._db:
            cursor = self._db.execute(
                "INSERT INTO runs (started, argv, options, version, problems) VALUES (?, ?, ?, ?, ?)",
                (
                    _now(),
                    json.dumps(list(argv)),
                    json.dumps(dict(options), default=repr),
                    version,
                    json.dumps([str(problem) for problem in problems]),
                ),
            )
        return int(cursor.lastrowid)

    @_reports_database_errors
    def finish_run(self, run_id: int) -> None:
        """Mark a run as finished (a run killed early keeps ``finished`` NULL)."""
        with self._db:
            self._db.execute("UPDATE runs SET finished = ? WHERE id = ?", (_now(), run_id))

    @_reports_database_errors
    def add_cell(self, run_id: int, result: CellResult) -> int:
        """Store a cell and all its frames in one transaction; return the cell id."""
        n_frames = len(result.scores)
        with self._db:
            cursor = self._db.execute(
                "INSERT INTO cells (run_id, tracker, tracker_version, tracker_key, params, dataset, dataset_key, "
                "modality, seed, init, status, message, detail, frames, elapsed_s, finished, training, deterministic) "
                "VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)",
                (
                    run_id,
                    result.tracker,
                    result.tracker_version,
                    result.tracker_key,
                    json.dumps(result.params, sort_keys=True, default=repr),
                    result.dataset,
                    result.dataset_key,
                    result.modality,
                    int(result.seed),
                    result.init,
                    result.status,
                    result.message,
                    result.detail,
                    n_frames,
                    float(result.elapsed_s),
                    _now(),
                    result.training,
                    int(result.deterministic),
                ),
            )
            cell_id = int(cursor.lastrowid)
            self._db.executemany(
                "INSERT INTO frames (cell_id, position, frame, outcome, step_ms) VALUES (?, ?, ?, ?, ?)",
                (
                    (cell_id, position, int(score.index), None if score.outcome is None else str(score.outcome),
                     1000.0 * float(score.step_s))
                    for position, score in enumerate(result.scores)
                ),
            )
            self._db.executemany(
                "INSERT INTO frame_errors (cell_id, position, name, value) VALUES (?, ?, ?, ?)",
                (
                    (cell_id, position, name, float(value))
                    for position, score in enumerate(result.scores)
                    for name, value in score.errors.items()
                    if math.isfinite(float(value))
                ),
            )
            self._db.executemany(
                "INSERT OR IGNORE INTO pictures (cell_id, frame, outcome, png) VALUES (?, ?, ?, ?)",
                ((cell_id, int(shot.frame), str(shot.outcome), bytes(shot.png)) for shot in result.pictures),
            )
            self._db.execute("INSERT INTO run_cells (run_id, cell_id) VALUES (?, ?)", (run_id, cell_id))
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
        for chunk in _chunks(ids):
            marks = ", ".join("?" * len(chunk))
            rows = self._db.execute(
                f"SELECT cell_id, frame, outcome, png FROM pictures WHERE cell_id IN ({marks}) ORDER BY cell_id, frame",
                chunk,
            )
            for cell_id, frame, outcome, png in rows:
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
            (key, str(name), json.dumps(value, allow_nan=False))
            for key, found in conditions.items()
            for name, value in found.items()
        ]
        with self._db:
            self._db.executemany("INSERT OR REPLACE INTO conditions (dataset_key, name, value) VALUES (?, ?, ?)", rows)

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
        for chunk in _chunks(keys):
            marks = ", ".join("?" * len(chunk))
            rows = self._db.execute(
                f"SELECT dataset_key, name, value FROM conditions WHERE dataset_key IN ({marks}) ORDER BY rowid", chunk
            )
            for key, name, value in rows:
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
        found: dict[CellKey, int] = {}
        for key in keys:
            row = self._db.execute(
                "SELECT max(id) FROM cells WHERE tracker_key = ? AND dataset_key = ? AND seed = ? AND init = ? "
                "AND status = 'ok'",
                (key.tracker_key, key.dataset_key, int(key.seed), key.init),
            ).fetchone()
            if row[0] is not None:
                found[key] = int(row[0])
        return found

    @_reports_database_errors
    def reuse_cells(self, run_id: int, cell_ids: Iterable[int]) -> None:
        """Make earlier cells part of a run's results (``--resume``)."""
        with self._db:
            self._db.executemany(
                "INSERT OR IGNORE INTO run_cells (run_id, cell_id) VALUES (?, ?)",
                ((run_id, int(cell_id)) for cell_id in cell_ids),
            )

    @_reports_database_errors
    def runs(self) -> pd.DataFrame:
        """All runs, oldest first, with the number of cells in each (``problems`` as stored, JSON)."""
        rows = self._db.execute(
            "SELECT runs.id, started, finished, argv, options, version, problems, count(run_cells.cell_id) "
            "FROM runs LEFT JOIN run_cells ON run_cells.run_id = runs.id GROUP BY runs.id ORDER BY runs.id"
        ).fetchall()
        return pd.DataFrame.from_records(
            rows, columns=["id", "started", "finished", "argv", "options", "version", "problems", "cells"]
        )

    @_reports_database_errors
    def latest_run(self) -> int | None:
        """Id of the latest run that has at least one cell, or None."""
        row = self._db.execute("SELECT max(run_id) FROM run_cells").fetchone()
        return None if row[0] is None else int(row[0])

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
        row = self._db.execute("SELECT problems FROM runs WHERE id = ?", (run_id,)).fetchone()
        return [] if row is None else [str(problem) for problem in json.loads(row[0])]

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
        select = ", ".join(f"cells.{column}" for column in CELL_COLUMNS)
        if all_runs:
            rows = self._db.execute(f"SELECT {select} FROM cells ORDER BY cells.id").fetchall()
        else:
            run_id = self.latest_run() if run_id is None else run_id
            rows = self._db.execute(
                f"SELECT {select} FROM cells JOIN run_cells ON run_cells.cell_id = cells.id "
                "WHERE run_cells.run_id = ? ORDER BY cells.id",
                (run_id,),
            ).fetchall()
        table = pd.DataFrame.from_records(rows, columns=list(CELL_COLUMNS))
        table["deterministic"] = table["deterministic"].astype(bool)
        return table.drop_duplicates(["tracker_key", "dataset_key", "seed", "init"], keep="last").reset_index(drop=True)

    @_reports_database_errors
    def frame_tables(self, cell_ids: Iterable[int]) -> pd.DataFrame:
        """Frame scores of the given cells, one row per frame.

        Returns
        -------
        pandas.DataFrame
            ``cell_id``, ``frame``, ``outcome``, ``step_ms`` and one column per
            error name found, in the order they were written (``nan`` where
            not stored); rows in processing order.
        """
        ids = sorted({int(cell_id) for cell_id in cell_ids})
        frame_rows: list[tuple] = []
        error_rows: list[tuple] = []
        for chunk in _chunks(ids):
            marks = ", ".join("?" * len(chunk))
            frame_rows += self._db.execute(
                f"SELECT cell_id, position, frame, outcome, step_ms FROM frames WHERE cell_id IN ({marks})", chunk
            ).fetchall()
            error_rows += self._db.execute(
                f"SELECT cell_id, position, name, value FROM frame_errors WHERE cell_id IN ({marks}) ORDER BY rowid",
                chunk,
            ).fetchall()
        frames = pd.DataFrame.from_records(
            frame_rows, columns=["cell_id", "position", "frame", "outcome", "step_ms"]
        ).astype({"cell_id": "int64", "position": "int64", "frame": "int64", "step_ms": "float64"})
        if error_rows:
            errors = pd.DataFrame.from_records(error_rows, columns=["cell_id", "position", "name", "value"])
            wide = errors.pivot(index=["cell_id", "position"], columns="name", values="value")
            wide = wide[list(dict.fromkeys(errors["name"]))]  # the scorer's order, as the columns were written
            wide.columns = [str(name) for name in wide.columns]
            frames = frames.merge(wide.reset_index(), on=["cell_id", "position"], how="left")
        frames = frames.sort_values(["cell_id", "position"], kind="stable")
        return frames.drop(columns="position").reset_index(drop=True)
