"""Reading a stereo frame: measurements as given, image pairs through the front end, front-end parameters."""

from __future__ import annotations

import dataclasses
import itertools
import math
import typing
from collections.abc import Iterator

import numpy as np
import pydantic
import pytest
from trackbench_stereo_ekf import StereoEkfTracker
from trackbench_stereo_raw import StereoRawTracker

from benchmark.errors import DataError, ParameterError
from benchmark.modalities.stereo.frontend import FrontEndParams, measure
from benchmark.modalities.stereo.model import ChaseNavigation, StereoMeasurement
from benchmark.modalities.stereo.observation import PREFIX, FrontEndSettings, front_end_params, read_frame
from benchmark.model import Frame, Sequence, SequenceInfo
from benchmark.plugins import load_registry

NAVIGATION = ChaseNavigation((1.0, 2.0), 0.3)
CLIP_FRAMES = 10


@dataclasses.dataclass(frozen=True)
class Clip(Sequence):
    """The first frames of a registered sequence, rendered once and kept."""

    clip_info: SequenceInfo
    clip_frames: tuple[Frame, ...]

    @property
    def info(self) -> SequenceInfo:
        return self.clip_info

    def frames(self) -> Iterator[Frame]:
        return iter(self.clip_frames)


@pytest.fixture(scope="module")
def stereo_clip() -> Clip:
    """The first frames of ``stereo-images/case1-medium``: image pairs with truth and CH's navigation."""
    suite = load_registry().suites["stereo-images"]
    sequence = next(item for item in suite.sequences if item.info.name == "stereo-images/case1-medium")
    frames = tuple(itertools.islice(sequence.frames(), CLIP_FRAMES))
    return Clip(dataclasses.replace(sequence.info, n_frames=CLIP_FRAMES), frames)


def test_every_front_end_parameter_is_a_tracker_parameter_with_its_default() -> None:
    settings = {field.name: field.default for field in dataclasses.fields(FrontEndSettings)}
    expected = {PREFIX + field.name: field.default for field in dataclasses.fields(FrontEndParams)}
    assert settings == expected
    assert front_end_params(FrontEndSettings()) == FrontEndParams()
    for tracker in (StereoEkfTracker, StereoRawTracker):
        assert set(expected) <= set(tracker.defaults())


def test_every_front_end_parameter_has_the_same_declared_domain_as_a_tracker_parameter() -> None:
    settings = typing.get_type_hints(FrontEndSettings, include_extras=True)
    params = typing.get_type_hints(FrontEndParams, include_extras=True)
    assert settings == {PREFIX + name: hint for name, hint in params.items()}
    for tracker in (StereoEkfTracker, StereoRawTracker):
        hints = typing.get_type_hints(tracker.Params, include_extras=True)
        assert {name: hints[name] for name in settings} == settings


@pytest.mark.parametrize(
    "bad",
    [
        {"hue_max": 180},
        {"hue_min": 41},
        {"num_disparities": 24},
        {"block_size": 8},
        {"prefilter_size": 261},
        {"prefilter": "laplace"},
        {"min_disparity_px": math.nan},
    ],
)
def test_settings_refuse_what_the_front_end_refuses_naming_the_tracker_parameter(bad) -> None:
    ((name, value),) = bad.items()
    with pytest.raises(pydantic.ValidationError, match=name):
        FrontEndParams(**bad)
    with pytest.raises(pydantic.ValidationError, match=PREFIX + name):
        FrontEndSettings(**{PREFIX + name: value})


@pytest.mark.parametrize("tracker", [StereoEkfTracker, StereoRawTracker])
def test_command_line_overrides_reach_the_front_end(tracker, stereo_clip) -> None:
    params = tracker.make_params({"frontend_block_size": "9", "frontend_prefilter": "xsobel"})
    front_end = front_end_params(params)
    assert (front_end.block_size, front_end.prefilter) == (9, "xsobel")
    assert front_end.hue_min == FrontEndParams().hue_min
    with pytest.raises(ParameterError, match=rf"tracker '{tracker.name}'.*frontend_block_size"):
        tracker.make_params({"frontend_block_size": "8"})
    with pytest.raises(ParameterError, match=rf"tracker '{tracker.name}'.*frontend_hue_min"):
        tracker.make_params({"frontend_hue_min": "50"})
    # A marker colour nobody wears: the tracker's front end finds nothing in any pair.
    blind = tracker(tracker.make_params({"frontend_hue_min": "140", "frontend_hue_max": "170"}))
    blind.reset(stereo_clip.info, np.random.default_rng(0))
    assert [blind.step(frame) for frame in stereo_clip.frames()] == [None] * stereo_clip.info.n_frames


def test_measurements_and_none_pass_through(stereo_clip) -> None:
    info = stereo_clip.info
    measurement = StereoMeasurement(170.0, 168.0, (8.4, 0.6))
    assert read_frame(Frame(0, measurement, None, NAVIGATION, 0.0), info, FrontEndParams()) == (measurement, NAVIGATION)
    assert read_frame(Frame(0, None, None, None, 0.0), info, FrontEndParams()) is None


def test_an_image_pair_is_measured_by_the_front_end(stereo_clip) -> None:
    info = stereo_clip.info
    params = FrontEndParams(block_size=9)
    for frame in stereo_clip.frames():
        read = read_frame(frame, info, params)
        expected = measure(*frame.observation, info.calibration, params)
        assert expected is not None
        assert read == (expected, frame.navigation)


def test_a_pair_without_the_marker_gives_no_measurement(stereo_clip) -> None:
    frame = next(stereo_clip.frames())
    assert read_frame(frame, stereo_clip.info, FrontEndParams(hue_min=140, hue_max=170)) is None
    assert read_frame(frame, stereo_clip.info, FrontEndParams()) is not None


def test_bad_observations_name_the_sequence_and_frame(stereo_clip) -> None:
    info = stereo_clip.info
    left, right = next(stereo_clip.frames()).observation
    cases = [
        ((left,), r"frame 7: expected a StereoMeasurement, None or an image pair \(left, right\), got tuple"),
        (np.zeros((4, 4)), "frame 7: expected a StereoMeasurement, None or an image pair.*got ndarray"),
        ((left, right[..., 0]), "frame 7: stereo front end: the right image must be a uint8 BGR array"),
        ((left, right[:100]), "frame 7: stereo front end: .* differ in shape"),
    ]
    for observation, message in cases:
        with pytest.raises(DataError, match=f"sequence 'stereo-images/case1-medium', {message}"):
            read_frame(Frame(7, observation, None, NAVIGATION, 1.4), info, FrontEndParams())
    with pytest.raises(DataError, match="frame 7: a measurement needs the chase boat's ChaseNavigation"):
        read_frame(Frame(7, (left, right), None, None, 1.4), info, FrontEndParams())
    bare = SequenceInfo("x/y", "stereo", frame_interval_s=0.2)
    with pytest.raises(DataError, match="'x/y', frame 7: an image pair needs the sequence's StereoCalibration"):
        read_frame(Frame(7, (left, right), None, NAVIGATION, 1.4), bare, FrontEndParams())
