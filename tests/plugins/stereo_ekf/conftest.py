"""Synthetic chase scenes for the stereo EKF tests.

A chase boat (CH) and a target boat (TG) move in the North-East plane; each
frame projects TG into an ideal stereo pair (the camera of seeds/002,
Table 4: f = 140.83 px, 0.12 m baseline, 320 px), perturbs the two
horizontal pixel coordinates with Gaussian noise of variance ``Q_f``
(seeds/002, section 3) and triangulates them back.  The projection here is
written from the pinhole model (``y_l = C + f y / x``, disparity ``f B / x``)
rather than from the plugin's code.
"""

from __future__ import annotations

import math
import types
from collections.abc import Callable

import numpy as np
import pytest

from benchmark.modalities.stereo.model import (
    ChaseNavigation,
    StereoCalibration,
    StereoMeasurement,
    StereoTruth,
    TargetEstimate,
)
from benchmark.model import Frame, SequenceInfo

CALIBRATION = StereoCalibration(
    focal_px=16.9 / 0.12,
    baseline_m=0.12,
    principal_left_px=159.5,
    principal_right_px=159.5,
    width_px=320,
    range_limit_m=16.0,
    correlation_accuracy_px=0.11,
)
INTERVAL_S = 0.2
PIXEL_VARIANCE = 0.11**2 / 2.0


def info(n_frames: int, name: str = "synthetic/chase") -> SequenceInfo:
    """A stereo SequenceInfo with the Table 4 camera and T = 0.2 s."""
    return SequenceInfo(name, "stereo", n_frames=n_frames, frame_interval_s=INTERVAL_S, calibration=CALIBRATION)


def project(relative: np.ndarray) -> tuple[float, float]:
    """Ideal ``(y_l, y_r)`` of a point ``(x ahead, y starboard)`` in the camera frame."""
    x, y = relative
    left = CALIBRATION.principal_left_px + CALIBRATION.focal_px * y / x
    disparity = CALIBRATION.focal_px * CALIBRATION.baseline_m / x
    return left, left - disparity


def measure(left: float, right: float) -> StereoMeasurement:
    """Triangulate a pixel pair with the equal principal points of :data:`CALIBRATION`."""
    disparity = left - right
    x = CALIBRATION.focal_px * CALIBRATION.baseline_m / disparity
    y = CALIBRATION.baseline_m * (left - CALIBRATION.principal_left_px) / disparity
    return StereoMeasurement(left, right, (x, y))


def chase(
    n_frames: int,
    target: Callable[[float], tuple[np.ndarray, np.ndarray]],
    chaser: Callable[[float], tuple[np.ndarray, float]],
    seed: int = 0,
    pixel_std: float = math.sqrt(PIXEL_VARIANCE),
    gps_std: float = 0.0,
    compass_std_deg: float = 0.0,
    lost: Callable[[int], bool] = lambda index: False,
) -> list[Frame]:
    """Frames of a chase: ``target(t) -> (position, velocity)``, ``chaser(t) -> (position, heading)``.

    CH's navigation adds white noise of ``gps_std`` m per axis and
    ``compass_std_deg`` to the true pose; frames where ``lost(index)`` have
    no measurement.
    """
    rng = np.random.default_rng(seed)
    frames = []
    for index in range(n_frames):
        t = index * INTERVAL_S
        tg_position, tg_velocity = target(t)
        ch_position, heading = chaser(t)
        c, s = math.cos(heading), math.sin(heading)
        offset = tg_position - ch_position
        relative = np.array([c * offset[0] + s * offset[1], -s * offset[0] + c * offset[1]])
        left, right = project(relative)
        left, right = left + rng.normal(0.0, pixel_std), right + rng.normal(0.0, pixel_std)
        observation = None if lost(index) or left - right <= 0.0 else measure(left, right)
        gps = ch_position + rng.normal(0.0, gps_std, 2)
        compass = heading + math.radians(rng.normal(0.0, compass_std_deg))
        truth = StereoTruth(TargetEstimate(tuple(tg_position), tuple(tg_velocity)), tuple(ch_position), heading)
        frames.append(Frame(index, observation, truth, ChaseNavigation(tuple(gps), compass), t))
    return frames


def straight_chase(n_frames: int = 300, seed: int = 0, **kwargs) -> list[Frame]:
    """CH at 3 m/s on heading 30 deg; TG 6 m ahead and 1 m abeam at 3.25 m/s, drifting to 21 m after 60 s."""
    heading = math.radians(30.0)
    direction = np.array([math.cos(heading), math.sin(heading)])
    abeam = np.array([-direction[1], direction[0]])

    def chaser(t: float) -> tuple[np.ndarray, float]:
        return direction * 3.0 * t, heading

    def target(t: float) -> tuple[np.ndarray, np.ndarray]:
        return direction * (6.0 + 3.25 * t) + abeam * 1.0, direction * 3.25

    return chase(n_frames, target, chaser, seed=seed, **kwargs)


def run(tracker, frames: list[Frame], init=None) -> list:
    """Reset ``tracker`` on the frames' sequence and step through them."""
    tracker.reset(info(len(frames)), np.random.default_rng(0), init=init)
    return [tracker.step(frame) for frame in frames]


def errors(estimates: list, frames: list[Frame]) -> dict[str, np.ndarray]:
    """Per-frame position, speed and heading errors (nan where nothing was reported)."""
    out = {"position": [], "speed": [], "heading": []}
    for estimate, frame in zip(estimates, frames, strict=True):
        true = frame.truth.target
        if estimate is None:
            for values in out.values():
                values.append(math.nan)
            continue
        out["position"].append(math.dist(estimate.position_m, true.position_m))
        out["speed"].append(estimate.speed_mps - true.speed_mps)
        out["heading"].append(math.degrees(math.remainder(estimate.heading - true.heading, 2 * math.pi)))
    return {key: np.array(values) for key, values in out.items()}


def rmse(values: np.ndarray) -> float:
    """Root mean square over the finite values."""
    values = values[np.isfinite(values)]
    return float(np.sqrt(np.mean(values**2)))


@pytest.fixture(scope="session")
def scene() -> types.SimpleNamespace:
    """The helpers of this module."""
    return types.SimpleNamespace(
        CALIBRATION=CALIBRATION,
        INTERVAL_S=INTERVAL_S,
        PIXEL_VARIANCE=PIXEL_VARIANCE,
        info=info,
        project=project,
        measure=measure,
        chase=chase,
        straight_chase=straight_chase,
        run=run,
        errors=errors,
        rmse=rmse,
    )
