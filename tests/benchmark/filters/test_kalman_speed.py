"""Speed of the Kalman core against FilterPy's ExtendedKalmanFilter, on the same data in the same run.

Both filters run 1000 predict + update steps of the target filter of
seeds/002: the constant-velocity model of eq. (5) with its known input
``B a``, the process noise of eq. (9) (``T^3 / 2`` off the diagonal), and the
measurement of eq. (11), the target's position in the frame of the moving,
turning chase boat, with the Jacobian of eq. (12) and a measurement noise
that changes from step to step.  Both are handed the same measurement
function objects, so its cost weighs the same on each.  FilterPy keeps its
state as a flat vector here, which its EKF accepts and which spares it any
reshaping around those functions; its Jacobian is a function returning the
step's matrix, ours is the matrix itself.

The two tests share a pytest-benchmark group so that they are reported side
by side; ``extra_info`` carries the steps per second of each and, on the
second of the two, the ratio.  Nothing here asserts on time: each test
checks that its filter reached the same estimate as the other one.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from filterpy.kalman import ExtendedKalmanFilter
from pytest_benchmark.fixture import BenchmarkFixture

from benchmark.filters.kalman import Gaussian, predict, update

STEPS = 1000
T = 0.2
SIGMA_A = 1.5
ACCELERATION = 0.05
GROUP = "kalman: 1000 EKF steps of the seeds/002 stereo target filter"

A = np.array([[1.0, 0.0, T, 0.0], [0.0, 1.0, 0.0, T], [0.0, 0.0, 1.0, 0.0], [0.0, 0.0, 0.0, 1.0]])
B = np.array([[T**2 / 2], [T**2 / 2], [T], [T]])
R = SIGMA_A**2 * np.array(
    [
        [T**4 / 4, 0.0, T**3 / 2, 0.0],
        [0.0, T**4 / 4, 0.0, T**3 / 2],
        [T**3 / 2, 0.0, T**2, 0.0],
        [0.0, T**3 / 2, 0.0, T**2],
    ]
)
X0 = np.array([12.0, 0.0, 3.0, 0.5])
P0 = np.diag([4.0, 4.0, 1.0, 1.0])

_steps_per_s: dict[str, float] = {}


def make_steps(seed: int) -> list[tuple[np.ndarray, Callable[[np.ndarray], np.ndarray], np.ndarray, np.ndarray]]:
    """Per step: ``z``, ``h`` of eq. (11), ``H`` of eq. (12) and the measurement noise."""
    rng = np.random.default_rng(seed)
    target = X0.copy()
    chase = np.zeros(2)
    steps = []
    for k in range(STEPS):
        target = A @ target + B.ravel() * rng.normal(ACCELERATION, 0.3)
        heading = 0.15 * np.sin(0.05 * k)
        chase = chase + T * np.hypot(*target[2:]) * np.array([np.cos(heading), np.sin(heading)])
        c, s = np.cos(heading), np.sin(heading)
        H = np.array([[c, s, 0.0, 0.0], [-s, c, 0.0, 0.0]])
        offset = H[:, :2] @ chase
        depth = max(float(H[0] @ target - offset[0]), 1.0)
        Q = np.diag([(0.1 + 0.004 * depth**2) ** 2, 0.05**2])
        z = H @ target - offset + np.sqrt(np.diag(Q)) * rng.normal(size=2)
        steps.append((z, lambda x, H=H, offset=offset: H @ x - offset, H, Q))
    return steps


STEPS_DATA = make_steps(7)


def run_ours() -> Gaussian:
    control = B.ravel() * ACCELERATION
    belief = Gaussian(X0, P0)
    for z, h, H, Q in STEPS_DATA:
        belief = predict(belief, A, None, R, control=control)
        belief = update(belief, z, h, H, Q)
    return belief


def run_filterpy() -> ExtendedKalmanFilter:
    ekf = ExtendedKalmanFilter(dim_x=4, dim_z=2, dim_u=1)
    ekf.x, ekf.P, ekf.F, ekf.B, ekf.Q = X0.copy(), P0.copy(), A, B, R
    u = np.array([ACCELERATION])
    jacobians = [lambda x, H=H: H for _, _, H, _ in STEPS_DATA]
    for (z, h, _, Q), jacobian in zip(STEPS_DATA, jacobians, strict=True):
        ekf.predict(u=u)
        ekf.update(z, jacobian, h, R=Q)
    return ekf


def record(benchmark: BenchmarkFixture, name: str) -> None:
    """Steps per second from the fastest round, and the ratio once both filters have run."""
    if not benchmark.stats:
        return
    _steps_per_s[name] = STEPS / benchmark.stats.stats.min
    benchmark.extra_info["steps_per_s"] = round(_steps_per_s[name])
    if {"ours", "filterpy"} <= _steps_per_s.keys():
        benchmark.extra_info["speedup_ours_over_filterpy"] = round(_steps_per_s["ours"] / _steps_per_s["filterpy"], 2)


def test_speed_ours(benchmark: BenchmarkFixture) -> None:
    benchmark.group = GROUP
    belief = benchmark.pedantic(run_ours, rounds=10, warmup_rounds=1)
    record(benchmark, "ours")
    reference = run_filterpy()
    np.testing.assert_allclose(belief.mean, reference.x, rtol=1e-9, atol=1e-9)
    np.testing.assert_allclose(belief.covariance, reference.P, rtol=1e-9, atol=1e-12)


def test_speed_filterpy(benchmark: BenchmarkFixture) -> None:
    benchmark.group = GROUP
    ekf = benchmark.pedantic(run_filterpy, rounds=5, warmup_rounds=1)
    record(benchmark, "filterpy")
    reference = run_ours()
    np.testing.assert_allclose(ekf.x, reference.mean, rtol=1e-9, atol=1e-9)
    np.testing.assert_allclose(ekf.P, reference.covariance, rtol=1e-9, atol=1e-12)
