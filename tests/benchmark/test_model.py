"""Tests of benchmark.model: the generic frame every modality shares, and sequences."""

import dataclasses
import pickle

import numpy as np
import pytest

from benchmark.modalities.camera.model import CableState, CameraFrame, CameraTruth
from benchmark.model import Frame, Outcome, Sequence, SequenceInfo


def test_a_frame_is_made_through_its_generic_alias():
    image = np.arange(6, dtype=np.uint8).reshape(2, 3)
    frame = Frame[np.ndarray, int](index=2, observation=image, truth=7, time_s=0.08)
    assert type(frame) is Frame
    assert (frame.index, frame.truth, frame.navigation, frame.time_s) == (2, 7, None, 0.08)
    assert frame.observation is image
    unlabelled = CameraFrame(0, image)
    assert type(unlabelled) is Frame and unlabelled.truth is None and unlabelled.time_s == 0.0


def test_a_frame_pickles_with_its_parts():
    truth = CameraTruth(CableState(1.0, 0.1, 20.0, 0.0))
    frame = Frame[np.ndarray, CameraTruth](4, np.full((2, 2), 9, dtype=np.uint8), truth, {"u": 0.5}, 0.16)
    back = pickle.loads(pickle.dumps(frame))
    assert (back.index, back.truth, back.navigation, back.time_s) == (4, truth, {"u": 0.5}, 0.16)
    np.testing.assert_array_equal(back.observation, frame.observation)


def test_a_frame_is_frozen():
    frame = Frame[str, int](0, "ping", 1)
    with pytest.raises(dataclasses.FrozenInstanceError):
        frame.truth = 2  # type: ignore[misc]
    assert dataclasses.replace(frame, truth=2).truth == 2 and frame.truth == 1


class Three(Sequence):
    @property
    def info(self) -> SequenceInfo:
        return SequenceInfo("mini/three", "anything")

    def frames(self):
        return (Frame(index, f"obs {index}") for index in range(3))


def test_a_sequence_iterates_its_frames_and_names_itself():
    sequence = Three()
    assert [frame.observation for frame in sequence] == ["obs 0", "obs 1", "obs 2"]
    assert repr(sequence) == "<Three 'mini/three'>"
    assert sequence.info.modality == "anything" and sequence.info.extra == {}


def test_outcomes_are_the_rates_of_table_v():
    assert [str(outcome) for outcome in Outcome] == ["correct", "false", "missed"]
