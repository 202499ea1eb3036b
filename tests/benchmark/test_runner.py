"""Tests of benchmark.runner: cells run, score, fail and time out in isolation."""

from __future__ import annotations

import dataclasses
import math
import pickle
import time
import types
from collections.abc import Callable, Iterator
from typing import Any

import cv2
import numpy as np
import pandas as pd
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from benchmark.identity import DatasetIdentity, digest
from benchmark.modalities.camera.modality import CAMERA
from benchmark.modalities.camera.model import CameraTruth
from benchmark.modalities.sonar.model import SonarTruth
from benchmark.model import Frame, Outcome, Sequence, SequenceInfo
from benchmark.registry import Registry
from benchmark.results import CellResult, Picture
from benchmark.executors import run_cells
from benchmark.runner import MAX_PICTURES, Cell, cell_result, cell_rng, run_cell

MakeCell = Callable[..., Cell]


@pytest.fixture
def make_cell(fakes: types.ModuleType, fake_registry: Registry) -> MakeCell:
    """Build a cell of a fake tracker (with parameter overrides) on a fake sequence."""

    def make(tracker: str, sequence: object = None, seed: int = 0, init: str = "truth", **params: object) -> Cell:
        entry = fake_registry.trackers[tracker]
        if params:
            entry = entry.with_params(params)
        return fakes.make_cell(entry, sequence or fakes.FakeSequence(), seed, init)

    return make


def without_timing(result: CellResult) -> pd.DataFrame:
    return result.frames.drop(columns=["step_ms", "wall_ms"])


def test_perfect_tracker_scores_every_frame_correct(make_cell: MakeCell, fake_registry: Registry) -> None:
    result = run_cell(make_cell("perfect"))
    summary = result.summary()
    assert result.status == "ok" and result.message == ""
    assert [s.index for s in result.scores] == list(range(10))
    assert summary["correct_pct"] == 100.0
    assert summary["correct_pct"] + summary["false_pct"] + summary["missed_pct"] == pytest.approx(100.0)
    assert summary["rmse_d_px"] == 0.0
    assert (result.tracker, result.dataset, result.modality) == ("perfect", "fake/S1", "camera")
    assert result.tracker_key == fake_registry.trackers["perfect"].cache_key


def test_blind_tracker_misses_every_frame(make_cell: MakeCell) -> None:
    assert run_cell(make_cell("blind")).summary()["missed_pct"] == 100.0


@settings(max_examples=15, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), sigma=st.floats(0.0, 20.0))
def test_rates_of_any_run_sum_to_100(fakes: types.ModuleType, seed: int, sigma: float) -> None:
    entry = fakes.make_registry().trackers["noisy"].with_params({"sigma_px": sigma})
    summary = run_cell(fakes.make_cell(entry, fakes.FakeSequence(), seed)).summary()
    assert summary["frames"] == 10
    assert summary["correct_pct"] + summary["false_pct"] + summary["missed_pct"] == pytest.approx(100.0)


def test_reset_gets_the_whole_first_truth_or_none(
    make_cell: MakeCell, fakes: types.ModuleType, monkeypatch: pytest.MonkeyPatch
) -> None:
    seen: list[object] = []
    original = fakes.Perfect.reset

    def spy(self, info, rng, init=None):  # noqa: ANN001, ANN202
        seen.append(init)
        return original(self, info, rng, init)

    monkeypatch.setattr(fakes.Perfect, "reset", spy)
    run_cell(make_cell("perfect"))
    run_cell(make_cell("perfect", init="none"))
    assert isinstance(seen[0], CameraTruth) and seen[0] == fakes.truth_at(0)
    assert seen[1] is None


def test_raising_tracker_becomes_an_error_row_keeping_earlier_frames(make_cell: MakeCell) -> None:
    result = run_cell(make_cell("raising", fail_at=4))
    assert result.status == "error"
    assert result.message.startswith("RuntimeError: lost the cable")
    assert result.message.endswith("(frame 4)")
    assert [s.index for s in result.scores] == [0, 1, 2, 3]
    assert "lost the cable" in result.detail and "Traceback" in result.detail


@pytest.mark.parametrize(("kind", "returned"), [("string", "'a cable, probably'"), ("nan", "non-finite")])
def test_garbage_estimate_becomes_an_error_naming_tracker_frame_and_value(
    make_cell: MakeCell, kind: str, returned: str
) -> None:
    result = run_cell(make_cell("garbage", kind=kind, at=2))
    assert result.status == "error"
    assert result.message.startswith("EstimateError")
    assert "'garbage'" in result.message and result.message.endswith("(frame 2)") and returned in result.message
    assert len(result.scores) == 2


def test_corrupt_frame_becomes_an_error_naming_the_frame(make_cell: MakeCell, fakes: types.ModuleType) -> None:
    result = run_cell(make_cell("perfect", fakes.FakeSequence(corrupt_at=5)))
    assert result.status == "error"
    assert result.message.startswith("DataError: fake/S1: frame 5 is corrupt")
    assert result.message.endswith("(reading frame 5)")
    assert len(result.scores) == 5


def test_empty_sequence_is_an_error(make_cell: MakeCell, fakes: types.ModuleType) -> None:
    result = run_cell(make_cell("perfect", fakes.FakeSequence(n_frames=0)))
    assert result.status == "error" and "no frames" in result.message


def test_same_seed_replays_bit_for_bit_and_other_seeds_differ(make_cell: MakeCell) -> None:
    first = run_cell(make_cell("noisy", seed=7))
    again = run_cell(make_cell("noisy", seed=7))
    other = run_cell(make_cell("noisy", seed=8))
    pd.testing.assert_frame_equal(without_timing(first), without_timing(again))
    assert not without_timing(first).equals(without_timing(other))


def test_an_observer_sees_every_scored_frame_and_changes_nothing(make_cell: MakeCell) -> None:
    seen: list[tuple[int, Any, Any]] = []

    def observe(tracker: Any, frame: Frame, estimate: Any, score: Any) -> None:
        assert score.index == frame.index
        seen.append((frame.index, estimate, score))

    plain = run_cell(make_cell("noisy", seed=3))
    observed = run_cell(make_cell("noisy", seed=3), observer=observe)
    pd.testing.assert_frame_equal(without_timing(plain), without_timing(observed))
    assert [index for index, _, _ in seen] == list(range(10))
    assert tuple(score for _, _, score in seen) == observed.scores


def test_until_stops_before_its_frame_and_an_observer_that_raises_ends_the_cell(make_cell: MakeCell) -> None:
    cut = run_cell(make_cell("noisy", seed=3), until=4)
    whole = run_cell(make_cell("noisy", seed=3))
    assert cut.status == "ok" and [s.index for s in cut.scores] == [0, 1, 2, 3]
    pd.testing.assert_frame_equal(without_timing(cut), without_timing(whole).iloc[:4])

    def observe(tracker: Any, frame: Frame, estimate: Any, score: Any) -> None:
        if frame.index == 2:
            raise OSError("disk full")

    failed = run_cell(make_cell("noisy", seed=3), observer=observe)
    assert failed.status == "error" and len(failed.scores) == 3
    assert failed.message == "OSError: disk full (observing frame 2)"


def test_cell_generators_are_independent_per_seed_tracker_and_dataset_fingerprint() -> None:
    def identity(fingerprint: str, name: str = "x") -> DatasetIdentity:
        return DatasetIdentity(name, "camera", "here", digest(fingerprint))

    keys = [(0, "a", "x"), (0, "b", "x"), (0, "a", "y"), (1, "a", "x")]
    draws = {key: tuple(cell_rng(key[0], key[1], identity(key[2])).random(4)) for key in keys}
    assert len(set(draws.values())) == len(keys)
    assert tuple(cell_rng(0, "a", identity("x")).random(4)) == draws[(0, "a", "x")]
    renamed = identity("x", name="../elsewhere/x")
    assert tuple(cell_rng(0, "a", renamed).random(4)) == draws[(0, "a", "x")]


def test_inline_timeout_is_checked_between_frames_and_keeps_frames(make_cell: MakeCell) -> None:
    result = run_cell(make_cell("sleepy", from_frame=0, sleep_s=0.05), timeout_s=0.01)
    assert result.status == "timeout"
    assert "0.01 s" in result.message
    assert len(result.scores) == 1


def test_inline_run_keeps_input_order_and_finishes_after_failures(make_cell: MakeCell) -> None:
    cells = [make_cell("raising"), make_cell("perfect"), make_cell("garbage")]
    results = list(run_cells(cells, in_process=True))
    assert [r.tracker for r in results] == ["raising", "perfect", "garbage"]
    assert [r.status for r in results] == ["error", "ok", "error"]


def test_cell_rejects_an_unknown_init_mode(make_cell: MakeCell) -> None:
    with pytest.raises(ValueError, match="init"):
        make_cell("perfect", init="guess")


def test_cell_rejects_a_modality_its_tracker_does_not_read(fake_registry: Registry, fakes: types.ModuleType) -> None:
    with pytest.raises(ValueError, match="tracker 'perfect' reads camera frames, not sonar frames"):
        Cell(fake_registry.trackers["perfect"], fakes.FakeSequence(), 0, modality=fake_registry.modalities["sonar"])


def test_pool_isolates_a_hanging_and_a_raising_tracker(make_cell: MakeCell) -> None:
    cells = [
        make_cell("sleepy", from_frame=1, sleep_s=60.0),
        make_cell("raising", fail_at=2),
        make_cell("perfect"),
        make_cell("noisy", seed=3),
    ]
    results = {r.tracker: r for r in run_cells(cells, jobs=2, timeout_s=1.0)}
    assert results["sleepy"].status == "timeout" and "1 s" in results["sleepy"].message
    assert results["raising"].status == "error" and results["raising"].message.endswith("(frame 2)")
    assert len(results["raising"].scores) == 2
    assert results["perfect"].status == "ok" and results["perfect"].summary()["correct_pct"] == 100.0
    inline = run_cell(make_cell("noisy", seed=3))
    pd.testing.assert_frame_equal(without_timing(results["noisy"]), without_timing(inline))
    assert results["noisy"].pictures == inline.pictures and len(inline.pictures) >= 2


# ---------------------------------------------------------------- frames are checked against the cell's modality
@dataclasses.dataclass(frozen=True)
class Altered(Sequence):
    """Another sequence with one frame's observation or truth replaced."""

    inner: Sequence
    at: int
    changes: tuple[tuple[str, Any], ...]

    @property
    def info(self) -> SequenceInfo:
        return self.inner.info

    def frames(self) -> Iterator[Frame]:
        for frame in self.inner.frames():
            yield dataclasses.replace(frame, **dict(self.changes)) if frame.index == self.at else frame


def test_a_frame_not_of_the_modality_s_types_is_a_data_error_naming_it(
    make_cell: MakeCell, fakes: types.ModuleType
) -> None:
    sequence = Altered(fakes.FakeSequence(), 3, (("observation", "not an image"),))
    result = run_cell(make_cell("perfect", sequence))
    assert result.status == "error"
    assert result.message.startswith("DataError: sequence 'fake/S1', frame 3: the observation is a str")
    assert "camera" in result.message and result.message.endswith("(reading frame 3)")
    assert [score.index for score in result.scores] == [0, 1, 2]


def test_a_first_frame_with_a_truth_of_another_modality_fails_before_reset(
    make_cell: MakeCell, fakes: types.ModuleType, monkeypatch: pytest.MonkeyPatch
) -> None:
    resets: list[object] = []
    monkeypatch.setattr(fakes.Perfect, "reset", lambda self, info, rng, init=None: resets.append(init))
    truth = SonarTruth(across_m=1.0, depth_m=20.0, burial=0.0, resolution_m=0.2)
    result = run_cell(make_cell("perfect", Altered(fakes.FakeSequence(), 0, (("truth", truth),))))
    assert result.status == "error" and result.scores == () and resets == []
    assert result.message.startswith("DataError: sequence 'fake/S1', frame 0: the truth is a SonarTruth, not a Camera")
    assert result.message.endswith("(reading frame 0)")


class Distance:
    """A camera scorer of one column: any estimate is correct, its error the true d."""

    error_columns = ("err_true_d_px",)

    def check(self, estimate: Any) -> None:
        pass

    def score(self, estimate: Any, truth: Any, info: SequenceInfo) -> tuple[Outcome | None, tuple[float, ...]]:
        return (Outcome.CORRECT if estimate is not None else Outcome.MISSED), (truth.cable.d,)


def test_the_cell_s_modality_scores_its_frames(fake_registry: Registry, fakes: types.ModuleType) -> None:
    modality = dataclasses.replace(CAMERA, scorer=Distance())
    cell = Cell(fake_registry.trackers["perfect"], fakes.FakeSequence(n_frames=3), 0, modality=modality)
    result = run_cell(cell)
    assert result.status == "ok" and result.error_columns == ("err_true_d_px",)
    assert result.frames["err_true_d_px"].tolist() == [fakes.truth_at(i).cable.d for i in range(3)]
    assert "rmse_true_d_px" in result.summary() and "rmse_d_px" not in result.summary()


def test_a_cell_needs_its_modality_by_keyword(fake_registry: Registry, fakes: types.ModuleType) -> None:
    entry = fake_registry.trackers["perfect"]
    with pytest.raises(TypeError, match="modality"):
        Cell(entry, fakes.FakeSequence(), 0)  # type: ignore[call-arg]
    with pytest.raises(TypeError):
        Cell(entry, fakes.FakeSequence(), 0, "truth", CAMERA)  # type: ignore[misc]


# ---------------------------------------------------------------- pictures of failed frames
class Scripted:
    """A camera scorer whose outcomes follow a script, a letter a frame: correct, false, missed, or ``-`` unscored."""

    error_columns = ("err_d_px",)
    LETTERS = {"c": Outcome.CORRECT, "f": Outcome.FALSE, "m": Outcome.MISSED, "-": None}

    def __init__(self, script: str) -> None:
        self.script = script

    def check(self, estimate: Any) -> None:
        pass

    def score(self, estimate: Any, truth: Any, info: SequenceInfo) -> tuple[Outcome | None, tuple[float, ...]]:
        index = round((truth.cable.d + 6.0) / 1.5)  # the fake sequence's truth_at(index)
        return self.LETTERS[self.script[index]], (float(index),)


class Recorder:
    """A drawer that notes what it drew and draws a 2 x 3 picture of the frame's index."""

    def __init__(self) -> None:
        self.calls: list[tuple[int, Any]] = []

    def __call__(self, frame: Frame, estimate: Any) -> np.ndarray:
        self.calls.append((frame.index, estimate))
        return np.full((2, 3, 3), frame.index, dtype=np.uint8)


def scripted_cell(fake_registry: Registry, fakes: types.ModuleType, script: str, draw: Any) -> Cell:
    modality = dataclasses.replace(CAMERA, scorer=Scripted(script), draw=draw)
    return Cell(fake_registry.trackers["perfect"], fakes.FakeSequence(n_frames=len(script)), 0, modality=modality)


def decoded(picture: Picture) -> np.ndarray:
    return cv2.imdecode(np.frombuffer(picture.png, np.uint8), cv2.IMREAD_UNCHANGED)


def test_pictures_are_kept_of_the_first_frame_of_each_run_of_failures(
    fake_registry: Registry, fakes: types.ModuleType
) -> None:
    drawer = Recorder()
    result = run_cell(scripted_cell(fake_registry, fakes, "cffmm-ffcmfc", drawer))
    assert result.status == "ok"
    assert [(p.frame, p.outcome) for p in result.pictures] == [
        (1, "false"), (3, "missed"), (6, "false"), (9, "missed"), (10, "false")
    ]
    assert drawer.calls == [(index, fakes.truth_at(index).cable) for index in (1, 3, 6, 9, 10)]
    for picture in result.pictures:
        assert decoded(picture).shape == (2, 3, 3) and (decoded(picture) == picture.frame).all()


def test_a_cell_keeps_at_most_six_pictures_and_draws_no_more(fake_registry: Registry, fakes: types.ModuleType) -> None:
    drawer = Recorder()
    result = run_cell(scripted_cell(fake_registry, fakes, "fm" * 5 + "c" + "f" * 3, drawer))
    assert MAX_PICTURES == 6
    assert [p.frame for p in result.pictures] == [0, 1, 2, 3, 4, 5]
    assert [index for index, _ in drawer.calls] == [0, 1, 2, 3, 4, 5]


def test_a_cell_without_failures_or_without_a_drawer_keeps_no_pictures(
    fake_registry: Registry, fakes: types.ModuleType
) -> None:
    drawer = Recorder()
    assert run_cell(scripted_cell(fake_registry, fakes, "cc-cc", drawer)).pictures == () and drawer.calls == []
    assert run_cell(scripted_cell(fake_registry, fakes, "ffmm", None)).pictures == ()


def not_a_picture(frame: Frame, estimate: Any) -> Any:
    """A string at frame 1, a float picture at frame 6, else a good picture."""
    return {1: "a picture", 6: np.zeros((2, 2, 3))}.get(frame.index, np.zeros((2, 2, 3), np.uint8))


@pytest.mark.parametrize(
    "failure",
    [RuntimeError("no ink"), SystemExit(3), KeyboardInterrupt(), MemoryError()],
    ids=lambda failure: type(failure).__name__,
)
def test_a_drawer_that_fails_costs_only_its_picture(
    fake_registry: Registry, fakes: types.ModuleType, failure: BaseException
) -> None:
    script = "cffmm-ffcmfc"

    def broken(frame: Frame, estimate: Any) -> np.ndarray:
        if frame.index == 3:
            raise failure
        return not_a_picture(frame, estimate)

    plain = run_cell(scripted_cell(fake_registry, fakes, script, None))
    result = run_cell(scripted_cell(fake_registry, fakes, script, broken))
    assert (result.status, result.message, result.detail) == ("ok", "", "")
    pd.testing.assert_frame_equal(without_timing(result), without_timing(plain))
    assert [p.frame for p in result.pictures] == [9, 10]


def test_drawing_is_not_timed_as_the_tracker_s_step(fake_registry: Registry, fakes: types.ModuleType) -> None:
    def slow(frame: Frame, estimate: Any) -> np.ndarray:
        time.sleep(0.2)
        return np.zeros((2, 2, 3), np.uint8)

    result = run_cell(scripted_cell(fake_registry, fakes, "cfc", slow))
    assert [p.frame for p in result.pictures] == [1]
    assert result.scores[1].step_s < 0.1 <= 0.2 <= result.elapsed_s


def test_the_built_in_camera_drawer_pictures_a_blind_tracker_s_first_miss(
    make_cell: MakeCell, fakes: types.ModuleType
) -> None:
    (picture,) = run_cell(make_cell("blind")).pictures
    assert (picture.frame, picture.outcome) == (0, "missed")
    image = decoded(picture)
    assert image.shape == (fakes.HEIGHT, fakes.WIDTH, 3) and image.dtype == np.uint8
    assert np.all(image == (0, 255, 0), axis=2).any()  # the true borders


def test_a_result_with_pictures_pickles(make_cell: MakeCell) -> None:
    result = run_cell(make_cell("noisy", seed=3))
    assert result.pictures
    again = pickle.loads(pickle.dumps(result))
    assert again.pictures == result.pictures and isinstance(again.pictures[0], Picture)


# ---------------------------------------------------------------- cell_result
def test_a_cell_result_carries_the_cell_s_identity_and_its_modality_s_columns(
    make_cell: MakeCell, fake_registry: Registry
) -> None:
    cell = make_cell("raising", seed=4, init="none", fail_at=2)
    result = cell_result(cell, "timeout", "too slow", elapsed_s=1.5)
    assert (result.tracker, result.dataset, result.modality, result.seed, result.init) == (
        "raising", "fake/S1", "camera", 4, "none"
    )
    assert result.tracker_key == cell.tracker.cache_key != fake_registry.trackers["raising"].cache_key
    assert result.params == {"fail_at": 2} and result.key == cell.key
    assert (result.status, result.message, result.scores, result.elapsed_s, result.detail) == (
        "timeout", "too slow", (), 1.5, ""
    )
    assert result.error_columns == CAMERA.error_columns


class Unreadable(Sequence):
    @property
    def info(self) -> SequenceInfo:
        raise OSError("disk gone")

    def frames(self) -> Iterator[Frame]:
        return iter(())

    def __repr__(self) -> str:
        return "<Unreadable>"


def test_a_cell_whose_sequence_cannot_describe_itself_still_gets_a_result(fake_registry: Registry) -> None:
    cell = Cell(fake_registry.trackers["perfect"], Unreadable(), 0, modality=CAMERA)
    result = run_cell(cell)
    assert (result.status, result.dataset, result.modality) == ("error", "<Unreadable>", "camera")
    assert result.message == "OSError: disk gone (reading the sequence's info)"
    assert math.isnan(result.summary()["correct_pct"])
