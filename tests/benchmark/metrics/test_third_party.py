"""A third party's metric is one module and one entry point: on the boards, in the history and judged."""

from __future__ import annotations

import importlib.util
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pandas as pd

from benchmark.history.database import History
from benchmark.history.regressions import find_changes
from benchmark.metrics import CORE

from ..executors.test_registry import FAULT_PLUGIN, installed

ESTIMATED = '''
"""acme-estimated: how often a tracker gives an estimate at all, per cent of scored frames."""

from benchmark import hookimpl
from benchmark.metrics import Effect, Metric, percentage


def sums(frames, scale):
    scored = frames["outcome"].notna()
    estimated = frames.filter(like="err_").notna().any(axis=1) & scored
    return float(scored.sum()), float(estimated.sum())


ESTIMATED = Metric(
    name="estimated_pct", better="higher", kind="detection", columns=("outcome",), sums=sums,
    value=percentage, digits=1, minimum_effect=Effect(5.0),
)


@hookimpl
def trackbench_register_metrics(registry):
    registry.add_metric(ESTIMATED)
'''


def test_a_third_party_metric_stands_on_the_board_in_the_history_and_the_site_and_is_judged(tmp_path: Path) -> None:
    site = tmp_path / "site"
    site.mkdir()
    shutil.copy(FAULT_PLUGIN, site / "acme_faults.py")
    installed(site, "acme_faults_dist", "", "[trackbench]\nfaults = acme_faults\n")
    installed(site, "acme_estimated", ESTIMATED, "[trackbench]\nestimated = acme_estimated\n")
    out, history = tmp_path / "out", tmp_path / "history.sqlite"
    arguments = [
        "nightly", "--suite", "faults", "--tracker", "honest", "--seeds", "2", "--in-process", "--out", str(out),
        "--history", str(history), "--site", str(tmp_path / "pages"),
    ]
    result = subprocess.run(
        [sys.executable, "-c", "from benchmark.cli import main; main()", *arguments],
        capture_output=True, text=True, env={**os.environ, "PYTHONPATH": str(site)}, check=False,
    )
    assert result.returncode == 0, result.stderr

    board = pd.read_csv(out / "leaderboard.csv")
    assert board["estimated_pct"].notna().all() and {"estimated_lo_pct", "estimated_hi_pct"} <= set(board.columns)
    assert list(board.columns).index("estimated_pct") < list(board.columns).index("rmse_d_px")  # with the rates
    assert "estimated\\_pct" in (out / "leaderboard.md").read_text()
    assert "estimated_<wbr>pct" in (tmp_path / "pages" / "index.html").read_text()
    with History(history) as database:
        cells = database.cells()
    assert cells["estimated_pct"].notna().all()

    spec = importlib.util.spec_from_file_location("acme_estimated", site / "acme_estimated.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    worse = cells.assign(run_id=2, estimated_pct=cells["estimated_pct"] - 10.0)
    changes = find_changes(pd.concat([cells, worse]), 2, metrics=CORE.adding(module.ESTIMATED))
    assert changes[["metric", "verdict"]].values.tolist() == [["estimated_pct", "regression"]]
    assert find_changes(pd.concat([cells, worse]), 2).empty  # without the plugin, nobody judges its column
