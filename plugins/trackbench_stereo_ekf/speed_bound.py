"""The speed bounds of the Kalman core the stereo tracker runs on: FilterPy's filters, same model, same steps.

One predict and one update a frame of the target filter of seeds/002: the
state ``[X, Y, X_dot, Y_dot]`` moved by eq. (5)-(6) with its known input
``B a`` and the process noise of eq. (9), measured by eq. (11), the
target's position seen from the moving, turning chase boat, with the
Jacobian of eq. (12) (:mod:`trackbench_stereo_ekf.motion`,
:mod:`trackbench_stereo_ekf.measurement`, the tracker's default
parameters).  The measurement of each frame is the truth seen through
eq. (11), worked out once per frame and shared by both sides, so that only
the filters are timed.

* ``EKF predict+update``: the stereo tracker's own filter step,
  :meth:`trackbench_stereo_ekf.target_filter.TargetFilter.advance` (one
  compiled call a frame that evaluates ``h`` and ``H`` itself, corrects and
  predicts the next frame), given each frame's measurement, CH's navigation
  and ``Q`` as the tracker gives them (:func:`~trackbench_stereo_ekf.target_filter.measurement_inputs`),
  against FilterPy's ``ExtendedKalmanFilter`` given ``h`` and its Jacobian
  as Python functions, as a user of FilterPy writes them (issue 34: at
  least 10 times faster);
* ``KF predict+update``: :func:`benchmark.filters.kalman.predict` and
  :func:`~benchmark.filters.kalman.update`, the Kalman core other trackers
  use, with the measurement made linear (``H x`` of the truth measured by
  the matrix ``H``), against FilterPy's ``KalmanFilter``; shown for
  information.

FilterPy is in the ``test`` extra; without it the rows say so.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np

from benchmark import hookimpl
from benchmark.filters.kalman import Gaussian, predict, update
from benchmark.modalities.stereo.model import ChaseNavigation
from benchmark.model import Frame, SequenceInfo
from benchmark.speed.bounds import BoundContext, BoundUnavailable, PerFrame, SpeedBound, SpeedBounds, TimesFaster
from trackbench_stereo_ekf.measurement import observation_jacobian, observe
from trackbench_stereo_ekf.motion import control_vector, process_noise, transition_matrix
from trackbench_stereo_ekf.target_filter import TargetFilter, measurement_inputs
from trackbench_stereo_ekf.tracker import StereoEkfParams

DATASET = "stereo/case2-medium"
"""The sequence timed: the target weaving about the chase boat's line (seeds/002, case 2)."""
MEASUREMENT_STD_M = (0.5, 0.1)
"""Standard deviations of the measured ``(x_v, y_v)``, m: the order of eq. (20)'s at a range of 10 m."""
START_COVARIANCE = np.diag([4.0, 4.0, 1.0, 1.0])
"""The belief's covariance at the first frame's truth."""

Step = tuple[np.ndarray, Callable[[np.ndarray], np.ndarray], np.ndarray, np.ndarray, np.ndarray]
"""A frame's ``z`` (eq. 11 of the truth), ``h``, ``H`` (eq. 12), the linear measurement ``H x`` of the truth,
and the inputs of the tracker's filter step (``z``, CH's navigation and ``Q``)."""


class FilterSteps:
    """The filter model of the tracker's defaults, and each frame's measurement worked out once."""

    def __init__(self) -> None:
        params = StereoEkfParams()
        self.interval = 0.0
        self.sigma_a = float(params.sigma_a_mps2)
        self.acceleration = float(params.control_acceleration_mps2)
        self.noise = np.diag(np.square(MEASUREMENT_STD_M))
        self.of: PerFrame[Step] = PerFrame(self._step)
        self.start = np.zeros(4)

    def reset(self, info: SequenceInfo, init: Any) -> None:
        self.interval = float(info.frame_interval_s or 0.2)
        self.transition = transition_matrix(self.interval)
        self.control_matrix = control_vector(self.interval).reshape(4, 1)
        self.control = self.control_matrix.ravel() * self.acceleration
        self.process = process_noise(self.interval, self.sigma_a)
        self.start = _truth_state(init)

    def _step(self, frame: Frame) -> Step:
        truth = frame.truth
        navigation = ChaseNavigation(tuple(truth.chase_position_m), float(truth.chase_heading))
        state = _truth_state(truth)
        H = observation_jacobian(navigation)
        z = observe(state, navigation)
        return z, lambda x: observe(x, navigation), H, H @ state, measurement_inputs(z, navigation, self.noise)


def _truth_state(truth: Any) -> np.ndarray:
    target = truth.target
    return np.array([*target.position_m, *target.velocity_mps], dtype=float)


class OursExtended:
    """The stereo tracker's :class:`~trackbench_stereo_ekf.target_filter.TargetFilter`, its model compiled.

    Its reset predicts the first frame (as FilterPy's first ``predict``
    does); each step then corrects it and predicts the next, one predict
    and one update a frame as on FilterPy's side.
    """

    def __init__(self, context: BoundContext) -> None:
        self.model = FilterSteps()
        self.filter: TargetFilter | None = None

    def reset(self, info: SequenceInfo, rng: np.random.Generator, init: Any = None) -> None:
        m = self.model
        m.reset(info, init)
        self.filter = TargetFilter(m.interval, m.acceleration, m.sigma_a)
        self.filter.start(Gaussian(m.start, START_COVARIANCE))
        self.filter.predict()

    def step(self, frame: Frame) -> np.ndarray:
        self.filter.advance(self.model.of(frame)[4])
        return self.filter.mean


class OursLinear:
    """:mod:`benchmark.filters.kalman`, ``H`` a matrix."""

    def __init__(self, context: BoundContext) -> None:
        self.model = FilterSteps()
        self.belief: Gaussian | None = None

    def reset(self, info: SequenceInfo, rng: np.random.Generator, init: Any = None) -> None:
        self.model.reset(info, init)
        self.belief = Gaussian(self.model.start, START_COVARIANCE)

    def step(self, frame: Frame) -> Gaussian:
        m = self.model
        _, _, H, z_linear, _ = m.of(frame)
        belief = predict(self.belief, m.transition, None, m.process, control=m.control)
        self.belief = update(belief, z_linear, H, None, m.noise)
        return self.belief


class FilterPyExtended:
    """FilterPy's ``ExtendedKalmanFilter`` on the same model and measurements."""

    def __init__(self, context: BoundContext) -> None:
        try:
            from filterpy.kalman import ExtendedKalmanFilter
        except ImportError as exc:
            raise BoundUnavailable("FilterPy is not installed (pip install subsea-trackbench[test])") from exc
        self.make = lambda: ExtendedKalmanFilter(dim_x=4, dim_z=2, dim_u=1)
        self.model = FilterSteps()
        self.jacobians: dict[int, Callable[[np.ndarray], np.ndarray]] = {}
        self.filter: Any = None
        self.u = np.zeros(1)

    def reset(self, info: SequenceInfo, rng: np.random.Generator, init: Any = None) -> None:
        m = self.model
        m.reset(info, init)
        self.filter = self.make()
        self.filter.x, self.filter.P = m.start.copy(), START_COVARIANCE.copy()
        self.filter.F, self.filter.B, self.filter.Q = m.transition, m.control_matrix, m.process
        self.u = np.array([m.acceleration])

    def step(self, frame: Frame) -> np.ndarray:
        z, h, H, _, _ = self.model.of(frame)
        jacobian = self.jacobians.setdefault(frame.index, lambda x, H=H: H)
        self.filter.predict(u=self.u)
        self.filter.update(z, jacobian, h, R=self.model.noise)
        return self.filter.x


class FilterPyLinear(FilterPyExtended):
    """FilterPy's ``KalmanFilter`` on the same model and measurements."""

    def __init__(self, context: BoundContext) -> None:
        super().__init__(context)
        from filterpy.kalman import KalmanFilter

        self.make = lambda: KalmanFilter(dim_x=4, dim_z=2, dim_u=1)

    def step(self, frame: Frame) -> np.ndarray:
        _, _, H, z_linear, _ = self.model.of(frame)
        self.filter.predict(u=self.u)
        self.filter.update(z_linear, R=self.model.noise, H=H)
        return self.filter.x


@hookimpl
def trackbench_register_speed_bounds(registry: SpeedBounds) -> None:
    """The Kalman core's predict + update against FilterPy's EKF (goal) and KF (for information)."""
    registry.add_bound(
        SpeedBound(
            "EKF predict+update",
            "FilterPy ExtendedKalmanFilter",
            FilterPyExtended,
            DATASET,
            TimesFaster(10),
            ours=OursExtended,
        )
    )
    registry.add_bound(
        SpeedBound("KF predict+update", "FilterPy KalmanFilter", FilterPyLinear, DATASET, ours=OursLinear)
    )
