"""The stereo modality's hypothesis strategies: cameras, measurements, scene specs and sequences."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from hypothesis import Phase, find, given, settings
from hypothesis import strategies as st

from benchmark.modalities.stereo.geometry import in_front, in_view, project, triangulate
from benchmark.modalities.stereo.modality import STEREO
from benchmark.modalities.stereo.model import StereoCalibration, StereoMeasurement
from benchmark.modalities.stereo.scenes.image_spec import StereoImageSceneSpec
from benchmark.modalities.stereo.scenes.scene import MIN_SEPARATION_M, StereoScene
from benchmark.modalities.stereo.scenes.spec import StereoCameraSpec, StereoSceneSpec
from benchmark.modalities.stereo.strategies import (
    calibrations,
    scene_specs,
    sequences,
    stereo_measurements,
)
from benchmark.model import Frame, Sequence

BUMBLEBEE = StereoCameraSpec().calibration()

MAX_FRAMES = 4

FIRST_FOUND = settings(max_examples=200, derandomize=True, database=None, deadline=None, phases=[Phase.generate])
"""For :func:`hypothesis.find`: the first example found, the same on every run."""


def image_pair(observation: object) -> bool:
    return isinstance(observation, tuple)


def sequence_where(condition) -> Sequence:
    """The first sequence hypothesis finds whose frames meet ``condition``; fails if there is none."""
    return find(sequences(MAX_FRAMES), lambda sequence: condition(list(sequence)), settings=FIRST_FOUND)


def identical_frames(a: Frame, b: Frame) -> bool:
    """Whether two frames hold the same observation, truth, navigation and time, bit for bit."""
    if image_pair(a.observation):
        observations_equal = image_pair(b.observation) and all(
            np.array_equal(x, y) for x, y in zip(a.observation, b.observation, strict=True)
        )
    else:
        observations_equal = a.observation == b.observation
    return observations_equal and dataclasses.replace(a, observation=None) == dataclasses.replace(b, observation=None)


# ------------------------------------------------------------ calibrations
@settings(max_examples=100, deadline=None)
@given(calibrations())
def test_calibrations_are_cameras_the_scenes_accept(calibration: StereoCalibration) -> None:
    assert StereoCameraSpec(**dataclasses.asdict(calibration)).calibration() == calibration
    assert 64 <= calibration.width_px <= 1280
    assert 0.05 <= calibration.baseline_m <= 0.6
    assert 5.0 <= calibration.range_limit_m <= 50.0
    assert 0.0 <= calibration.correlation_accuracy_px <= 0.5
    principal_points = [calibration.principal_left_px, calibration.principal_right_px]
    assert np.all(in_view(principal_points, calibration))


@settings(max_examples=100, deadline=None)
@given(calibrations())
def test_a_target_straight_ahead_at_the_range_limit_is_in_view_of_both_cameras(calibration) -> None:
    left, right = project(calibration.range_limit_m, 0.0, calibration)
    assert np.all(in_view([left, right], calibration))


# ------------------------------------------------------------ measurements
def check_measurement(measurement: StereoMeasurement, calibration: StereoCalibration) -> None:
    """In both images, in front, within the range limit, and ``relative_m`` the triangulation of the pixels."""
    left, right = measurement.left_px, measurement.right_px
    assert np.all(in_view([left, right], calibration))
    assert in_front(left, right, calibration)
    disparity = (left - calibration.principal_left_px) - (right - calibration.principal_right_px)
    assert disparity > 0
    assert measurement.relative_m == tuple(map(float, triangulate(left, right, calibration)))
    ahead, starboard = measurement.relative_m
    assert 0 < ahead <= calibration.range_limit_m
    # round trip: the triangulated point projects back onto the measured pixels
    np.testing.assert_allclose(project(ahead, starboard, calibration), (left, right), rtol=0, atol=1e-9 * ahead)


@settings(max_examples=100, deadline=None)
@given(calibrations().flatmap(lambda calibration: st.tuples(st.just(calibration), stereo_measurements(calibration))))
def test_measurements_lie_in_both_images_within_range_and_triangulate_back(drawn) -> None:
    calibration, measurement = drawn
    check_measurement(measurement, calibration)


@settings(max_examples=100, deadline=None)
@given(stereo_measurements(BUMBLEBEE))
def test_measurements_of_the_bumblebee_span_its_16_m_range(measurement) -> None:
    check_measurement(measurement, BUMBLEBEE)


@settings(max_examples=50, deadline=None)
@given(stereo_measurements())
def test_measurements_of_a_random_camera_lie_in_an_image_within_50_m(measurement) -> None:
    assert -0.5 <= min(measurement.left_px, measurement.right_px)
    assert max(measurement.left_px, measurement.right_px) <= 1280 - 0.5
    assert 0 < measurement.relative_m[0] <= 50.0


def test_measurements_reach_the_range_limit_and_the_nearest_target_in_view() -> None:
    find(stereo_measurements(BUMBLEBEE), lambda m: m.relative_m[0] > 15.9, settings=FIRST_FOUND)
    find(stereo_measurements(BUMBLEBEE), lambda m: m.relative_m[0] < 0.1, settings=FIRST_FOUND)


def test_a_camera_that_sees_no_target_within_range_is_refused() -> None:
    myopic = dataclasses.replace(BUMBLEBEE, range_limit_m=0.01)  # the disparity there exceeds the image
    with pytest.raises(ValueError, match="in view of both cameras"):
        stereo_measurements(myopic)


# ------------------------------------------------------------ scene specs
@settings(max_examples=40, deadline=None)
@given(st.booleans().flatmap(lambda images: scene_specs(MAX_FRAMES, images=images)))
def test_scene_specs_are_valid_suite_entries(spec: StereoSceneSpec) -> None:
    assert type(spec).from_dict(spec.to_dict()) == spec
    assert 1 <= spec.n_frames <= MAX_FRAMES
    assert spec.name.startswith("stereo-images/" if isinstance(spec, StereoImageSceneSpec) else "stereo/")


@settings(max_examples=60, deadline=None)
@given(scene_specs(max_frames=40))
def test_boats_stay_apart_and_the_target_starts_in_the_field_of_view(spec: StereoSceneSpec) -> None:
    geometry = StereoScene(spec).relative_geometry()
    assert geometry.range_m.min() > MIN_SEPARATION_M
    half_view = math.atan(spec.camera.width_px / 2 / spec.camera.focal_px)
    assert abs(geometry.bearing[0]) <= 0.9 * half_view + 1e-9


@settings(max_examples=10, deadline=None)
@given(scene_specs(MAX_FRAMES, images=True))
def test_image_specs_render_small_images(spec: StereoImageSceneSpec) -> None:
    width, height = spec.frame_size
    assert 32 <= width <= 128 and 24 <= height <= 96


# ------------------------------------------------------------ sequences
@settings(max_examples=30, deadline=None)
@given(sequences(MAX_FRAMES))
def test_sequence_frames_are_labelled_stereo_frames(sequence: Sequence) -> None:
    frames = list(sequence)
    assert 1 <= len(frames) <= MAX_FRAMES
    assert len(frames) == sequence.info.n_frames and sequence.info.modality == "stereo"
    for frame in frames:
        STEREO.check_frame(frame, f"frame {frame.index}")
        assert frame.truth is not None
        if image_pair(frame.observation):
            assert all(image.shape == (*reversed(sequence.info.frame_size), 3) for image in frame.observation)


@settings(max_examples=20, deadline=None)
@given(max_frames=st.integers(1, 6), data=st.data())
def test_sequences_have_one_to_max_frames(max_frames: int, data: st.DataObject) -> None:
    sequence = data.draw(sequences(max_frames))
    assert 1 <= len(list(sequence)) <= max_frames


def test_both_observation_forms_and_lost_targets_occur() -> None:
    sequence_where(lambda frames: any(image_pair(frame.observation) for frame in frames))
    sequence_where(lambda frames: any(isinstance(frame.observation, StereoMeasurement) for frame in frames))
    sequence_where(lambda frames: any(frame.observation is None for frame in frames))


@settings(max_examples=20, deadline=None)
@given(st.booleans().flatmap(lambda images: scene_specs(MAX_FRAMES, images=images)))
def test_the_same_spec_gives_the_same_frames_bit_for_bit(spec: StereoSceneSpec) -> None:
    kind = "stereo-images" if isinstance(spec, StereoImageSceneSpec) else "stereo"
    first = list(STEREO.scene_kinds[kind](spec.to_dict()))
    again = list(STEREO.scene_kinds[kind](spec.to_dict()))
    assert len(first) == len(again) == spec.n_frames
    assert all(identical_frames(a, b) for a, b in zip(first, again))
