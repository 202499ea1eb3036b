"""The history on a real PostgreSQL server, started by the tests where one is installed (skipped where not).

PostgreSQL refuses to run as root, as the tests do in CI: a root test
runs the server as an unprivileged user (``postgres``, else ``nobody``)
in a temporary folder that user owns.  The server listens on a Unix
socket in that folder only, and asks for a password (SCRAM), so that the
URLs of these tests carry one and the tests can check it is never shown.
"""

from __future__ import annotations

import os
import pwd
import shutil
import subprocess
import tempfile
from collections.abc import Iterator
from pathlib import Path

import pytest
import sqlalchemy as sa

from benchmark import schema
from benchmark.history.database import History

from ..conftest import Invoke

PASSWORD = "pg-Secret-4711"
WRONG_PASSWORD = "not-the-Secret-0815"
USER = "trackbench"
SERVER_PROGRAMS = ("initdb", "pg_ctl", "postgres")
UNPRIVILEGED_USERS = ("postgres", "nobody")


def server_programs() -> dict[str, str] | None:
    """initdb, pg_ctl and postgres of one installation: on the PATH, else Debian's newest, else None."""
    on_path = {name: shutil.which(name) for name in SERVER_PROGRAMS}
    if all(on_path.values()):
        return {name: str(found) for name, found in on_path.items()}
    for folder in sorted(Path("/usr/lib/postgresql").glob("*/bin"), key=lambda path: path.parent.name, reverse=True):
        if all((folder / name).is_file() for name in SERVER_PROGRAMS):
            return {name: str(folder / name) for name in SERVER_PROGRAMS}
    return None


def server_user() -> tuple[list[str], pwd.struct_passwd | None]:
    """The command prefix that runs the server's programs, and the user they run as (None: this process's)."""
    if os.geteuid() != 0:
        return [], None
    runuser = shutil.which("runuser")
    if runuser is None:
        pytest.skip("PostgreSQL refuses to run as root, and runuser, to run it as another user, is not installed")
    for name in UNPRIVILEGED_USERS:
        try:
            user = pwd.getpwnam(name)
        except KeyError:
            continue
        return [runuser, "-u", name, "--"], user
    pytest.skip(f"PostgreSQL refuses to run as root, and none of the users {UNPRIVILEGED_USERS} exists to run it")


def url(folder: Path, password: str = PASSWORD, database: str = "postgres") -> str:
    """The URL of a database of the server whose socket is in ``folder``."""
    return f"postgresql://{USER}:{password}@/{database}?host={folder}"


@pytest.fixture(scope="session")
def postgresql_server() -> Iterator[Path]:
    """A PostgreSQL server of this session, by its socket's folder; user :data:`USER`, password :data:`PASSWORD`."""
    pytest.importorskip("psycopg", reason="the driver psycopg is not installed (pip install -e '.[test]')")
    programs = server_programs()
    if programs is None:
        pytest.skip("no PostgreSQL server installed (initdb, pg_ctl, postgres on the PATH or in /usr/lib/postgresql)")
    prefix, user = server_user()
    # /tmp, whatever $TMPDIR says: the server's user must reach the folder, and a socket's path is short (107 bytes).
    folder = Path(tempfile.mkdtemp(prefix="trackbench-pg-", dir="/tmp" if Path("/tmp").is_dir() else None))
    password_file = folder / "password"
    password_file.write_text(PASSWORD)
    if user is not None:
        for path in (folder, password_file):
            os.chown(path, user.pw_uid, user.pw_gid)
    data = folder / "data"

    def run(*command: str) -> None:
        done = subprocess.run([*prefix, *command], capture_output=True, text=True, cwd=folder)
        if done.returncode != 0:
            log = folder / "log"
            detail = log.read_text() if log.exists() else ""
            pytest.fail(f"{' '.join(command)} failed ({done.returncode}): {done.stdout}{done.stderr}{detail}")

    run(programs["initdb"], "--no-sync", "-E", "UTF8", "--locale=C", "-D", str(data), "-U", USER,
        "-A", "scram-sha-256", f"--pwfile={password_file}")
    options = f"-k {folder} -c listen_addresses='' -c fsync=off -c full_page_writes=off"
    run(programs["pg_ctl"], "-D", str(data), "-o", options, "-l", str(folder / "log"), "-w", "start")
    try:
        yield folder
    finally:
        subprocess.run([*prefix, programs["pg_ctl"], "-D", str(data), "-m", "immediate", "stop"],
                       capture_output=True, cwd=folder)
        shutil.rmtree(folder, ignore_errors=True)


@pytest.fixture
def empty_database(postgresql_server: Path, request: pytest.FixtureRequest) -> str:
    """The URL of a new, empty database of the session's server."""
    name = "h_" + "".join(c if c.isalnum() else "_" for c in request.node.name.lower())[:50]
    engine = sa.create_engine(url(postgresql_server).replace("postgresql://", "postgresql+psycopg://"),
                              isolation_level="AUTOCOMMIT")
    with engine.connect() as connection:
        connection.execute(sa.text(f'DROP DATABASE IF EXISTS "{name}"'))
        connection.execute(sa.text(f'CREATE DATABASE "{name}"'))
    engine.dispose()
    return url(postgresql_server, database=name)


def nightly(invoke: Invoke, tmp_path: Path, history: str, *extra: str):  # noqa: ANN201
    return invoke(
        "nightly", "--tracker", "noisy", "--seeds", "2", "--in-process", "--out", str(tmp_path / "out"),
        "--history", history, "--site", str(tmp_path / "site"), *extra,
    )


def test_two_nightlies_are_kept_and_read_back_and_the_password_is_never_shown(
    invoke: Invoke, tmp_path: Path, empty_database: str
) -> None:
    first = nightly(invoke, tmp_path, empty_database)
    assert first.exit_code == 0, first.output
    second = nightly(invoke, tmp_path, empty_database, "--param", "noisy.sigma_px=40")
    assert second.exit_code == 3, second.output  # a regression, found against the first run on the server
    assert "rmse_d_px" in second.stdout and "sigma_px" in second.stdout
    assert f"{USER}:***@" in second.output

    with History(empty_database) as history:
        runs = history.runs()
        cells = history.cells()
        first_cell = int(cells["id"].iloc[0])
        frames = history.frames(first_cell)
        pictures = history.pictures(int(cells["id"].iloc[-1]))
        replays = history.replays()
        page = history.replay_page(int(replays["cell_id"].iloc[-1]))
    assert runs["id"].tolist() == [1, 2] and runs["seeds"].tolist() == [2, 2]
    assert set(cells["run_id"]) == {1, 2} and set(cells["seed"]) == {0, 1}
    assert (cells[cells["run_id"] == 2]["params"].map(lambda params: params["sigma_px"]) == 40).all()
    assert len(frames) > 0 and {"frame", "outcome"} <= set(frames.columns)
    assert all(picture.png.startswith(b"\x89PNG") for picture in pictures)
    assert set(replays["state"]) == {"recorded"} and page.startswith(b"<!DOCTYPE html>")  # noisy misses frames
    assert len(page) == int(replays["size"].iloc[-1])

    compared = invoke("compare", "1", "2", "--history", empty_database)
    assert compared.exit_code == 0, compared.output
    assert "regression" in compared.stdout

    refused = nightly(invoke, tmp_path / "refused", empty_database.replace(PASSWORD, WRONG_PASSWORD))
    assert refused.exit_code == 2 and refused.output.startswith("Error: history database postgresql://")
    assert "password authentication failed" in refused.output and not (tmp_path / "refused" / "out").exists()
    for result in (first, second, compared, refused):
        assert PASSWORD not in result.output and WRONG_PASSWORD not in result.output
    assert "Traceback" not in refused.output and len(refused.output.strip().splitlines()) == 1


def test_another_programs_database_on_the_server_is_refused_before_any_cell_runs(
    invoke: Invoke, tmp_path: Path, empty_database: str
) -> None:
    with History(empty_database):
        pass  # an empty database is taken and given the tables of a history
    engine = sa.create_engine(empty_database.replace("postgresql://", "postgresql+psycopg://"))
    schema.HISTORY.drop_all(engine)
    with engine.begin() as connection:
        connection.execute(sa.text("CREATE TABLE invoices (x TEXT)"))
    engine.dispose()
    result = nightly(invoke, tmp_path, empty_database)
    assert result.exit_code == 2, result.output
    assert "holds other tables (invoices)" in result.output and PASSWORD not in result.output
    assert not (tmp_path / "out").exists()
