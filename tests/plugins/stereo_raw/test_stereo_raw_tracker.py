"""The raw stereovision baseline (seeds/002, eq. 10 and Tables 6-8)."""

from __future__ import annotations

import math

import numpy as np
import pydantic
import pytest
from trackbench_stereo_raw import StereoRawParams, StereoRawTracker

from benchmark.errors import DataError, ParameterError
from benchmark.modalities.stereo.modality import STEREO
from benchmark.modalities.stereo.model import ChaseNavigation, StereoCalibration, StereoMeasurement
from benchmark.model import Frame, SequenceInfo
from benchmark.runner import Cell, run_cell

CALIBRATION = StereoCalibration(140.8, 0.12, 159.5, 159.5, 320, 16.0, 0.11)
INFO = SequenceInfo("synthetic/raw", "stereo", n_frames=100, frame_interval_s=0.2, calibration=CALIBRATION)


def _measurement(x: float, y: float) -> StereoMeasurement:
    disparity = CALIBRATION.focal_px * CALIBRATION.baseline_m / x
    left = CALIBRATION.principal_left_px + CALIBRATION.focal_px * y / x
    return StereoMeasurement(left, left - disparity, (x, y))


def _frames(n: int, lost=lambda index: False) -> list[Frame]:
    """CH heading east at 2 m/s from the origin; TG 10 m ahead and 1 m to starboard, keeping pace."""
    frames = []
    for index in range(n):
        t = index * 0.2
        navigation = ChaseNavigation((0.0, 2.0 * t), math.pi / 2)
        observation = None if lost(index) else _measurement(10.0, 1.0)
        frames.append(Frame(index, observation, None, navigation, t))
    return frames


def _run(frames: list[Frame], params: StereoRawParams | None = None) -> list:
    tracker = StereoRawTracker(params)
    tracker.reset(INFO, np.random.default_rng(0))
    return [tracker.step(frame) for frame in frames]


def test_position_is_eq_10_applied_to_the_measurement():
    estimates = _run(_frames(3))
    # heading east: ahead is east, starboard is south
    assert estimates[1].position_m == pytest.approx((-1.0, 0.4 + 10.0))


def test_velocity_speed_and_heading_follow_the_target():
    estimates = _run(_frames(30))
    for estimate in estimates[1:]:
        assert estimate.velocity_mps == pytest.approx((0.0, 2.0), abs=1e-9)
        assert estimate.speed_mps == pytest.approx(2.0)
        assert estimate.heading == pytest.approx(math.pi / 2)


def test_nothing_is_reported_without_a_measurement_or_before_a_velocity():
    estimates = _run(_frames(12, lost=lambda index: index in (0, 5, 6)))
    assert [index for index, e in enumerate(estimates) if e is None] == [0, 1, 5, 6]
    assert estimates[7].velocity_mps == pytest.approx((0.0, 2.0), abs=1e-9)


def test_a_measurement_behind_the_camera_is_not_reported():
    frames = _frames(3)
    frames[2] = Frame(2, StereoMeasurement(160.0, 161.0, (-140.8, 0.0)), None, frames[2].navigation, 0.4)
    assert _run(frames)[2] is None


def test_the_window_smooths_speed_noise():
    rng = np.random.default_rng(1)
    frames = []
    for index, frame in enumerate(_frames(200)):
        x, y = 10.0 + rng.normal(0.0, 0.5), 1.0 + rng.normal(0.0, 0.1)
        frames.append(Frame(index, _measurement(x, y), None, frame.navigation, frame.time_s))

    def speed_rmse(window: int) -> float:
        estimates = _run(frames, StereoRawParams(window=window))[20:]
        return float(np.sqrt(np.mean([(e.speed_mps - 2.0) ** 2 for e in estimates])))

    assert speed_rmse(15) < 0.25 * speed_rmse(1)


def test_bad_window_and_bad_inputs_are_refused():
    with pytest.raises(ParameterError, match=r"tracker 'stereo_raw'.*'window'"):
        StereoRawTracker.make_params({"window": 0})
    with pytest.raises(pydantic.ValidationError, match="window"):
        StereoRawParams(window=0)
    tracker = StereoRawTracker()
    with pytest.raises(DataError, match="frame_interval_s"):
        tracker.reset(SequenceInfo("x/y", "stereo"), np.random.default_rng(0))
    tracker.reset(INFO, np.random.default_rng(0))
    with pytest.raises(DataError, match="frame 4.*StereoMeasurement"):
        tracker.step(Frame(4, "not a measurement", None, None, 0.8))
    with pytest.raises(DataError, match="frame 5.*ChaseNavigation"):
        tracker.step(Frame(5, _measurement(10.0, 0.0), None, None, 1.0))


def test_rendered_image_pairs_give_the_positions_and_velocities_of_their_measurements(
    plugin_registry, stereo_clip, stereo_clip_measured
):
    result = run_cell(
        Cell(plugin_registry.trackers["stereo_raw"], stereo_clip, seed=0, init="none", modality=STEREO)
    )
    assert result.status == "ok", result.message
    errors = result.frames["err_position_m"].to_numpy()
    assert np.isnan(errors[0]) and np.all(errors[1:] < 2.0)
    pairs = _run_on(list(stereo_clip.frames()), stereo_clip.info)
    assert pairs == _run_on(stereo_clip_measured, stereo_clip.info)
    assert pairs[0] is None and None not in pairs[1:]


def _run_on(frames: list[Frame], info: SequenceInfo) -> list:
    tracker = StereoRawTracker()
    tracker.reset(info, np.random.default_rng(0))
    return [tracker.step(frame) for frame in frames]
