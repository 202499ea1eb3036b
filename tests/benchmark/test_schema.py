"""Tests of benchmark.schema: the results database and the history keep cells and pictures in the same columns."""

from __future__ import annotations

import sqlalchemy as sa

from benchmark import schema


def described(column: sa.Column) -> tuple[str, str, bool, str | None, list[str]]:
    """A column's name, SQLite type, nullability, default and checks, as the database would be told them."""
    dialect = sa.create_engine("sqlite://").dialect
    default = None if column.server_default is None else str(sa.schema.CreateColumn(column).compile(dialect=dialect))
    checks = [str(constraint.sqltext) for constraint in column.constraints if isinstance(constraint, sa.CheckConstraint)]
    return column.name, column.type.compile(dialect=dialect), bool(column.nullable), default, checks


def test_both_databases_keep_cells_and_pictures_in_the_same_columns() -> None:
    shared = [column.name for column in schema.cell_columns()]
    assert {"tracker_key", "dataset_key", "seed", "init", "status", "deterministic"} <= set(shared)
    for name in shared:
        assert described(schema.results_cells.c[name]) == described(schema.history_cells.c[name])
    for name in ("cell_id", "frame", "outcome", "png"):
        assert described(schema.results_pictures.c[name]) == described(schema.history_cell_pictures.c[name])
    assert set(schema.results_cells.c.keys()) - set(shared) == {"id", "run_id", "detail", "finished"}
    assert set(schema.history_cells.c.keys()) - set(shared) == {"id", "run_id", "metrics"}


def test_a_table_of_an_older_version_gains_the_columns_it_lacks_with_their_defaults() -> None:
    engine = sa.create_engine("sqlite://")
    with engine.begin() as connection:
        connection.exec_driver_sql("CREATE TABLE run_cells (run_id INTEGER, cell_id INTEGER)")  # no other table
        connection.exec_driver_sql(
            "CREATE TABLE runs (id INTEGER PRIMARY KEY, started TEXT, finished TEXT, argv TEXT, options TEXT, version TEXT)"
        )
        connection.exec_driver_sql("INSERT INTO runs VALUES (1, 's', NULL, '[]', '{}', '0.1')")
        assert [column.name for column in schema.missing_columns(connection, schema.results_runs)] == ["problems"]
        schema.add_missing_columns(connection, schema.RESULTS)
        assert schema.missing_columns(connection, schema.results_runs) == []
        assert connection.execute(sa.select(schema.results_runs.c.problems)).scalar_one() == "[]"
        assert sa.inspect(connection).get_table_names() == ["run_cells", "runs"]  # missing tables are create_all's
