"""CameraScene: the Sequence contract, navigation and ground truth of each frame."""

from __future__ import annotations

import math

import numpy as np
import pytest

from benchmark.errors import DataError
from benchmark.modalities.camera.model import CameraCalibration, CameraTruth, VehicleSpeeds
from benchmark.modalities.camera.scenes.motion import psi_matrix
from benchmark.modalities.camera.scenes.scene import CameraScene
from benchmark.modalities.camera.scenes.silhouette import cable_truth
from benchmark.model import Sequence


def test_info_describes_the_sequence(flat_scene) -> None:
    scene = CameraScene.from_dict(flat_scene(description="wavy", nominal_tilt_deg=55.0))
    info = scene.info
    assert isinstance(scene, Sequence)
    assert (info.name, info.modality, info.n_frames, info.frame_size) == ("camera/flat", "camera", 6, (320, 240))
    assert info.frame_interval_s == pytest.approx(0.04)
    assert info.calibration == CameraCalibration(380.0, 0.2, pytest.approx(math.radians(55.0)))
    assert info.extra["description"] == "wavy"


def test_frames_carry_image_truth_navigation_and_time(flat_scene) -> None:
    scene = CameraScene.from_dict(flat_scene(n_frames=3))
    frames = list(scene)
    assert [f.index for f in frames] == [0, 1, 2]
    assert [f.time_s for f in frames] == pytest.approx([0.0, 0.04, 0.08])
    for frame in frames:
        assert frame.observation.shape == (240, 320) and frame.observation.dtype == np.uint8
        assert isinstance(frame.truth, CameraTruth) and isinstance(frame.navigation, VehicleSpeeds)
        pose = scene.trajectory().pose(frame.index)
        assert frame.truth.pose == pose
        assert frame.truth.cable == cable_truth(pose, 0.1, 380.0, (320, 240))
        assert frame.truth.visible_fraction == 1.0


def test_reported_speeds_satisfy_equation_seven_without_noise(flat_scene) -> None:
    scene = CameraScene.from_dict(flat_scene(n_frames=8, nominal_tilt_deg=50.0))
    trajectory, phi0 = scene.trajectory(), math.radians(50.0)
    for k in range(8):
        s = scene.navigation(k)
        psi = psi_matrix(trajectory.theta[k], trajectory.phi[k] - phi0, trajectory.xi[k])
        moved = psi @ np.array((s.lateral, s.vertical, s.frontal)) * 0.04
        np.testing.assert_allclose(moved, trajectory.centres()[k + 1] - trajectory.centres()[k], atol=1e-12)


def test_sensor_noise_perturbs_the_reported_speeds(flat_scene) -> None:
    data = flat_scene(n_frames=50)
    exact = CameraScene.from_dict(data)
    data["motion"] = dict(data["motion"], speed_noise_mps=0.05)
    noisy = CameraScene.from_dict(data)
    errors = np.array([
        np.subtract(
            (noisy.navigation(k).lateral, noisy.navigation(k).frontal),
            (exact.navigation(k).lateral, exact.navigation(k).frontal),
        )
        for k in range(50)
    ])
    assert errors.std() == pytest.approx(0.05, rel=0.3)


def test_frames_out_of_range_are_an_index_error(flat_scene) -> None:
    scene = CameraScene.from_dict(flat_scene(n_frames=2))
    with pytest.raises(IndexError, match="camera/flat: frame 2"):
        scene.truth(2)


@pytest.mark.parametrize(
    ("motion", "message"),
    [
        ({"cy_m": {"mean": -0.2}}, "is less than 5 cm above the seabed"),
        ({"cy_m": {"mean": 0.05}, "cx_m": {"mean": 0.05}}, "touches the pipe"),
        ({"phi_deg": {"mean": 150.0}}, "looks backwards"),
    ],
)
def test_impossible_camera_paths_are_data_errors(flat_scene, motion, message) -> None:
    scene = CameraScene.from_dict(flat_scene(motion=motion))
    with pytest.raises(DataError, match=f"camera/flat: at frame 0 the camera {message}"):
        scene.truth(0)
