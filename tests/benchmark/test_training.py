"""Training the trackers that learn: the split, the one fit per run, the stored model, the error rows."""

from __future__ import annotations

import dataclasses
import pickle
import types
from collections.abc import Iterator
from pathlib import Path
from typing import Any, ClassVar

import numpy as np
import pytest

from benchmark import storage
from benchmark.harness import run_benchmark
from benchmark.model import Frame, Sequence
from benchmark.registry import Registry
from benchmark.selection import Selection, SelectionError, select_cells
from benchmark.training import Training, learns

from .conftest import ORIGIN, FakeSequence, Perfect, make_registry


@dataclasses.dataclass(frozen=True)
class SpySequence(FakeSequence):
    """A fake sequence that notes every frame read from it (in this process)."""

    reads: ClassVar[list[tuple[str, int]]] = []

    def frames(self) -> Iterator[Frame]:
        for frame in super().frames():
            type(self).reads.append((self.name, frame.index))
            yield frame


class Learner(Perfect):
    """Learns the mean grey level of its training frames; without a model it cannot step."""

    name = "learner"
    fits: ClassVar[list[list[str]]] = []

    def fit(self, training: list[Sequence], rng: np.random.Generator) -> dict[str, Any]:
        seen = [sequence.identity.name for sequence in training]
        type(self).fits.append(seen)
        levels = [float(np.mean(frame.observation)) for sequence in training for frame in sequence.frames()]
        self.model = {"level": float(np.mean(levels)), "draw": float(rng.random()), "seen": seen}
        return self.model

    def use_model(self, model: dict[str, Any]) -> None:
        self.model = model

    def step(self, frame: Frame) -> Any:
        if getattr(self, "model", None) is None:
            raise RuntimeError("learner: no model")
        return frame.truth.cable


class Failing(Learner):
    """A learner whose fit always fails."""

    name = "failing"

    def fit(self, training: list[Sequence], rng: np.random.Generator) -> dict[str, Any]:
        raise ValueError("no cable in any training frame")


TRAINING = ("train/T1", "train/T2")


def registry_with_training(training: str | None = "train") -> Registry:
    """The fake registry plus the learners, a training split ``train`` named by the suite ``fake``."""
    registry = make_registry((Perfect, Learner, Failing))
    scored = registry.suites.pop("fake")
    with registry.acting_for(ORIGIN):
        registry.add_suite("fake", scored.sequences, training=training)
        registry.add_suite("train", [SpySequence(name, 5) for name in TRAINING], scored=False)
    return registry


@pytest.fixture(autouse=True)
def fresh_spies() -> Iterator[None]:
    Learner.fits.clear()
    SpySequence.reads.clear()
    yield
    Learner.fits.clear()
    SpySequence.reads.clear()


def board(summary: Any) -> Any:
    table = summary.publication.boards["camera"]
    return table[table["dataset"] == "(all)"].set_index("tracker")


def test_a_learner_is_fitted_once_on_the_split_and_never_sees_a_scored_frame(tmp_path: Path) -> None:
    registry = registry_with_training()
    cells = select_cells(registry, Selection(trackers=("perfect", "learner"), seeds=2))
    assert {cell.dataset for cell in cells} == {"fake/S1", "fake/S2"}  # the split is not scored
    assert [learns(entry) for entry in registry.trackers.values()] == [False, True, True]
    lines: list[str] = []
    summary = run_benchmark(cells, registry.modalities, tmp_path, in_process=True, log=lines.append)
    assert summary.clean
    assert Learner.fits == [list(TRAINING)]
    # Every read of the training sequences is the one fit's; no cell read them, the fit read nothing else.
    assert sorted(SpySequence.reads) == [(name, k) for name in TRAINING for k in range(5)]
    rows = board(summary)
    assert rows.loc["learner", "training"] == "train" and rows.loc["perfect", "training"] == ""
    assert rows.loc["learner", "correct_pct"] == 100.0
    assert any(line.startswith("training: learner on train (2 sequences): fitted in") for line in lines)
    assert len(list((tmp_path / "models").glob("learner-*.model"))) == 1


def test_the_stored_model_serves_resume_and_the_next_run_without_refitting(tmp_path: Path) -> None:
    registry = registry_with_training()
    first = select_cells(registry, Selection(trackers=("learner",)))
    run_benchmark(first, registry.modalities, tmp_path, in_process=True)
    more = select_cells(registry, Selection(trackers=("learner",), seeds=3))
    lines: list[str] = []
    summary = run_benchmark(more, registry.modalities, tmp_path, in_process=True, resume=True, log=lines.append)
    assert summary.clean and summary.statuses["ok"] == 6
    assert len(Learner.fits) == 1
    assert any("reusing" in line for line in lines)


class Planted:
    """What a pickle planted as a model would run: it leaves a mark."""

    def __init__(self, mark: Path) -> None:
        self.mark = mark

    def __reduce__(self):  # type: ignore[no-untyped-def]
        return (Path.write_text, (self.mark, "code ran"))


@pytest.mark.parametrize(
    ("spoil", "says"),
    [
        (lambda path, mark: path.write_bytes(path.read_bytes()[:-3] + b"xyz"), "fails its checksum"),
        (lambda path, mark: path.write_bytes(pickle.dumps(Planted(mark))), "not a trackbench record"),
        (lambda path, mark: path.write_bytes(storage.dumps({"key": "0" * 16, "model": {}}, frozenset())), "not the model"),
    ],
    ids=["damaged", "planted pickle", "another training's"],
)
def test_a_stored_model_that_fails_its_checks_is_fitted_again_and_runs_nothing(tmp_path: Path, spoil: Any, says: str) -> None:
    registry = registry_with_training()
    cells = select_cells(registry, Selection(trackers=("learner",)))
    run_benchmark(cells, registry.modalities, tmp_path / "out", in_process=True)
    [path] = (tmp_path / "out" / "models").glob("learner-*.model")
    spoil(path, tmp_path / "mark")
    lines: list[str] = []
    summary = run_benchmark(cells, registry.modalities, tmp_path / "out", in_process=True, log=lines.append)
    assert summary.clean and len(Learner.fits) == 2 and not (tmp_path / "mark").exists()
    assert any(says in line and "fitting it again" in line and path.name in line for line in lines), lines


class Unstorable(Learner):
    """A learner whose model holds an object a record cannot."""

    name = "unstorable"

    def fit(self, training: list[Sequence], rng: np.random.Generator) -> Any:
        return {"level": object()}


def test_a_model_a_record_cannot_hold_makes_error_rows_that_say_what(tmp_path: Path) -> None:
    registry = make_registry((Unstorable,))
    scored = registry.suites.pop("fake")
    with registry.acting_for(ORIGIN):
        registry.add_suite("fake", scored.sequences, training="train")
        registry.add_suite("train", [SpySequence(name, 5) for name in TRAINING], scored=False)
    lines: list[str] = []
    summary = run_benchmark(select_cells(registry, Selection()), registry.modalities, tmp_path, in_process=True, log=lines.append)
    assert board(summary).loc["unstorable", "status"].startswith(
        "error (2/2 cells): TrainingError: training on train failed: StorageError: cannot store a builtins.object"
    )
    assert not (tmp_path / "models").exists() or not list((tmp_path / "models").iterdir())


def test_the_training_set_is_part_of_a_cell_s_identity(tmp_path: Path) -> None:
    registry = registry_with_training()
    by_suite = select_cells(registry, Selection(trackers=("learner",), suites=("fake",)))
    by_sequence = select_cells(registry, Selection(trackers=("learner",), suites=("fake",), train=("train/T1",)))
    assert {cell.training.name for cell in by_sequence} == {"train/T1"}
    assert {cell.key for cell in by_suite}.isdisjoint({cell.key for cell in by_sequence})
    summary = run_benchmark(by_sequence, registry.modalities, tmp_path, in_process=True)
    assert Learner.fits == [["train/T1"]] and board(summary).loc["learner", "training"] == "train/T1"


def test_a_training_set_holding_a_scored_sequence_is_refused_and_its_cells_are_error_rows(tmp_path: Path) -> None:
    registry = registry_with_training()
    cells = select_cells(registry, Selection(trackers=("perfect", "learner"), suites=("fake",), train=("fake/S2",)))
    summary = run_benchmark(cells, registry.modalities, tmp_path, in_process=True)
    assert Learner.fits == [] and SpySequence.reads == []
    rows = board(summary)
    assert rows.loc["perfect", "status"] == "ok"
    status = rows.loc["learner", "status"]
    assert status.startswith("error (2/2 cells): TrainingError: training set 'fake/S2' holds sequence(s) this run")
    assert "fake/S2" in status and "(adopting the model trained on fake/S2)" in status


def test_a_fit_that_fails_in_its_worker_makes_error_rows_naming_the_training_set(tmp_path: Path) -> None:
    registry = registry_with_training()
    cells = select_cells(registry, Selection(trackers=("perfect", "failing"), suites=("fake",)))
    lines: list[str] = []
    summary = run_benchmark(cells, registry.modalities, tmp_path, jobs=1, log=lines.append)
    rows = board(summary)
    assert rows.loc["perfect", "status"] == "ok"
    assert rows.loc["failing", "status"].startswith(
        "error (2/2 cells): TrainingError: training on train failed: ValueError: no cable in any training frame"
    )
    assert sum("failed" in line for line in lines if line.startswith("training:")) == 1
    assert not (tmp_path / "models").exists() or not list((tmp_path / "models").iterdir())


def test_a_learner_without_a_training_set_is_an_error_row_that_says_how_to_give_one(tmp_path: Path) -> None:
    registry = registry_with_training(training=None)
    cells = select_cells(registry, Selection(trackers=("learner",), suites=("fake",)))
    assert all(isinstance(cell.training, Training) and cell.training.error for cell in cells)
    summary = run_benchmark(cells, registry.modalities, tmp_path, in_process=True)
    assert "suite 'fake' names no training suite; give one with --train" in board(summary).loc["learner", "status"]


def test_a_train_word_that_names_nothing_is_a_selection_error(fakes: types.ModuleType) -> None:
    registry = registry_with_training()
    with pytest.raises(SelectionError, match="unknown dataset 'nowhere'"):
        select_cells(registry, Selection(trackers=("learner",), train=("nowhere",)))


def test_a_split_is_scored_when_a_run_names_it() -> None:
    registry = registry_with_training()
    cells = select_cells(registry, Selection(trackers=("perfect",), suites=("train",)))
    assert {cell.dataset for cell in cells} == set(TRAINING)


def test_the_command_line_trains_on_what_train_names_and_the_board_says_so(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path
) -> None:
    import pandas as pd
    from click.testing import CliRunner

    import benchmark.plugins
    from benchmark.cli import main

    monkeypatch.setattr(benchmark.plugins, "load_registry", lambda disable=(), strict=False: registry_with_training())
    out = tmp_path / "out"
    args = ["run", "--tracker", "learner", "--train", "train/T2", "--train", "train", "--in-process", "--out", str(out)]
    result = CliRunner().invoke(main, args)
    assert result.exit_code == 0, result.output
    assert Learner.fits == [["train/T1", "train/T2"]]  # suites first, each sequence once
    rows = pd.read_csv(out / "leaderboard.csv", keep_default_na=False)
    assert set(rows["training"]) == {"train/T2, train"}
    listing = CliRunner().invoke(main, ["datasets"]).stdout
    assert "fake  from fake-trackers 9.9 (plugin fakes)  [trains on train]" in listing
    assert "train  from fake-trackers 9.9 (plugin fakes)  [training split, not scored unless named]" in listing


def test_an_edit_of_the_tracker_s_code_fits_again_with_the_same_generator(monkeypatch: pytest.MonkeyPatch) -> None:
    registry = registry_with_training()
    entry, sequences = registry.trackers["learner"], registry.suites["train"].sequences
    before = Training.plan(entry, "train", sequences)
    monkeypatch.setattr("benchmark.registry.code_digest", lambda module: "edited")
    after = Training.plan(entry, "train", sequences)
    assert after.key != before.key and after.seed == before.seed
