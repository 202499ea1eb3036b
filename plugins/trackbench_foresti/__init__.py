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

four trackers:

* ``foresti_ekf``: the EKF, reporting the borders its state projects to
  and the camera pose (:mod:`trackbench_foresti.tracker`);
* ``foresti_lines``: the feature extraction module alone, frame by frame
  (:mod:`trackbench_foresti.baseline`), what the filter adds to;
* ``foresti_ekf-paper`` and ``foresti_lines-paper``: the same with the
  fixed image thresholds of the paper's reading (Canny's pair on every
  frame, pixel counts whatever the frame size, the most reliable pair),
  as they were before the defaults were re-chosen on the camera world
  (:mod:`trackbench_foresti.params`).
"""

from benchmark import Registry, hookimpl
from trackbench_foresti.baseline import ForestiLinesTracker
from trackbench_foresti.params import FeatureParams, ForestiParams
from trackbench_foresti.tracker import ForestiEkfTracker

__all__ = [
    "PAPER",
    "FeatureParams",
    "ForestiEkfTracker",
    "ForestiLinesTracker",
    "ForestiParams",
    "trackbench_register_trackers",
]

PAPER: dict[str, object] = {
    "blur_sigma_px": 1.5,
    "canny_rule": "fixed",
    "phase_tolerance_deg": 5.0,
    "domain_tolerance_px": 1.5,
    "reference_rows": 0.0,
    "nest_slack": 0.0,
}
"""The feature extractor's fixed image thresholds: the overrides of the ``-paper`` variants."""


@hookimpl
def trackbench_register_trackers(registry: Registry) -> None:
    """Register the Foresti EKF and its feature extractor on its own, each with its ``-paper`` variant."""
    for tracker in (ForestiEkfTracker, ForestiLinesTracker):
        registry.add_tracker(tracker)
        registry.add_tracker(tracker, name=f"{tracker.name}-paper", params=PAPER)
