"""trackbench_hough: the Hough baseline tracker of seeds/000, section 2.1.

The oldest approach to cable tracking the thesis reviews: filter the image
with a Laplacian of Gaussian, keep its strong zero crossings as a binary
edge image, find straight lines with the Hough transform and take the pair
of lines that looks most like two cable borders.  Once the cable is found,
the transform is limited to a window around it (Balasuriya et al.), and
widened again after the cable is lost.

The plugin registers one tracker, ``hough`` (:class:`HoughTracker`), through
the same ``trackbench`` entry-point group every third-party tracker uses::

    [project.entry-points.trackbench]
    hough = "trackbench_hough"
"""

from benchmark import Registry, hookimpl
from trackbench_hough.tracker import HoughParams, HoughTracker

__all__ = ["HoughParams", "HoughTracker", "trackbench_register_trackers"]


@hookimpl
def trackbench_register_trackers(registry: Registry) -> None:
    """Register the Hough baseline tracker."""
    registry.add_tracker(HoughTracker)
