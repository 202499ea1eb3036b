"""The history database: every nightly run, its machine and commit, and each cell's summary, frames and pictures.

A nightly run (``trackbench nightly``) appends one row to ``runs`` and one
row per cell to ``cells``, copied from the run's results database
(:mod:`benchmark.store`) in one transaction.  Tables::

    runs(id, started, finished, version, commit, machine_key, machine JSON, argv JSON, seeds, load JSON)
    cells(id, run_id -> runs, tracker, tracker_version, tracker_key, params JSON, dataset,
          dataset_key, modality, seed, init, training, status, message, frames, elapsed_s,
          metrics JSON, deterministic)
    cell_frames(cell_id -> cells, frames BLOB)
    cell_pictures(cell_id -> cells, frame, outcome, png BLOB)

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
the history alone.  Frames and pictures (about 0.5 MB for a camera cell
that failed often) are kept for the last :data:`DETAILED_RUNS` runs only;
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
works too, so a team can share one history.  Any database error is a
:class:`~benchmark.errors.DataError` naming the database.
"""

from __future__ import annotations

import functools
import json
import zlib
from collections.abc import Callable, Iterable, Mapping, Sequence
from datetime import UTC, datetime
from pathlib import Path
from typing import Any, Concatenate, ParamSpec, TypeVar

import pandas as pd
import sqlalchemy as sa
from sqlalchemy.exc import SQLAlchemyError

from benchmark import schema
from benchmark.errors import DataError
from benchmark.files import resolved
from benchmark.leaderboard import board_metrics
from benchmark.metrics import CORE, Metrics
from benchmark.modality import Modality
from benchmark.results import Picture, summarise
from benchmark.store import ResultStore

DETAILED_RUNS = 30
"""How many of the latest runs keep their cells' frame tables and pictures."""

SERIES = ["tracker", "dataset_key", "seed", "init"]
"""The columns of :meth:`History.cells` that identify a series of comparable cells."""

_metadata = schema.HISTORY
_runs = schema.history_runs
_cells = schema.history_cells
_cell_frames = schema.history_cell_frames
_cell_pictures = schema.history_cell_pictures

_P = ParamSpec("_P")
_T = TypeVar("_T")


def _reports_database_errors(method: Callable[Concatenate[History, _P], _T]) -> Callable[Concatenate[History, _P], _T]:
    @functools.wraps(method)
    def wrapper(self: History, /, *args: _P.args, **kwargs: _P.kwargs) -> _T:
        try:
            return method(self, *args, **kwargs)
        except SQLAlchemyError as exc:
            raise DataError(f"history database {self.location}: {type(exc).__name__}: {exc}") from exc

    return wrapper


def database_url(location: str | Path) -> str:
    """An SQLAlchemy URL as given, or the URL of an SQLite file at a path."""
    text = str(location)
    return text if "://" in text else f"sqlite:///{resolved(Path(text).expanduser())}"


def _pack(frames: pd.DataFrame) -> bytes:
    return zlib.compress(frames.to_json(orient="split", index=False, double_precision=15).encode())


WALL_TIMED = {"fps": "wall_fps"}
"""Metrics of runs recorded before the CPU timing, by the name they are read under: they timed the wall clock."""


def _unpack(blob: bytes) -> pd.DataFrame:
    from io import StringIO

    frames = pd.read_json(StringIO(zlib.decompress(blob).decode()), orient="split")
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
        If the database cannot be opened or is not a trackbench history;
        every method raises it, naming the database, for any database error.
    """

    def __init__(self, location: str | Path, *, must_exist: bool = False) -> None:
        self.location = str(location)
        url = database_url(location)
        if url.startswith("sqlite:///"):
            path = Path(url.removeprefix("sqlite:///"))
            if must_exist and not path.is_file():
                raise DataError(f"history database {self.location}: no such file (run 'trackbench nightly' first)")
            path.parent.mkdir(parents=True, exist_ok=True)
        self._engine = sa.create_engine(url)
        self._create()

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
            raise DataError(
                f"history database {self.location}: holds other tables ({', '.join(sorted(existing)[:5])}) and "
                "none of a trackbench history's; the database was left unchanged"
            )
        for table in _metadata.sorted_tables:
            if table.name not in existing:
                continue
            found = {column["name"] for column in inspector.get_columns(table.name)}
            if any(column.server_default is None for column in table.columns if column.name not in found):
                raise DataError(
                    f"history database {self.location}: its table {table.name!r} is not a trackbench history's "
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
            command line and the number of seeds.
        metrics : Metrics
            The catalogue of metrics each cell's summary holds (the registry's).
        load : Mapping, optional
            How busy the machine was during the run
            (:meth:`benchmark.history.machine.LoadMeter.stop`), JSON values.
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
                    argv=json.dumps(list(argv)),
                    seeds=seeds,
                    load=json.dumps(dict(load or {})),
                )
            ).inserted_primary_key[0]
            for cell in cells.itertuples(index=False):
                table = by_cell.get(int(cell.id), frames.iloc[0:0].drop(columns="cell_id"))
                of_board = board_metrics(metrics, cell.modality, modalities.get(cell.modality), table)
                cell_id = connection.execute(
                    _cells.insert().values(
                        run_id=history_run,
                        **{name: getattr(cell, name) for name in _COPIED},
                        seed=int(cell.seed),
                        frames=int(cell.frames),
                        elapsed_s=float(cell.elapsed_s),
                        metrics=json.dumps(summarise(table, of_board)),
                    )
                ).inserted_primary_key[0]
                connection.execute(_cell_frames.insert().values(cell_id=cell_id, frames=_pack(table)))
                rows = [
                    {"cell_id": cell_id, "frame": p.frame, "outcome": p.outcome, "png": p.png}
                    for p in pictures.get(int(cell.id), [])
                ]
                if rows:
                    connection.execute(_cell_pictures.insert(), rows)
            self._forget_details(connection)
        return int(history_run)

    @staticmethod
    def _forget_details(connection: sa.Connection) -> None:
        """Drop the frame tables and pictures of the runs older than the last :data:`DETAILED_RUNS`."""
        kept = sa.select(_runs.c.id).order_by(_runs.c.id.desc()).limit(DETAILED_RUNS)
        old_cells = sa.select(_cells.c.id).where(_cells.c.run_id.not_in(kept.scalar_subquery()))
        for table in (_cell_frames, _cell_pictures):
            connection.execute(table.delete().where(table.c.cell_id.in_(old_cells.scalar_subquery())))

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
            have it; the ``fps`` of older runs is ``wall_fps``), plus the
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
            raise DataError(
                f"history database {self.location}: no frame table of cell {cell_id} "
                f"(only the last {DETAILED_RUNS} runs keep theirs)"
            )
        return _unpack(blob)

    @_reports_database_errors
    def pictures(self, cell_id: int) -> list[Picture]:
        """The pictures of the frames a cell failed on, in frame order."""
        query = sa.select(_cell_pictures).where(_cell_pictures.c.cell_id == int(cell_id)).order_by("frame")
        with self._engine.connect() as connection:
            rows = connection.execute(query).mappings().all()
        return [Picture(int(row["frame"]), str(row["outcome"]), bytes(row["png"])) for row in rows]


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
)
"""Columns of a results database's cells copied as they are."""
