"""The camera's data model: cable states as the thesis parameterises them, and camera frames."""

import math
import pickle

import numpy as np
from hypothesis import given
from hypothesis import strategies as st

from benchmark.modalities.camera.model import UNKNOWN_CABLE, CableState, CameraFrame, CameraTruth

finite = st.floats(-1e6, 1e6)


@given(finite, finite, finite, finite)
def test_a_state_round_trips_through_an_array(d: float, alpha: float, w: float, beta: float) -> None:
    state = CableState(d, alpha, w, beta)
    assert CableState.from_array(state.as_array()) == state
    assert state.as_array().dtype == float and state.is_known


def test_a_state_with_any_nan_is_unknown() -> None:
    assert not UNKNOWN_CABLE.is_known
    assert not CableState(1.0, 0.0, math.nan, 0.0).is_known


def test_a_camera_frame_is_built_through_its_alias_and_pickles() -> None:
    frame = CameraFrame(2, np.zeros((3, 4), np.uint8), CameraTruth(CableState(1.0, 0.0, 9.0, 0.0)))
    again = pickle.loads(pickle.dumps(frame))
    assert again.index == 2 and again.truth == frame.truth and np.array_equal(again.observation, frame.observation)
