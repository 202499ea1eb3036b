"""The tables of trackbench's two databases, defined once in SQLAlchemy Core.

A run's results database (:mod:`benchmark.store`, a plain SQLite file) and
the nightly history (:mod:`benchmark.history.database`, SQLite or any
SQLAlchemy URL) both keep a table of cells and a table of the pictures of
failed frames.  What a cell is (the tracker, the dataset's identity, seed
and initialisation, how it ended) and what a picture is are written here
once, by :func:`cell_columns` and :func:`picture_columns`, and each
database's tables add what only they keep: the results database a cell's
traceback, its frame rows and the runs it belongs to; the history a cell's
metrics and the machine and commit of its run.

:data:`RESULTS` and :data:`HISTORY` hold the two databases' tables.  The
results database's schema carries a version (``PRAGMA user_version``,
:data:`benchmark.store.SCHEMA_VERSION`); both databases grow in place
through :func:`add_missing_columns`, which gives an older table the
columns it lacks, each with its default.
"""

from __future__ import annotations

from typing import get_args

import sqlalchemy as sa

from benchmark.results import Status

_STATUSES = ", ".join(f"'{status}'" for status in get_args(Status))


def cell_columns() -> list[sa.Column]:
    """The columns of every table of cells: what ran on what, and how it ended.

    A cell's identity (:class:`benchmark.results.CellKey`) is its
    ``tracker_key``, ``dataset_key``, ``seed`` and ``init``; ``dataset`` is
    only the name it was shown under.  ``training`` names the training set
    of a tracker that learns (empty for the others) and ``deterministic``
    whether the tracker declares that it draws no random numbers;
    ``real_time`` the source of the step time of a cell run in real time
    (empty for the others; :mod:`benchmark.closedloop.real_time`); these
    have defaults, so that tables of older versions can gain them.

    Returns
    -------
    list of sqlalchemy.Column
        New column objects (a column belongs to one table), in table order.
    """
    return [
        sa.Column("tracker", sa.String(200), nullable=False),
        sa.Column("tracker_version", sa.String(64), nullable=False),
        sa.Column("tracker_key", sa.String(200), nullable=False),
        sa.Column("params", sa.Text, nullable=False),
        sa.Column("dataset", sa.Text, nullable=False),
        sa.Column("dataset_key", sa.String(200), nullable=False),
        sa.Column("modality", sa.String(64), nullable=False),
        sa.Column("seed", sa.Integer, nullable=False),
        sa.Column("init", sa.String(16), nullable=False),
        sa.Column("training", sa.Text, nullable=False, server_default=""),
        sa.Column("status", sa.String(16), sa.CheckConstraint(f"status IN ({_STATUSES})"), nullable=False),
        sa.Column("message", sa.Text, nullable=False),
        sa.Column("frames", sa.Integer, nullable=False),
        sa.Column("elapsed_s", sa.Float, nullable=False),
        sa.Column("deterministic", sa.Boolean, nullable=False, server_default=sa.false()),
        sa.Column("real_time", sa.Text, nullable=False, server_default=""),
    ]


def picture_columns(cells: str) -> list[sa.Column]:
    """The columns of a table of pictures of failed frames (:class:`benchmark.results.Picture`).

    Parameters
    ----------
    cells : str
        The name of the table of cells the pictures belong to.

    Returns
    -------
    list of sqlalchemy.Column
        ``cell_id`` and the sequence's ``frame`` index (together the
        primary key), the frame's ``outcome`` and the ``png`` bytes.
    """
    return [
        sa.Column("cell_id", sa.Integer, sa.ForeignKey(f"{cells}.id"), primary_key=True),
        sa.Column("frame", sa.Integer, primary_key=True),
        sa.Column("outcome", sa.String(16), nullable=False),
        sa.Column("png", sa.LargeBinary, nullable=False),
    ]


RESULTS = sa.MetaData()
"""The tables of a results database (:mod:`benchmark.store`)."""

results_runs = sa.Table(
    "runs",
    RESULTS,
    sa.Column("id", sa.Integer, primary_key=True),
    sa.Column("started", sa.Text, nullable=False),
    sa.Column("finished", sa.Text),
    sa.Column("argv", sa.Text, nullable=False),
    sa.Column("options", sa.Text, nullable=False),
    sa.Column("version", sa.Text, nullable=False),
    sa.Column("problems", sa.Text, nullable=False, server_default="[]"),
)
results_cells = sa.Table(
    "cells",
    RESULTS,
    sa.Column("id", sa.Integer, primary_key=True),
    sa.Column("run_id", sa.Integer, sa.ForeignKey("runs.id"), nullable=False),
    *cell_columns(),
    sa.Column("detail", sa.Text, nullable=False),
    sa.Column("finished", sa.Text, nullable=False),
)
cells_by_key = sa.Index(
    "cells_by_key",
    results_cells.c.tracker_key,
    results_cells.c.dataset_key,
    results_cells.c.seed,
    results_cells.c.init,
)
results_run_cells = sa.Table(
    "run_cells",
    RESULTS,
    sa.Column("run_id", sa.Integer, sa.ForeignKey("runs.id"), primary_key=True),
    sa.Column("cell_id", sa.Integer, sa.ForeignKey("cells.id"), primary_key=True),
)
results_frames = sa.Table(
    "frames",
    RESULTS,
    sa.Column("cell_id", sa.Integer, sa.ForeignKey("cells.id"), primary_key=True),
    sa.Column("position", sa.Integer, primary_key=True),
    sa.Column("frame", sa.Integer, nullable=False),
    sa.Column("outcome", sa.Text),
    # The CPU time of the step's thread; NULL in frames of files older than version 7, which timed the wall only.
    sa.Column("step_ms", sa.Float),
    sa.Column("wall_ms", sa.Float, nullable=False),
)
results_frame_errors = sa.Table(
    "frame_errors",
    RESULTS,
    sa.Column("cell_id", sa.Integer, primary_key=True),
    sa.Column("position", sa.Integer, primary_key=True),
    sa.Column("name", sa.Text, primary_key=True),
    sa.Column("value", sa.Float, nullable=False),
    sa.ForeignKeyConstraint(["cell_id", "position"], ["frames.cell_id", "frames.position"]),
)
results_pictures = sa.Table("pictures", RESULTS, *picture_columns("cells"))
results_conditions = sa.Table(
    "conditions",
    RESULTS,
    sa.Column("dataset_key", sa.Text, primary_key=True),
    sa.Column("name", sa.Text, primary_key=True),
    sa.Column("value", sa.Text, nullable=False),
)

HISTORY = sa.MetaData()
"""The tables of a history database (:mod:`benchmark.history.database`)."""

history_runs = sa.Table(
    "runs",
    HISTORY,
    sa.Column("id", sa.Integer, primary_key=True),
    sa.Column("started", sa.String(32), nullable=False),
    sa.Column("finished", sa.String(32), nullable=False),
    sa.Column("version", sa.String(64), nullable=False),
    sa.Column("commit", sa.String(64), nullable=False),
    sa.Column("machine_key", sa.String(32), nullable=False),
    sa.Column("machine", sa.Text, nullable=False),
    sa.Column("argv", sa.Text, nullable=False),
    sa.Column("seeds", sa.Integer, nullable=False),
    sa.Column("load", sa.Text, nullable=False, server_default="{}"),
)
history_cells = sa.Table(
    "cells",
    HISTORY,
    sa.Column("id", sa.Integer, primary_key=True),
    sa.Column("run_id", sa.Integer, sa.ForeignKey("runs.id"), nullable=False, index=True),
    *cell_columns(),
    sa.Column("metrics", sa.Text, nullable=False),
)
history_cell_frames = sa.Table(
    "cell_frames",
    HISTORY,
    sa.Column("cell_id", sa.Integer, sa.ForeignKey("cells.id"), primary_key=True),
    sa.Column("frames", sa.LargeBinary, nullable=False),
)
history_cell_pictures = sa.Table("cell_pictures", HISTORY, *picture_columns("cells"))
history_run_boards = sa.Table(
    "run_boards",
    HISTORY,
    sa.Column("run_id", sa.Integer, sa.ForeignKey("runs.id"), primary_key=True),
    sa.Column("modality", sa.Text, primary_key=True),
    sa.Column("board", sa.Text, nullable=False),
)
history_run_changes = sa.Table(
    "run_changes",
    HISTORY,
    sa.Column("run_id", sa.Integer, sa.ForeignKey("runs.id"), primary_key=True),
    sa.Column("changes", sa.Text, nullable=False),
)
history_cell_replays = sa.Table(
    "cell_replays",
    HISTORY,
    sa.Column("cell_id", sa.Integer, sa.ForeignKey("cells.id"), primary_key=True),
    sa.Column("state", sa.String(16), nullable=False),
    sa.Column("why", sa.Text, nullable=False),
    sa.Column("frames", sa.String(32), nullable=False),
    sa.Column("command", sa.Text, nullable=False),
    sa.Column("size", sa.Integer, nullable=False),
    sa.Column("digest", sa.String(64), nullable=False),
    sa.Column("page", sa.LargeBinary, nullable=True),
)


def add_column(connection: sa.Connection, table: sa.Table, column: sa.Column) -> None:
    """Add ``column``, as ``table`` declares it and with its default, to the database's older ``table``."""
    spec = sa.schema.CreateColumn(column).compile(dialect=connection.dialect)
    connection.execute(sa.text(f"ALTER TABLE {table.name} ADD COLUMN {spec}"))


def missing_columns(connection: sa.Connection, table: sa.Table) -> list[sa.Column]:
    """The columns of ``table`` that the database's table of that name lacks, in declaration order."""
    found = {column["name"] for column in sa.inspect(connection).get_columns(table.name)}
    return [column for column in table.columns if column.name not in found]


def add_missing_columns(connection: sa.Connection, metadata: sa.MetaData) -> None:
    """Give each of the database's tables of ``metadata`` the columns it lacks (see :func:`add_column`).

    Tables the database does not hold are left to
    :meth:`sqlalchemy.MetaData.create_all`.
    """
    existing = set(sa.inspect(connection).get_table_names())
    for table in metadata.sorted_tables:
        if table.name in existing:
            for column in missing_columns(connection, table):
                add_column(connection, table, column)
