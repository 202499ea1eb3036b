"""The camera modality's hypothesis strategies: states in the image, valid specs, labelled rendered frames."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import event, given, settings
from hypothesis import strategies as st

from benchmark.modalities.camera.geometry import Line, cable_borders, chord_midpoint
from benchmark.modalities.camera.modality import CAMERA
from benchmark.modalities.camera.model import CameraTruth
from benchmark.modalities.camera.scenes.scene import CameraScene
from benchmark.modalities.camera.scenes.spec import CameraSceneSpec
from benchmark.modalities.camera.strategies import cable_states, frames, scene_specs, sequences
from benchmark.model import Frame

MAX_FRAMES = 3


def inside(point: tuple[float, float], size: tuple[int, int]) -> bool:
    """Whether a model point lies in the rectangle spanned by the pixel centres."""
    return abs(point[0]) <= (size[0] - 1) / 2.0 and abs(point[1]) <= (size[1] - 1) / 2.0


def crossing(first: Line, second: Line) -> tuple[float, float] | None:
    """Where two lines meet; None for parallel lines."""
    cross = first.dx * second.dy - first.dy * second.dx
    if abs(cross) < 1e-12:
        return None
    s = ((second.x0 - first.x0) * second.dy - (second.y0 - first.y0) * second.dx) / cross
    return first.x0 + s * first.dx, first.y0 + s * first.dy


def check_labelled_camera_frame(frame: Frame) -> None:
    CAMERA.check_frame(frame, f"frame {frame.index}")
    assert isinstance(frame.truth, CameraTruth) and frame.truth.cable.is_known
    assert frame.observation.dtype == np.uint8 and frame.observation.ndim == 2


@settings(max_examples=200, deadline=None)
@given(st.data(), st.integers(8, 640), st.integers(8, 480))
def test_cable_states_lie_in_the_image_by_the_chord_rule(data: st.DataObject, width: int, height: int) -> None:
    size = (width, height)
    state = data.draw(cable_states(width, height))
    # chord_midpoint falls back to the point nearest the centre, outside the image, when a line misses it.
    assert inside(chord_midpoint(Line.from_normal(state.d, state.alpha), size), size)
    assert -math.pi / 2 < state.alpha <= math.pi / 2
    assert 3.0 <= state.w <= 0.4 * min(size)
    assert state.beta >= 0.0
    apex = crossing(*cable_borders(state))
    assert apex is None or not inside(apex, size)


def test_cable_states_need_an_image_of_8_x_8_px() -> None:
    with pytest.raises(ValueError, match="at least 8 x 8"):
        cable_states(7, 100)


@settings(max_examples=30, deadline=None)
@given(scene_specs(MAX_FRAMES))
def test_scene_specs_are_valid_and_survive_a_suite_file(spec: CameraSceneSpec) -> None:
    assert 1 <= spec.n_frames <= MAX_FRAMES
    assert spec.frame_size[0] <= 320 and spec.frame_size[1] <= 240
    assert CameraSceneSpec.from_dict(spec.to_dict()) == spec
    CameraScene(spec).trajectory()  # checks the camera's clearance of the seabed and the pipe


def test_scene_specs_need_a_frame() -> None:
    with pytest.raises(ValueError, match="max_frames"):
        scene_specs(0)


@settings(max_examples=25, deadline=None)
@given(sequences(MAX_FRAMES))
def test_sequences_hold_1_to_max_frames_labelled_camera_frames(sequence: CameraScene) -> None:
    rendered = list(sequence.frames())
    assert 1 <= len(rendered) <= MAX_FRAMES
    assert [frame.index for frame in rendered] == list(range(sequence.info.n_frames))
    width, height = sequence.info.frame_size
    for frame in rendered:
        check_labelled_camera_frame(frame)
        assert frame.observation.shape == (height, width)


@settings(max_examples=10, deadline=None)
@given(scene_specs(2))
def test_the_same_spec_renders_the_same_frames_bit_for_bit(spec: CameraSceneSpec) -> None:
    for first, second in zip(CameraScene(spec).frames(), CameraScene(spec).frames(), strict=True):
        assert np.array_equal(first.observation, second.observation)
        assert first.truth == second.truth and first.navigation == second.navigation


@settings(max_examples=25, deadline=None)
@given(sequences(MAX_FRAMES))
def test_the_true_cable_is_in_view_and_only_sand_hides_it(sequence: CameraScene) -> None:
    size = sequence.info.frame_size
    buried = bool(sequence.spec.burial)
    for frame in sequence.frames():
        cable = frame.truth.cable
        assert inside(chord_midpoint(Line.from_normal(cable.d, cable.alpha), size), size)
        assert 1.0 < cable.w < min(size)
        visible = frame.truth.visible_fraction
        event("fully visible" if visible == 1.0 else "hidden by sand" if visible == 0.0 else "partly buried")
        assert visible > 0.0 or buried


@settings(max_examples=15, deadline=None)
@given(frames(MAX_FRAMES))
def test_frames_are_labelled_camera_frames_of_a_short_sequence(frame: Frame) -> None:
    check_labelled_camera_frame(frame)
    height, width = frame.observation.shape
    assert 96 <= width <= 320 and 0.6 * width - 1 <= height <= 0.75 * width + 1
    assert 0 <= frame.index < MAX_FRAMES
