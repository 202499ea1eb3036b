"""The likelihood ceiling: a window of states around the truth, scored by the tracker's own model."""

from __future__ import annotations

import dataclasses
import math
import types
from collections.abc import Iterator
from typing import Any

import numpy as np
import pytest

from benchmark.modalities.camera.diagnostics import CeilingWindow, likelihood_ceiling
from benchmark.modalities.camera.model import UNKNOWN_CABLE, CableState, CameraTruth
from benchmark.model import Frame, Sequence, SequenceInfo
from benchmark.tracker import ScoresStates

TRUTH = CableState(d=4.0, alpha=0.1, w=20.0, beta=0.02)


class Peaked:
    """Scores states by their closeness to the true state shifted by ``offset``; records its calls."""

    name = "peaked"

    def __init__(self, offset: tuple[float, float, float, float] = (0.0, 0.0, 0.0, 0.0), nan: bool = False) -> None:
        self.offset = np.array(offset)
        self.nan = nan
        self.resets: list[tuple[SequenceInfo, float, Any]] = []
        self.calls: list[tuple[int, tuple[int, ...]]] = []

    def reset(self, info: SequenceInfo, rng: np.random.Generator, init: Any = None) -> None:
        self.resets.append((info, rng.random(), init))

    def score_states(self, frame: Frame, states: np.ndarray) -> np.ndarray:
        self.calls.append((frame.index, states.shape))
        peak = frame.truth.cable.as_array() + self.offset
        scores = -np.abs(states - peak) @ np.array([1.0, 100.0, 1.0, 100.0])
        return np.full_like(scores, math.nan) if self.nan else scores


@dataclasses.dataclass(frozen=True)
class PartlyLabelled(Sequence):
    """Frames of the fake sequence; odd frames unlabelled (unknown cable), frame 4 without truth."""

    base: Sequence
    modality: str = "camera"

    @property
    def info(self) -> SequenceInfo:
        return dataclasses.replace(self.base.info, modality=self.modality)

    def frames(self) -> Iterator[Frame]:
        for frame in self.base.frames():
            if frame.index % 2:
                frame = dataclasses.replace(frame, truth=CameraTruth(UNKNOWN_CABLE))
            elif frame.index == 4:
                frame = dataclasses.replace(frame, truth=None)
            yield frame


def test_the_default_window_holds_the_truth_in_its_middle() -> None:
    window = CeilingWindow()
    states = window.states(TRUTH)
    assert window.size == len(states) == 31 * 13 * 9 * 7
    assert np.array_equal(states[window.truth_index], TRUTH.as_array())
    assert len(np.unique(states, axis=0)) == window.size
    d, alpha, w, beta = states.T
    assert (d.min(), d.max()) == (TRUTH.d - 15, TRUTH.d + 15)
    assert np.allclose(np.degrees([alpha.min(), alpha.max()]), np.degrees(TRUTH.alpha) + np.array([-6, 6]))
    assert np.allclose([w.min(), w.max()], [0.6 * TRUTH.w, 1.4 * TRUTH.w])
    assert np.allclose(np.degrees(np.unique(beta - TRUTH.beta)), np.arange(-3, 4))


def test_a_coarser_window_still_holds_the_truth() -> None:
    window = CeilingWindow(d_px=10, d_step_px=4, alpha_deg=0, w_fraction=0, w_steps=1, beta_step_deg=2)
    assert window.size == 5 * 1 * 1 * 3
    assert np.array_equal(window.states(TRUTH)[window.truth_index], TRUTH.as_array())


@pytest.mark.parametrize(
    ("change", "name"),
    [({"d_px": -1}, "d_px"), ({"alpha_step_deg": 0}, "alpha_step_deg"), ({"w_fraction": 1.0}, "w_fraction"),
     ({"w_steps": 8}, "w_steps"), ({"beta_step_deg": math.nan}, "beta_step_deg")],
)
def test_a_bad_window_names_its_field(change: dict, name: str) -> None:
    with pytest.raises(ValueError, match=rf"CeilingWindow\.{name} must"):
        CeilingWindow(**change)


def test_a_model_that_peaks_at_the_truth_has_a_ceiling_of_100(fakes: types.ModuleType) -> None:
    sequence = fakes.FakeSequence("fake/S1", 6)
    tracker = Peaked()
    result = likelihood_ceiling(tracker, sequence)
    assert isinstance(tracker, ScoresStates)
    assert result.ceiling_pct == 100.0 and result.labelled == 6 and result.failures == []
    assert (result.tracker, result.sequence) == ("peaked", "fake/S1")
    # One reset, with generator seed 0 and the first frame's truth; one call a frame with the whole window.
    [(info, draw, init)] = tracker.resets
    assert info == sequence.info and draw == np.random.default_rng(0).random() and init == fakes.truth_at(0)
    assert tracker.calls == [(index, (CeilingWindow().size, 4)) for index in range(6)]
    row = result.frames.iloc[3]
    truth = fakes.truth_at(3).cable
    assert (row["best_d_px"], row["best_w_px"]) == (truth.d, truth.w)
    assert row["best_alpha_deg"] == pytest.approx(math.degrees(truth.alpha))
    assert row["best_score"] == row["truth_score"] == 0.0
    assert (result.frames["score_ms"] >= 0).all()


def test_a_model_that_peaks_10_px_off_has_a_ceiling_of_0(fakes: types.ModuleType) -> None:
    result = likelihood_ceiling(Peaked(offset=(10.0, 0.0, 0.0, 0.0)), fakes.FakeSequence("fake/S1", 5))
    assert result.ceiling_pct == 0.0 and result.failures == [0, 1, 2, 3, 4]
    assert np.allclose(result.frames["best_d_px"], [fakes.truth_at(k).cable.d + 10 for k in range(5)])
    assert (result.frames["truth_score"] < result.frames["best_score"]).all()


def test_the_detection_rule_decides_not_equality_with_the_truth(fakes: types.ModuleType) -> None:
    near = likelihood_ceiling(Peaked(offset=(3.0, 0.0, 0.0, 0.0)), fakes.FakeSequence("fake/S1", 4))
    turned = likelihood_ceiling(Peaked(offset=(0.0, math.radians(4), 0.0, 0.0)), fakes.FakeSequence("fake/S1", 4))
    assert near.ceiling_pct == 100.0 and turned.ceiling_pct == 0.0


def test_unlabelled_frames_are_not_scored(fakes: types.ModuleType) -> None:
    tracker = Peaked(offset=(10.0, 0.0, 0.0, 0.0))
    result = likelihood_ceiling(tracker, PartlyLabelled(fakes.FakeSequence("fake/S1", 8)))
    assert [index for index, _ in tracker.calls] == [0, 2, 6]
    assert result.frames["frame"].tolist() == [0, 2, 6] and result.labelled == 3


def test_bad_inputs_are_named(fakes: types.ModuleType) -> None:
    sequence = fakes.FakeSequence("fake/S1", 3)
    with pytest.raises(TypeError, match=r"tracker 'perfect' \(Perfect\) does not implement score_states"):
        likelihood_ceiling(fakes.Perfect(), sequence)
    with pytest.raises(ValueError, match=r"sequence 'fake/S1' is a sonar sequence"):
        likelihood_ceiling(Peaked(), PartlyLabelled(sequence, modality="sonar"))
    with pytest.raises(ValueError, match=r"tracker 'peaked', sequence 'fake/S1', frame 0: score_states returned NaN"):
        likelihood_ceiling(Peaked(nan=True), sequence)
    with pytest.raises(ValueError, match=r"sequence 'fake/S0' has no frames"):
        likelihood_ceiling(Peaked(), fakes.FakeSequence("fake/S0", 0))


@dataclasses.dataclass(frozen=True)
class FirstFrames(Sequence):
    """The first ``count`` frames of a sequence."""

    base: Sequence
    count: int

    @property
    def info(self) -> SequenceInfo:
        return dataclasses.replace(self.base.info, n_frames=self.count)

    def frames(self) -> Iterator[Frame]:
        for frame, _ in zip(self.base.frames(), range(self.count)):
            yield frame


@pytest.mark.slow
def test_condensation_s_weight_finds_the_cable_on_a_clean_sequence() -> None:
    from benchmark.plugins import load_registry

    registry = load_registry()
    tracker = registry.trackers["condensation"].create()
    result = likelihood_ceiling(tracker, FirstFrames(registry.sequence("camera/S3"), 3))
    assert result.labelled == 3 and result.ceiling_pct == 100.0
    assert (result.frames["best_score"] >= result.frames["truth_score"]).all()
