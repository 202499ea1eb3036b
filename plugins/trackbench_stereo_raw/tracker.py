"""The raw stereovision baseline of seeds/002, Tables 6-8.

The paper compares its EKF against what the stereo camera gives without
filtering: the target's position straight from triangulation and CH's
navigation (eq. 10), and its speed and heading from the changes of those
raw positions smoothed by a moving average (sections 3.3-3.4; 15 samples,
section 4).  Each frame with a measurement reports

* the position of eq. (10), unsmoothed, as Tables 6-8's "Position Raw";
* the velocity of :class:`trackbench_stereo_raw.smoothing.VelocitySmoother`,
  from which the leaderboard takes speed and heading.

A frame's observation is a StereoMeasurement (or None), or an image pair
that the stereo modality's front end measures first
(:func:`benchmark.modalities.stereo.observation.read_frame`, settings in the
``frontend_*`` parameters), the same front end the ``stereo_ekf`` filter
uses, so that both trackers see the same measurements; the baseline depends
on nothing of the filter itself.  The geometry of eq. (10) is
:mod:`benchmark.modalities.stereo.geometry`.

A frame without a measurement, or whose measurement is not a finite point
ahead of the camera (disparity not positive), reports nothing: the raw
baseline has no model to bridge the gap.  The first measurement of a
sequence reports nothing either, as no velocity exists before a second
position; a zero velocity would fabricate a heading.  The baseline ignores
``init`` and uses no randomness.
"""

from __future__ import annotations

import math
from typing import Annotated

import numpy as np
import pydantic
from annotated_types import Ge

from benchmark.errors import DataError
from benchmark.modalities.stereo.geometry import to_north_east
from benchmark.modalities.stereo.model import StereoFrame, StereoTruth, TargetEstimate
from benchmark.modalities.stereo.observation import FrontEndSettings, front_end_params, read_frame
from benchmark.model import SequenceInfo
from benchmark.tracker import Tracker
from trackbench_stereo_raw.smoothing import VelocitySmoother


@pydantic.dataclasses.dataclass(frozen=True)
class StereoRawParams(FrontEndSettings):
    """Parameters of the raw baseline (seeds/002, section 4); ``frontend_*`` set the front end for image pairs.

    Each field's type declares its domain; a value outside it is a :class:`pydantic.ValidationError`.
    """

    window: Annotated[int, Ge(1)] = 15
    """Samples of the moving average smoothing speed and heading (seeds/002, section 4, Figs. 14-15)."""


class StereoRawTracker(Tracker[StereoTruth, TargetEstimate]):
    """Triangulated positions, and moving-average speed and heading, without a filter.

    References
    ----------
    seeds/002, eq. (10), sections 3.3-3.5 and Tables 6-8 ("Raw" rows).
    """

    name = "stereo_raw"
    version = "1.1"
    modality = "stereo"
    deterministic = True
    needs = ("calibration", "frame_interval_s")  # the calibration for the front end on image pairs
    Params = StereoRawParams

    def __init__(self, params: StereoRawParams | None = None) -> None:
        super().__init__(params)
        self._front_end = front_end_params(self.params)
        self._info: SequenceInfo | None = None
        self._smoother = VelocitySmoother(self.params.window)

    def reset(self, info: SequenceInfo, rng: np.random.Generator, init: StereoTruth | None = None) -> None:
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

    def step(self, frame: StereoFrame) -> TargetEstimate | None:
        """The raw position and the smoothed velocity, or None without a usable measurement.

        Raises
        ------
        DataError
            If the observation is neither a StereoMeasurement, None nor an
            image pair, or a measurement comes without CH's ChaseNavigation.
        """
        info = self._info
        if info is None:
            raise RuntimeError("reset must be called before step")
        read = read_frame(frame, info, self._front_end)
        if read is None:
            return None
        observation, navigation = read
        ahead, starboard = observation.relative_m
        if not (math.isfinite(ahead) and math.isfinite(starboard) and ahead > 0.0):
            return None
        position = np.array(to_north_east(ahead, starboard, navigation.position_m, navigation.heading))
        velocity = self._smoother.add(frame.index * info.frame_interval_s, position)
        if velocity is None:
            return None
        return TargetEstimate((float(position[0]), float(position[1])), (float(velocity[0]), float(velocity[1])))
