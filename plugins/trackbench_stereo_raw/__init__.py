"""trackbench_stereo_raw: the raw stereovision baseline of seeds/002.

Positions straight from triangulation and the chase boat's navigation, and
speed and heading from the moving average of their changes: the "Raw" rows
of seeds/002, Tables 6-8, against which the ``stereo_ekf`` filter is
measured.  It reads the ``stereo`` suite's measurements and the
``stereo-images`` suite's image pairs alike, measuring a pair with the
stereo modality's front end (:mod:`benchmark.modalities.stereo.frontend`
through :mod:`benchmark.modalities.stereo.observation`), as ``stereo_ekf``
does.  Registered as ``stereo_raw`` through the ``trackbench`` entry-point
group::

    [project.entry-points.trackbench]
    stereo_raw = "trackbench_stereo_raw"
"""

from benchmark import Registry, hookimpl
from trackbench_stereo_raw.tracker import StereoRawParams, StereoRawTracker

__all__ = ["StereoRawParams", "StereoRawTracker", "trackbench_register_trackers"]


@hookimpl
def trackbench_register_trackers(registry: Registry) -> None:
    """Register the raw baseline."""
    registry.add_tracker(StereoRawTracker)
