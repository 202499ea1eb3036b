"""Executors by name: trackbench's own and a third party's come through the entry-point group alike."""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from benchmark.errors import DataError
from benchmark.executors import ENTRY_POINT_GROUP, ExecutorOptions, executor_names, open_executor
from benchmark.executors.local import LocalExecutor

FAULT_PLUGIN = Path(__file__).parents[1] / "fault_plugin.py"

SERIAL = '''
"""acme-serial: an executor that runs cells one after another in the calling process, and says so."""

import os

from benchmark.runner import run_cell


class SerialExecutor:
    runs_here = True

    @classmethod
    def open(cls, options):
        return cls()

    def run(self, cells, timeout_s):
        for cell in cells:
            with open(os.environ["ACME_SERIAL_LOG"], "a") as log:
                log.write(cell.label() + "\\n")
            yield run_cell(cell, timeout_s)

    def call(self, function, args, timeout_s):
        return function(*args)

    def running(self):
        return []

    def close(self):
        pass
'''


def installed(site: Path, module: str, source: str, entry_points: str) -> None:
    """A distribution ``acme-<module> 1.0`` in ``site``, holding ``module`` with ``entry_points``."""
    (site / f"{module}.py").write_text(source)
    info = site / f"{module}-1.0.dist-info"
    info.mkdir()
    (info / "METADATA").write_text(f"Metadata-Version: 2.1\nName: {module.replace('_', '-')}\nVersion: 1.0\n")
    (info / "entry_points.txt").write_text(entry_points)


def test_trackbench_s_own_executors_are_registered_the_local_one_first() -> None:
    assert executor_names()[:1] == ("local",) and "dask" in executor_names()
    assert isinstance(open_executor("local", ExecutorOptions(jobs=1)), LocalExecutor)


@pytest.mark.parametrize(
    ("name", "options", "says"),
    [
        ("ray", ExecutorOptions(), "unknown executor 'ray' (installed: local, dask"),
        ("local", ExecutorOptions(scheduler="tcp://h:8786"), "--scheduler needs --executor dask"),
        ("dask", ExecutorOptions(in_process=True), "--in-process runs cells in this process"),
    ],
)
def test_an_executor_that_is_not_installed_or_an_option_it_does_not_take_is_a_data_error(
    name: str, options: ExecutorOptions, says: str
) -> None:
    with pytest.raises(DataError, match="^" + re.escape(says)):
        open_executor(name, options)


def test_a_third_party_executor_is_one_module_and_one_entry_point(tmp_path: Path) -> None:
    site = tmp_path / "site"
    site.mkdir()
    shutil.copy(FAULT_PLUGIN, site / "acme_faults.py")
    installed(site, "acme_faults_dist", "", "[trackbench]\nfaults = acme_faults\n")
    installed(site, "acme_serial", SERIAL, f"[{ENTRY_POINT_GROUP}]\nserial = acme_serial:SerialExecutor\n")
    log = tmp_path / "serial.log"
    out = tmp_path / "out"
    environment = {**os.environ, "PYTHONPATH": str(site), "ACME_SERIAL_LOG": str(log)}
    arguments = ["run", "--suite", "faults", "--tracker", "honest", "--executor", "serial", "--out", str(out)]
    result = subprocess.run(
        [sys.executable, "-c", "from benchmark.cli import main; main()", *arguments],
        capture_output=True, text=True, env=environment, check=False,
    )
    assert result.returncode == 0, result.stderr
    assert log.read_text().splitlines() == ["honest on faults/corridor, seed 0"]  # it ran the cell
    assert (out / "leaderboard.csv").is_file()
