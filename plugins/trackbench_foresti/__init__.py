"""trackbench_foresti: the pipeline tracker of seeds/004 (Foresti, visual inspection of sea bottom structures).

Its feature extraction module (section IV: Canny edges, a Hough transform
that keeps each line's modulus and domain, the reliability parameters of
eqs. (5)-(6) and the grouping of candidate lines into the pipeline's two
borders) measures where the borders cross the first and last image rows,
and an extended Kalman filter of the camera pose (section V) tracks them
with the vehicle's inertial speeds.

The plugin registers, through the ``trackbench`` entry-point group every
third-party tracker uses::

    [project.entry-points.trackbench]
    foresti = "trackbench_foresti"

two trackers:

* ``foresti_ekf``: the EKF, reporting the borders its state projects to
  and the camera pose (:mod:`trackbench_foresti.tracker`);
* ``foresti_lines``: the feature extraction module alone, frame by frame
  (:mod:`trackbench_foresti.baseline`), what the filter adds to.
"""

from benchmark import Registry, hookimpl
from trackbench_foresti.baseline import ForestiLinesTracker
from trackbench_foresti.tracker import ForestiEkfTracker, ForestiParams

__all__ = ["ForestiEkfTracker", "ForestiLinesTracker", "ForestiParams", "trackbench_register_trackers"]


@hookimpl
def trackbench_register_trackers(registry: Registry) -> None:
    """Register the Foresti EKF and its feature extractor on its own."""
    registry.add_tracker(ForestiEkfTracker)
    registry.add_tracker(ForestiLinesTracker)
