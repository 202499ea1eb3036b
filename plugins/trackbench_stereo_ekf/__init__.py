"""trackbench_stereo_ekf: the stereovision target EKF of seeds/002.

A chase boat follows a target boat with a stereo camera; an extended Kalman
filter on the target's North-East position and velocity combines the
camera's relative measurement, the chase boat's GPS and heading, and a
nearly-constant-velocity motion model (seeds/002, sections 2-3).  The
stereo geometry (eqs. 10-12, 15, 17) is :mod:`benchmark.modalities.stereo.geometry`.

Frames carry either the stereo front end's measurement (the ``stereo``
suite) or the camera's image pair (the ``stereo-images`` suite); a pair is
measured by the field system's front end, :mod:`benchmark.modalities.stereo.frontend`
(colour tracker and block-matching disparity, section 4.1), through
:mod:`benchmark.modalities.stereo.observation`, whose settings every tracker
here takes as ``frontend_*`` parameters.  Both modules belong to the stereo
modality, so the raw baseline uses them without importing this plugin.

The plugin registers three trackers through the ``trackbench`` entry-point
group:

* ``stereo_ekf``: the modified measurement covariance of eq. (20), which
  the paper keeps after section 3.1, evaluated at the predicted target and
  with CH's navigation errors added (see :mod:`trackbench_stereo_ekf.tracker`);
* ``stereo_ekf-paper``: the same filter exactly as printed: eq. (20) at the
  measured pixel coordinates, navigation errors left out;
* ``stereo_ekf-eq18``: the full covariance of eq. (18) as printed, the
  filter of the paper's Fig. 7(b), which over-corrects::

    [project.entry-points.trackbench]
    stereo_ekf = "trackbench_stereo_ekf"
"""

from benchmark import Registry, hookimpl
from trackbench_stereo_ekf.tracker import StereoEkfParams, StereoEkfTracker

__all__ = ["PAPER", "StereoEkfParams", "StereoEkfTracker", "trackbench_register_trackers"]

PAPER = {"noise_at": "measurement", "gps_std_m": 0.0, "compass_std_deg": 0.0}
"""Parameters that turn the default filter into seeds/002's as printed (Table 5, eq. 20)."""


@hookimpl
def trackbench_register_trackers(registry: Registry) -> None:
    """Register the EKF, the EKF as printed in seeds/002, and the EKF with the full covariance of eq. (18)."""
    registry.add_tracker(StereoEkfTracker)
    registry.add_tracker(StereoEkfTracker, name="stereo_ekf-paper", params=PAPER)
    registry.add_tracker(StereoEkfTracker, name="stereo_ekf-eq18", params={**PAPER, "covariance": "eq18"})
