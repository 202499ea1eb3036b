"""Cells on a real Dask cluster on localhost: the same board as the local pool, and the same isolation.

The board is compared on the first :data:`CLIP_FRAMES` frames of a camera, a
sonar and a stereo sequence, written as files, so that both runs read the
same short clips instead of rendering whole sequences.
"""

from __future__ import annotations

import dataclasses
import logging
from collections.abc import Iterator
from pathlib import Path

import pandas as pd
import pytest
from click.testing import CliRunner

from benchmark.cli import main
from benchmark.io import export_sequence
from benchmark.plugins import load_registry
from benchmark.results import Picture
from benchmark.store import DATABASE_NAME, ResultStore

from ..site.conftest import Clip

distributed = pytest.importorskip("distributed", reason="the Dask executor needs dask.distributed")

SPEED_COLUMNS = {"cpu_fps", "wall_fps", "ms_per_frame", "elapsed_s"}
TRACKERS = ["--tracker", "hough", "--tracker", "sonar_pf", "--tracker", "stereo_ekf"]
SEQUENCES = ["camera/S6", "sonar/concrete", "stereo-images/case1-medium"]
CLIP_FRAMES = 40
"""Long enough for the stereo EKF to lose its target (frame 28 of case1-medium), so that there are pictures to compare."""


@pytest.fixture(scope="module")
def selection(tmp_path_factory: pytest.TempPathFactory) -> list[str]:
    """The run's options: three trackers, two seeds, and a clip file of each sequence of :data:`SEQUENCES`."""
    registry = load_registry()
    folder = tmp_path_factory.mktemp("clips")
    clips = [
        export_sequence(Clip(registry.sequence(name), CLIP_FRAMES), folder, registry.modalities) for name in SEQUENCES
    ]
    return [*TRACKERS, *(word for clip in clips for word in ("--dataset", str(clip))), "--seeds", "2"]


@pytest.fixture(scope="module")
def cluster() -> Iterator[distributed.LocalCluster]:
    """A scheduler and a single-threaded worker process on localhost (a second would cost its start, prove no more)."""
    with distributed.LocalCluster(
        n_workers=1, threads_per_worker=1, processes=True, dashboard_address=None, silence_logs=logging.ERROR
    ) as running:
        yield running


def board(out: Path) -> pd.DataFrame:
    table = pd.read_csv(out / "leaderboard.csv")
    columns = [column for column in table.columns if column not in SPEED_COLUMNS]
    return table[columns].sort_values(["modality", "tracker", "dataset"]).reset_index(drop=True)


def pictures(out: Path) -> dict[tuple[str, str, int], list[Picture]]:
    """The pictures of failed frames of a run's cells, by tracker, dataset and seed."""
    with ResultStore(out / DATABASE_NAME) as store:
        cells = store.cells()
        found = store.pictures(cells["id"])
    return {(row.tracker, row.dataset, int(row.seed)): found.get(int(row.id), []) for row in cells.itertuples()}


def test_a_dask_cluster_gives_the_local_board_value_for_value(  # type: ignore[no-untyped-def]
    cluster, selection: list[str], tmp_path: Path
) -> None:
    runner = CliRunner()
    # One local worker: compiled kernels are compiled once and cached, and the cluster's workers load them.
    local = runner.invoke(main, ["run", *selection, "--jobs", "1", "--out", str(tmp_path / "local")])
    assert local.exit_code == 0, local.output
    remote = runner.invoke(
        main,
        ["run", *selection, "--executor", "dask", "--scheduler", cluster.scheduler_address]
        + ["--out", str(tmp_path / "dask")],
    )
    assert remote.exit_code == 0, remote.output
    assert "6 cells (6 ok)" in remote.stderr
    mine, theirs = board(tmp_path / "local"), board(tmp_path / "dask")
    assert len(mine) >= 3 and {"camera", "sonar", "stereo"} <= set(mine["modality"])
    pd.testing.assert_frame_equal(mine, theirs)
    local_pictures = pictures(tmp_path / "local")
    assert any(local_pictures.values()) and pictures(tmp_path / "dask") == local_pictures


@pytest.mark.parametrize("address", ["tcp://127.0.0.1:9", "not a url"])
def test_a_scheduler_that_cannot_be_reached_is_a_usage_error(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, address: str
) -> None:
    monkeypatch.setattr("benchmark.executors.dask_cluster.CONNECT_TIMEOUT_S", 1.0)
    result = CliRunner().invoke(
        main,
        ["run", "--tracker", "hough", "--dataset", "camera/S6", "--executor", "dask"]
        + ["--scheduler", address, "--out", str(tmp_path)],
    )
    assert result.exit_code == 2
    assert f"Error: --scheduler {address}: cannot reach the Dask scheduler" in result.output


def test_options_the_executor_does_not_take_are_refused(tmp_path: Path) -> None:
    runner = CliRunner()
    base = ["run", "--tracker", "hough", "--dataset", "camera/S6", "--out", str(tmp_path)]
    scheduler_alone = runner.invoke(main, [*base, "--scheduler", "tcp://127.0.0.1:9"])
    assert scheduler_alone.exit_code == 2 and "--scheduler needs --executor dask" in scheduler_alone.output
    in_process = runner.invoke(main, [*base, "--executor", "dask", "--in-process"])
    assert in_process.exit_code == 2 and "does not go with --executor dask" in in_process.output


def test_a_worker_keeps_a_model_it_is_sent_in_a_folder_only_its_user_may_write(tmp_path: Path) -> None:
    from benchmark.executors.dask_cluster import _adopt_model
    from benchmark.selection import Selection, select_cells
    from benchmark.training import Training

    from ..test_training import registry_with_training

    registry = registry_with_training()
    [cell, *_] = select_cells(registry, Selection(trackers=("learner",)))
    unseen = tmp_path / "results-folder-of-another-machine" / "learner-0123.model"
    cell = dataclasses.replace(cell, training=dataclasses.replace(cell.training, sequences=(), model_path=unseen))
    model = b"the model's record"
    adopted = _adopt_model(cell, model)
    path = adopted.training.model_path
    assert isinstance(adopted.training, Training) and path.read_bytes() == model and path.suffix == ".model"
    assert path.parent.name.startswith("trackbench-models-") and path.parent.stat().st_mode & 0o777 == 0o700
    assert _adopt_model(cell, model).training.model_path == path  # one file per model and worker
