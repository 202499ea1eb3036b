"""Fault injection: a third-party plugin whose trackers raise, exit, interrupt, spin, crash and lie.

The plugin (``fault_plugin.py``) is installed as a real distribution in a
temporary site folder.  Whatever its trackers do, a run must end with one
error or timeout row per faulty cell (frames before the fault kept), the
honest tracker's cell ``ok``, a board, exit status 1 and no traceback; only
the user's Ctrl-C stops a run (exit 130, finished cells kept), and workers
die with the run.
"""

from __future__ import annotations

import os
import re
import shutil
import signal
import subprocess
import sys
import time
from collections.abc import Iterator
from pathlib import Path

import filelock
import pandas as pd
import pytest
from click.testing import CliRunner, Result

from benchmark.cli import main
from benchmark.store import DATABASE_NAME, ResultStore

PLUGIN_SOURCE = Path(__file__).with_name("fault_plugin.py")
FAULT_AT = 2
TIMEOUT_S = 6.0  # long enough for an honest cell of six small frames on a loaded machine

EXPECTED = {
    # tracker: (status, message start, frames kept)
    "honest": ("ok", "", 6),
    "exits": ("error", "SystemExit: 3 (frame 2)", 2),
    "interrupts": ("error", "KeyboardInterrupt (frame 2)", 2),
    "raises-oddly": ("error", "Unprintable: <Unprintable that cannot be shown> (frame 2)", 2),
    "returns-nan": ("error", "EstimateError: tracker 'returns-nan' returned an invalid estimate", 2),
    "returns-absurd": ("ok", "", 6),
    "hangs": ("timeout", f"no result within the {TIMEOUT_S:g} s limit", 0),
    "exits-hard": ("error", "the worker process ended (exit status 7)", 0),
    "segfaults": ("error", "the worker process ended (killed by SIGSEGV)", 0),
    "leaves-session": ("ok", "", 6),
    "settled": ("ok", "", 6),  # after leaves-session: in a worker of the run's session, or an error
}
IN_PROCESS_SAFE = ["honest", "exits", "interrupts", "raises-oddly", "returns-nan", "returns-absurd"]


@pytest.fixture(scope="module")
def site(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A site folder holding the distribution ``acme-faults 1.0`` with its ``trackbench`` entry point."""
    folder = tmp_path_factory.mktemp("site")
    shutil.copy(PLUGIN_SOURCE, folder / "acme_faults.py")
    info = folder / "acme_faults-1.0.dist-info"
    info.mkdir()
    (info / "METADATA").write_text("Metadata-Version: 2.1\nName: acme-faults\nVersion: 1.0\n")
    (info / "entry_points.txt").write_text("[trackbench]\nfaults = acme_faults\n")
    return folder


@pytest.fixture
def faults_installed(site: Path, monkeypatch: pytest.MonkeyPatch) -> Iterator[None]:
    monkeypatch.syspath_prepend(str(site))
    yield
    sys.modules.pop("acme_faults", None)


def invoke(*arguments: str) -> Result:
    return CliRunner().invoke(main, list(arguments))


def stored_cells(out: Path) -> pd.DataFrame:
    with ResultStore(out / DATABASE_NAME) as store:
        return store.cells().set_index("tracker")


def assert_rows_as_expected(cells: pd.DataFrame, trackers: list[str]) -> None:
    assert sorted(cells.index) == sorted(trackers)
    for tracker in trackers:
        status, message, frames = EXPECTED[tracker]
        row = cells.loc[tracker]
        assert (row["status"], row["frames"]) == (status, frames), (tracker, row["message"])
        assert row["message"].startswith(message), (tracker, row["message"])


@pytest.mark.parametrize(
    "executor", [["--jobs", "0"], ["--jobs", "2"], ["--executor", "dask", "--jobs", "2"]], ids=["1", "2", "dask"]
)
def test_every_fault_becomes_its_cell_s_row_and_the_run_exits_1(
    faults_installed: None, site: Path, tmp_path: Path, executor: list[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    if "dask" in executor:
        pytest.importorskip("distributed", reason="the Dask executor needs dask.distributed")
        monkeypatch.setenv("PYTHONPATH", str(site))  # the cluster's worker processes import the plugin
    trackers = list(EXPECTED)
    selected = [word for tracker in trackers for word in ("--tracker", tracker)]
    limit = ["--timeout", f"{TIMEOUT_S}"]
    result = invoke("run", "--suite", "faults", *selected, *executor, *limit, "--out", str(tmp_path))
    assert result.exit_code == 1, result.output
    assert "Traceback" not in result.output
    assert "7 of 11 cells did not end ok" in result.output
    assert_rows_as_expected(stored_cells(tmp_path), trackers)
    board = pd.read_csv(tmp_path / "leaderboard.csv")
    absurd = board[(board.tracker == "returns-absurd") & (board.dataset == "(all)")].iloc[0]
    assert absurd["false_pct"] == pytest.approx(100.0 * 4 / 6)
    assert pd.notna(absurd["rmse_d_px"]) and absurd["rmse_d_px"] < float("inf")


def test_in_process_mode_keeps_every_fault_a_process_can_survive_in_its_cell(
    faults_installed: None, tmp_path: Path
) -> None:
    selected = [word for tracker in IN_PROCESS_SAFE for word in ("--tracker", tracker)]
    result = invoke("run", "--suite", "faults", *selected, "--in-process", "--out", str(tmp_path))
    assert result.exit_code == 1, result.output
    assert_rows_as_expected(stored_cells(tmp_path), IN_PROCESS_SAFE)


def test_a_clean_run_exits_0_and_a_usage_error_2_before_anything_runs(faults_installed: None, tmp_path: Path) -> None:
    assert invoke("run", "--suite", "faults", "--tracker", "honest", "--out", str(tmp_path)).exit_code == 0
    unknown = invoke("run", "--suite", "faults", "--tracker", "nobody", "--out", str(tmp_path / "other"))
    assert unknown.exit_code == 2 and unknown.output.startswith("Error: unknown tracker 'nobody'")
    assert not (tmp_path / "other").exists()


def test_a_second_run_on_the_same_folder_is_refused_while_the_first_holds_it(
    faults_installed: None, tmp_path: Path
) -> None:
    with filelock.FileLock(tmp_path / f"{DATABASE_NAME}.lock"):
        result = invoke("run", "--suite", "faults", "--tracker", "honest", "--out", str(tmp_path))
    assert result.exit_code == 2
    assert "another trackbench run is writing this results folder" in result.output
    assert not (tmp_path / DATABASE_NAME).exists()


def test_a_plugin_that_fails_to_import_leaves_only_its_own_trackers_out(
    faults_installed: None, installed, tmp_path: Path
) -> None:
    installed("broken-dist", {"broken": "no_such_module_anywhere"}, version="2.0")
    listing = invoke("list")
    assert listing.exit_code == 1
    assert "unavailable: plugin 'broken' (broken-dist 2.0) failed to import 'no_such_module_anywhere'" in listing.output
    assert "honest 1.0" in listing.output
    run = invoke("run", "--suite", "faults", "--tracker", "honest", "--out", str(tmp_path))
    assert run.exit_code == 1, run.output
    assert stored_cells(tmp_path).loc["honest", "status"] == "ok"
    for board in ("leaderboard.md", "leaderboard.html"):
        assert "plugin &#x27;broken&#x27;" in (text := (tmp_path / board).read_text()) or "plugin 'broken'" in text
    strict = invoke("--strict-plugins", "list")
    assert strict.exit_code == 2 and strict.output.startswith("Error: plugin 'broken' (broken-dist 2.0) failed")


# Processes of their own: Ctrl-C to the process group, kill -9 of the main process, a FIFO as a frame.


def start_trackbench(site: Path, *arguments: str, env: dict[str, str] | None = None) -> subprocess.Popen[str]:
    environment = {**os.environ, "PYTHONPATH": str(site), **(env or {})}
    return subprocess.Popen(
        [sys.executable, "-c", "from benchmark.cli import main; main()", *arguments],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        env=environment,
        start_new_session=True,
    )


def wait_for(predicate, timeout_s: float = 60.0) -> None:
    deadline = time.monotonic() + timeout_s
    while not predicate():
        assert time.monotonic() < deadline, "timed out waiting"
        time.sleep(0.05)


def alive(pid: int) -> bool:
    try:
        state = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0]
    except (FileNotFoundError, ProcessLookupError):
        return False
    return state != "Z"


linux_only = pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads /proc")


@linux_only
@pytest.mark.parametrize(("signum", "status"), [(signal.SIGINT, 130), (signal.SIGTERM, 143)], ids=["ctrl-c", "sigterm"])
def test_ctrl_c_or_sigterm_stops_the_run_keeps_the_finished_cells_publishes_and_exits_128_plus_the_signal(
    site: Path, tmp_path: Path, signum: int, status: int
) -> None:
    selected = ["--tracker", "honest", "--tracker", "slow"]
    process = start_trackbench(
        site, "run", "--suite", "faults", *selected, "--jobs", "1", "--out", str(tmp_path), "--verbose"
    )  # --verbose: a line for each finished cell, ok ones included
    lines: list[str] = []
    assert process.stderr is not None
    for line in process.stderr:
        lines.append(line)
        if line.startswith("honest "):
            break
    os.killpg(process.pid, signum)  # the whole process group, workers included, as a terminal or scheduler does
    stdout, rest = process.communicate()
    assert process.returncode == status, "".join(lines) + rest
    assert "interrupted: 1 cells finished and kept, 1 not run" in rest
    assert "Traceback" not in rest
    cells = stored_cells(tmp_path)
    assert list(cells.index) == ["honest"] and cells.loc["honest", "status"] == "ok"
    assert "honest" in (tmp_path / "leaderboard.md").read_text()


@linux_only
def test_workers_die_with_a_killed_run(site: Path, tmp_path: Path) -> None:
    pid_file = tmp_path / "worker.pid"
    process = start_trackbench(
        site,
        "run", "--suite", "faults", "--tracker", "spins", "--jobs", "1", "--timeout", "600", "--out", str(tmp_path),
        env={"ACME_FAULTS_PID_FILE": str(pid_file)},
    )
    wait_for(lambda: pid_file.exists() and pid_file.read_text().strip())
    worker = int(pid_file.read_text())
    assert alive(worker)
    process.kill()
    process.communicate(timeout=60)
    wait_for(lambda: not alive(worker), timeout_s=10.0)


@linux_only
def test_a_fifo_as_a_frame_costs_its_cell_not_the_run(site: Path, tmp_path: Path) -> None:
    os.mkfifo(tmp_path / "frame_000.png")
    (tmp_path / "seq.txt").write_text("1 0 6 0 # frame_000.png\n")
    process = start_trackbench(
        site, "run", "--dataset", str(tmp_path / "seq.txt"), "--tracker", "honest", "--timeout", "1",
        "--out", str(tmp_path / "out"),
    )
    stdout, stderr = process.communicate(timeout=120)
    assert process.returncode == 1, stderr
    cells = stored_cells(tmp_path / "out")
    assert cells.loc["honest", "status"] == "timeout"


def test_a_tracker_that_prints_does_not_print_into_the_board(site: Path, tmp_path: Path) -> None:
    process = start_trackbench(
        site, "run", "--suite", "faults", "--tracker", "chatty", "--tracker", "honest", "--jobs", "2",
        "--out", str(tmp_path / "out"),
    )
    stdout, stderr = process.communicate()
    assert process.returncode == 0, stderr
    assert "chatter" not in stdout and "chatty" in stdout  # its row is on the board, its words are not
    assert "chatter from print" in stderr and "chatter from fd 1" in stderr


def test_in_process_a_tracker_s_print_goes_to_stderr(faults_installed: None, tmp_path: Path) -> None:
    result = invoke("run", "--suite", "faults", "--tracker", "chatty", "--in-process", "--out", str(tmp_path))
    assert result.exit_code == 0, result.output
    assert "chatter from print" not in result.stdout and "chatter from print" in result.stderr


def test_terminal_escapes_in_a_plugin_s_message_are_shown_not_obeyed(faults_installed: None, tmp_path: Path) -> None:
    result = invoke("run", "--suite", "faults", "--tracker", "raises-in-colour", "--in-process", "--out", str(tmp_path))
    assert result.exit_code == 1
    for stream in (result.stdout, result.stderr):
        assert "\x1b" not in stream and "\x07" not in stream
    assert "RuntimeError: \\x1b[31mred\\x1b[0m\\x07" in result.stderr  # the cell's line
    board = invoke("leaderboard", "--out", str(tmp_path))
    assert "\x1b" not in board.stdout and "RuntimeError: \\x1b[31mred" in board.stdout  # the full board's status


def test_check_gives_each_fault_its_failed_checks_and_goes_on(faults_installed: None) -> None:
    trackers = ["exits", "interrupts", "raises-oddly", "spins", "exits-hard", "segfaults", "honest"]
    result = invoke("check", *trackers, "--frames", "3", "--time-limit", "0.5")
    assert result.exit_code == 1, result.output
    assert "Traceback" not in result.output
    rows = {tuple(line.split()[:2]): line for line in result.output.splitlines()[1:-1]}
    assert len(rows) == 7 * 14
    # A spinning tracker uses its 0.5 s of CPU time; on a machine so loaded that it gets less than a tenth of a core,
    # the wall-time stop (WAIT_FACTOR times the limit) comes first.  Either names the hang.
    spent = r"(0\.5 s of CPU time|5 s of waiting \(0\.5 s of CPU time allowed\))"
    expected = {
        "exits": re.escape("SystemExit: 3 (step, frame 2)"),
        "interrupts": re.escape("KeyboardInterrupt (step, frame 2)"),
        "raises-oddly": re.escape("Unprintable: <Unprintable that cannot be shown> (step, frame 2)"),
        "spins": f"did not finish within {spent} " + re.escape("(step, frame 2): does it hang?"),
        "exits-hard": re.escape("the worker process ended (exit status 7) during the check"),
        "segfaults": re.escape("the worker process ended (killed by SIGSEGV) during the check"),
    }
    for tracker, pattern in expected.items():
        assert "FAIL" in rows[tracker, "runs"] and re.search(pattern, rows[tracker, "runs"]), rows[tracker, "runs"]
        assert " ok " in rows[tracker, "metadata"]
        assert "follows from 'runs'" in rows[tracker, "same_seed_same_output"]  # the root cause is named once
    assert " ok " in rows["honest", "runs"] and " ok " in rows["honest", "pickles"]


@linux_only
def test_a_cell_s_folder_environment_group_session_and_daemons_do_not_outlive_it(site: Path, tmp_path: Path) -> None:
    pid_file = tmp_path / "daemon.pid"
    process = start_trackbench(
        site,
        "run", "--suite", "faults", "--tracker", "wanders", "--tracker", "daemonises", "--tracker", "regroups",
        "--tracker", "leaves-session", "--tracker", "settled",
        "--seeds", "2", "--jobs", "1", "--out", str(tmp_path / "out"),
        env={"ACME_FAULTS_PID_FILE": str(pid_file)},
    )
    stdout, stderr = process.communicate()
    assert process.returncode == 0, stderr
    cells = stored_cells(tmp_path / "out")
    assert (cells["status"] == "ok").all() and len(cells) == 10, cells["message"]
    assert cells.loc["settled", "id"].min() > cells.loc["leaves-session", "id"].min()  # after a cell that left
    daemons = [int(path.read_text()) for path in tmp_path.glob("daemon.pid.*")]
    assert len(daemons) == 2
    assert not any(alive(pid) for pid in daemons)  # killed before their cells returned, so gone by now


def test_a_tracker_drawing_from_numpy_s_global_generator_differs_by_seed_and_repeats_by_seed(
    faults_installed: None, tmp_path: Path
) -> None:
    boards = []
    for run in ("first", "second"):
        arguments = ["run", "--suite", "faults", "--tracker", "global-random", "--seeds", "2", "--jobs", "2"]
        result = invoke(*arguments, "--out", str(tmp_path / run))
        assert result.exit_code == 0, result.output
        boards.append(pd.read_csv(tmp_path / run / "leaderboard.csv").drop(columns=["cpu_fps", "wall_fps"]))
    pd.testing.assert_frame_equal(boards[0], boards[1])
    row = boards[0][boards[0].dataset == "(all)"].iloc[0]
    assert not row["deterministic"] and row["rmse_d_lo_px"] < row["rmse_d_hi_px"]
