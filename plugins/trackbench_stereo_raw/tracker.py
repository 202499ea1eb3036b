"""The raw stereovision baseline of seeds/002, Tables 6-8.

The paper compares its EKF against what the stereo camera gives without
filtering: the target's position straight from triangulation and CH's
navigation (eq. 10), and its speed and heading from the changes of those
raw positions smoothed by a moving average (sections 3.3-3.4; 15 samples,
section 4).  Each frame with a measurement reports

* the position of eq. (10), unsmoothed, as Tables 6-8's "Position Raw";
* the velocity of :class:`trackbench_stereo_raw.smoothing.VelocitySmoother`,
  from which the leaderboard takes speed and heading.

A frame without a measurement, or whose measurement is not a finite point
ahead of the camera (disparity not positive), reports nothing: the raw
baseline has no model to bridge the gap.  The first measurement of a
sequence reports nothing either, as no velocity exists before a second
position; a zero velocity would fabricate a heading.  The baseline ignores
``init`` and uses no randomness.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from benchmark.errors import DataError, ParameterError
from benchmark.model import ChaseNavigation, Frame, SequenceInfo, StereoMeasurement, TargetEstimate
from benchmark.tracker import Tracker
from trackbench_stereo_raw.smoothing import VelocitySmoother


def to_north_east(relative_m: np.ndarray, navigation: ChaseNavigation) -> np.ndarray:
    """The target's North-East position from its position relative to CH, eq. (10).

    Parameters
    ----------
    relative_m : array_like
        ``(x_v, y_v)``: ahead and to starboard of CH, m.
    navigation : ChaseNavigation
        CH's GPS position and heading (clockwise from north).

    Returns
    -------
    numpy.ndarray
        ``[X, Y]``, m.

    References
    ----------
    seeds/002, eq. (10).
    """
    x_v, y_v = np.asarray(relative_m, dtype=float)
    c, s = math.cos(navigation.heading), math.sin(navigation.heading)
    north, east = navigation.position_m
    return np.array([c * x_v - s * y_v + north, s * x_v + c * y_v + east])


@dataclass(frozen=True)
class StereoRawParams:
    """Parameters of the raw baseline (seeds/002, section 4)."""

    window: int = 15
    """Samples of the moving average smoothing speed and heading (seeds/002, section 4, Figs. 14-15)."""


class StereoRawTracker(Tracker):
    """Triangulated positions, and moving-average speed and heading, without a filter.

    References
    ----------
    seeds/002, eq. (10), sections 3.3-3.5 and Tables 6-8 ("Raw" rows).
    """

    name = "stereo_raw"
    version = "1.0"
    modality = "stereo"
    Params = StereoRawParams

    def __init__(self, params: StereoRawParams | None = None) -> None:
        super().__init__(params)
        if self.params.window < 1:
            raise ParameterError(
                f"tracker {self.name!r}: parameter 'window' must be at least 1, not {self.params.window}"
            )
        self._info: SequenceInfo | None = None
        self._smoother = VelocitySmoother(self.params.window)

    def reset(self, info: SequenceInfo, rng: np.random.Generator, init: Any = None) -> None:
        """Start a sequence; ``rng`` and ``init`` are not used.

        Raises
        ------
        DataError
            If the sequence has no positive ``frame_interval_s``.
        """
        if info.frame_interval_s is None or not info.frame_interval_s > 0.0:
            raise DataError(f"sequence {info.name!r}: frame_interval_s must be positive, not {info.frame_interval_s}")
        self._info = info
        self._smoother = VelocitySmoother(self.params.window)

    def step(self, frame: Frame) -> TargetEstimate | None:
        """The raw position and the smoothed velocity, or None without a usable measurement."""
        info = self._info
        if info is None:
            raise RuntimeError("reset must be called before step")
        observation = frame.observation
        if observation is None:
            return None
        if not isinstance(observation, StereoMeasurement):
            raise DataError(
                f"sequence {info.name!r}, frame {frame.index}: expected a StereoMeasurement or None, "
                f"got {type(observation).__name__}"
            )
        if not isinstance(frame.navigation, ChaseNavigation):
            raise DataError(
                f"sequence {info.name!r}, frame {frame.index}: a measurement needs the chase boat's "
                f"ChaseNavigation, got {type(frame.navigation).__name__}"
            )
        relative = np.asarray(observation.relative_m, dtype=float)
        if not (np.all(np.isfinite(relative)) and relative[0] > 0.0):
            return None
        position = to_north_east(relative, frame.navigation)
        velocity = self._smoother.add(frame.index * info.frame_interval_s, position)
        if velocity is None:
            return None
        return TargetEstimate((float(position[0]), float(position[1])), (float(velocity[0]), float(velocity[1])))
