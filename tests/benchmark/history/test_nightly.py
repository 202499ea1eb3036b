"""``trackbench nightly``, ``compare`` and ``report`` through click's runner, with the fake registry."""

from __future__ import annotations

from pathlib import Path

from benchmark.cli import EXIT_REGRESSION
from benchmark.history.database import History

from ..conftest import Invoke


def nightly(invoke: Invoke, tmp_path: Path, *extra: str):  # noqa: ANN201
    return invoke(
        "nightly", "--tracker", "noisy", "--seeds", "2", "--in-process", "--out", str(tmp_path / "out"),
        "--history", str(tmp_path / "history.sqlite"), "--site", str(tmp_path / "site"), *extra,
    )


def test_a_worsened_parameter_is_a_regression_in_the_exit_status_the_output_and_the_site(
    invoke: Invoke, tmp_path: Path
) -> None:
    first = nightly(invoke, tmp_path)
    assert first.exit_code == 0, first.output
    assert "cells 4/4, 0 failed, elapsed " in first.stderr and "site pages " in first.stderr  # a log's progress
    assert "no change beyond the thresholds" in first.stdout
    second = nightly(invoke, tmp_path, "--param", "noisy.sigma_px=40")
    assert second.exit_code == EXIT_REGRESSION, second.output
    assert "regression" in second.stdout and "rmse_d_px" in second.stdout and "sigma_px" in second.stdout
    with History(tmp_path / "history.sqlite") as history:
        assert history.runs()["id"].tolist() == [1, 2]
    index = (tmp_path / "site" / "index.html").read_text()
    assert "regression" in index.lower() and "rmse_d_px" in index and "noisy" in index

    compared = invoke("compare", "1", "2", "--history", str(tmp_path / "history.sqlite"))
    assert compared.exit_code == 0, compared.output
    assert "regression" in compared.stdout and "rmse_d_px" in compared.stdout
    backwards = invoke("compare", "2", "1", "--history", str(tmp_path / "history.sqlite"))
    assert "improvement" in backwards.stdout and "regression" not in backwards.stdout

    (tmp_path / "site" / "index.html").unlink()
    rebuilt = invoke("report", "--history", str(tmp_path / "history.sqlite"), "--site", str(tmp_path / "site"))
    assert rebuilt.exit_code == 0, rebuilt.output
    assert "site pages " in rebuilt.stderr
    assert "rmse_d_px" in (tmp_path / "site" / "index.html").read_text()


def test_compare_and_report_name_a_missing_history_or_run(invoke: Invoke, tmp_path: Path) -> None:
    missing = invoke("compare", "1", "2", "--history", str(tmp_path / "none.sqlite"))
    assert missing.exit_code == 2 and "none.sqlite" in missing.output
    assert not (tmp_path / "none.sqlite").exists()
    assert nightly(invoke, tmp_path).exit_code == 0
    unknown = invoke("compare", "1", "7", "--history", str(tmp_path / "history.sqlite"))
    assert unknown.exit_code == 2 and "no run 7" in unknown.output
    bad = nightly(invoke, tmp_path, "--min-effect", "correct_pct")
    assert bad.exit_code == 2 and "METRIC=NUMBER" in bad.output
