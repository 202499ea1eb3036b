"""StereoScene: the Sequence contract, measurements, navigation and truth of each frame."""

from __future__ import annotations

import math
import pickle
from typing import Any

import numpy as np
import pytest
from trackbench_suites.loader import merge_tables

from benchmark.errors import DataError
from benchmark.modalities.stereo.geometry import project
from benchmark.modalities.stereo.model import ChaseNavigation, StereoCalibration, StereoMeasurement, StereoTruth
from benchmark.modalities.stereo.scenes.scene import StereoScene
from benchmark.modalities.stereo.scenes.sensors import Loss
from benchmark.model import Sequence

WEAVING: dict[str, Any] = {
    "name": "stereo/weave",
    "n_frames": 300,
    "seed": 9,
    "case": 3,
    "speed": "medium",
    "target": {
        "start_m": 6.0,
        "speed_knots": [[0, 4.0], [10, 7.0], [30, 7.0], [40, 4.0]],
        "path": {"course_deg": 70.0, "amplitude_m": 5.0, "wavelength_m": 90.0, "onset_m": 20.0, "ramp_m": 40.0},
    },
    "chase": {
        "speed_knots": [[0, 4.0], [5, 4.0], [15, 7.0], [35, 7.0], [45, 4.0]],
        "path": {"course_deg": 70.0, "amplitude_m": 5.0, "wavelength_m": 90.0, "onset_m": 20.0, "ramp_m": 40.0},
    },
}
"""Both boats on one sinusoid; the gap opens from 6 m to 21 m and closes again after 45 s."""

QUIET = {
    "camera": {"correlation_accuracy_px": 0.0},
    "sensors": {"gps_sigma_m": 0.0, "heading_sigma_deg": 0.0, "dropout_rate": 0.0},
}


def _scene(**changes: Any) -> StereoScene:
    """The weaving scene with nested keys replaced by ``changes``."""
    return StereoScene.from_dict(merge_tables(WEAVING, changes))


def test_info_describes_the_sequence() -> None:
    scene = _scene(description="weaving")
    info = scene.info
    assert isinstance(scene, Sequence)
    assert (info.name, info.modality, info.n_frames, info.frame_interval_s) == ("stereo/weave", "stereo", 300, 0.2)
    assert isinstance(info.calibration, StereoCalibration) and info.calibration.width_px == 320
    assert (info.extra["description"], info.extra["case"], info.extra["speed"]) == ("weaving", 3, "medium")


def test_frames_carry_measurement_truth_navigation_and_time() -> None:
    scene = _scene(n_frames=4)
    frames = list(scene)
    assert [f.index for f in frames] == [0, 1, 2, 3]
    assert [f.time_s for f in frames] == pytest.approx([0.0, 0.2, 0.4, 0.6])
    chase, target = scene.tracks()
    for frame in frames:
        assert isinstance(frame.truth, StereoTruth) and isinstance(frame.navigation, ChaseNavigation)
        assert frame.observation is None or isinstance(frame.observation, StereoMeasurement)
        assert frame.truth.target.position_m == tuple(target.position_m[frame.index])
        assert frame.truth.chase_heading == chase.heading[frame.index]
        assert frame == scene.frame(frame.index)
    with pytest.raises(IndexError, match="frame 4"):
        scene.frame(4)


def test_same_seed_gives_identical_frames_and_another_seed_other_noise() -> None:
    a, b, c = list(_scene()), list(_scene()), list(_scene(seed=10))
    assert a == b
    assert [f.truth for f in a] == [f.truth for f in c]
    assert [f.navigation for f in a] != [f.navigation for f in c]
    assert [f.observation for f in a] != [f.observation for f in c]


def test_pickled_scene_is_small_and_gives_the_same_frames() -> None:
    scene = _scene()
    first = list(scene)
    payload = pickle.dumps(scene)
    assert len(payload) < 5000
    assert list(pickle.loads(payload)) == first


def test_without_noise_measurements_and_navigation_are_the_truth() -> None:
    scene = _scene(**QUIET)
    assert (scene.losses() == Loss.KEPT).all()
    for frame in scene:
        truth, nav, z = frame.truth, frame.navigation, frame.observation
        assert nav.position_m == truth.chase_position_m and nav.heading == pytest.approx(truth.chase_heading)
        # Eq. (10) maps the measured relative position onto TG's true position.
        psi, (x_v, y_v), (x_ch, y_ch) = truth.chase_heading, z.relative_m, truth.chase_position_m
        absolute = (math.cos(psi) * x_v - math.sin(psi) * y_v + x_ch, math.sin(psi) * x_v + math.cos(psi) * y_v + y_ch)
        assert absolute == pytest.approx(truth.target.position_m, abs=1e-9)


def test_range_opens_beyond_the_limit_and_matches_the_truth() -> None:
    scene = _scene()
    ranges = scene.relative_geometry().range_m
    assert ranges.min() < 7 and ranges.max() > 19
    assert [f.truth.range_m for f in scene] == pytest.approx(list(ranges))


def test_gps_and_compass_noise_have_the_given_sigmas() -> None:
    scene = _scene(n_frames=3000, sensors={"gps_sigma_m": 0.4, "heading_sigma_deg": 2.0})
    errors = np.array([np.subtract(f.navigation.position_m, f.truth.chase_position_m) for f in scene])
    assert errors.std(axis=0) == pytest.approx([0.4, 0.4], rel=0.06)
    assert abs(errors.mean()) < 0.03
    turn = np.array([math.remainder(f.navigation.heading - f.truth.chase_heading, math.tau) for f in scene])
    assert np.degrees(turn.std()) == pytest.approx(2.0, rel=0.06)


def test_pixel_noise_statistics_match_q_f_on_a_long_run() -> None:
    scene = _scene(n_frames=4000, sensors={"dropout_rate": 0.0})
    geometry = scene.relative_geometry()
    true_l, true_r = project(geometry.ahead_m, geometry.starboard_m, scene.info.calibration)
    measured = [(k, f.observation) for k, f in enumerate(scene) if f.observation is not None]
    assert len(measured) == 4000
    left = np.array([z.left_px for _, z in measured]) - true_l
    right = np.array([z.right_px for _, z in measured]) - true_r
    assert left.std() == pytest.approx(0.11 / math.sqrt(2), rel=0.05)
    assert right.std() == pytest.approx(0.11 / math.sqrt(2), rel=0.05)
    assert abs(np.corrcoef(left, right)[0, 1]) < 0.05


def test_dropped_frames_have_no_measurement() -> None:
    scene = _scene(n_frames=1000, sensors={"dropout_rate": 0.3, "dropout_burst_frames": 2.0})
    losses = scene.losses()
    missing = np.array([f.observation is None for f in scene])
    assert np.array_equal(missing, losses != Loss.KEPT)
    assert set(np.unique(losses)) == {Loss.KEPT, Loss.DROPOUT}
    assert missing.mean() == pytest.approx(0.3, abs=0.08)


def test_targets_out_of_view_or_too_far_are_lost() -> None:
    starboard = 30.0 * np.array((-math.sin(math.radians(70.0)), math.cos(math.radians(70.0))))
    abeam = _scene(n_frames=20, target={"path": {"origin_m": list(starboard), "amplitude_m": 0.0}})
    assert (abeam.losses() == Loss.OUT_OF_VIEW).all()
    assert all(f.observation is None for f in abeam)
    straight = {"path": {"amplitude_m": 0.0}}
    far = _scene(
        n_frames=20, camera={"correlation_accuracy_px": 0.0}, target={"start_m": 80.0, **straight}, chase=straight
    )
    assert far.relative_geometry().range_m.max() < 83.0  # about 0.21 px of disparity, below the 0.3 px minimum
    assert (far.losses() == Loss.LOW_DISPARITY).all()


def test_truth_heading_is_the_direction_of_motion_clockwise_from_north() -> None:
    scene = _scene(**QUIET)
    frames = list(scene)
    for before, after in zip(frames, frames[1:]):
        step = np.subtract(after.truth.target.position_m, before.truth.target.position_m)
        moving = math.atan2(step[1], step[0])
        assert math.remainder(moving - before.truth.target.heading, math.tau) == pytest.approx(0.0, abs=0.05)
    east = _scene(n_frames=5, target={"path": {"course_deg": 90.0}}, chase={"path": {"course_deg": 90.0}})
    truths = [f.truth for f in east]
    assert truths[0].target.heading == pytest.approx(math.pi / 2)
    assert truths[-1].target.position_m[1] > truths[0].target.position_m[1]
    assert truths[-1].target.position_m[0] == pytest.approx(truths[0].target.position_m[0])


def test_boats_that_collide_are_a_data_error() -> None:
    with pytest.raises(DataError, match=r"stereo/weave: at frame 0 the boats are 1\.00 m apart"):
        _scene(target={"start_m": 1.0}).frame(0)
