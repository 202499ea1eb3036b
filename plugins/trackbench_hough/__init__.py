"""trackbench_hough: the Hough baseline tracker of seeds/000, section 2.1.

The oldest approach to cable tracking the thesis reviews: filter the image
with a Laplacian of Gaussian, keep its strong zero crossings as a binary
edge image, find straight lines with the Hough transform and take the pair
of lines that looks most like two cable borders.  Once the cable is found,
the transform is limited to a window around it (Balasuriya et al.), and
widened again after the cable is lost.

The plugin registers, through the same ``trackbench`` entry-point group
every third-party tracker uses::

    [project.entry-points.trackbench]
    hough = "trackbench_hough"

two trackers, one class (:class:`HoughTracker`) with different parameters:

* ``hough``: the detector with the departures :mod:`trackbench_hough.params`
  argues (an edge threshold and sizes that follow the frame, a weaker
  partner border, a smaller LoG);
* ``hough-paper``: the detector as the benchmark first read section 2.1,
  with fixed thresholds and sizes in pixels of any frame, for comparison.
"""

from benchmark import Registry, hookimpl
from trackbench_hough.params import HoughParams
from trackbench_hough.tracker import HoughTracker

__all__ = ["VARIANTS", "HoughParams", "HoughTracker", "trackbench_register_trackers"]

VARIANTS: dict[str, dict[str, object]] = {
    "hough-paper": {
        "log_sigma": 3.0,
        "edge_rule": "step",
        "reference_side_px": None,
        "vote_fraction": 0.3,
        "partner_fraction": 0.3,
        "max_width_px": 100.0,
    },
}
"""Registered variants of :class:`HoughTracker` and their parameter overrides."""


@hookimpl
def trackbench_register_trackers(registry: Registry) -> None:
    """Register the Hough baseline and its variants."""
    registry.add_tracker(HoughTracker)
    for name, params in VARIANTS.items():
        registry.add_tracker(HoughTracker, name=name, params=params)
