"""trackbench_condensation: the particle-filter cable tracker of seeds/000, chapters 3-5.

A condensation filter (Isard and Blake, as the thesis lays it out in
sections 3.4 and 4.6) tracks the cable state ``(d, alpha, w, beta)`` with
the velocities ``v_d`` and ``v_alpha`` (section 4.4).  Particles drift at
their velocities and diffuse (eq. 4.9); each is weighed by the grey-level
changes a derivative-of-Gaussian filter finds across its two projected
borders (section 4.5, eqs. 4.10-4.11).  The reported state is the weighted
mean of the particles (eq. 3.11), or the peak of eq. (4.11) beside it,
with its borders moved out to the cable's outline.

The plugin registers, through the ``trackbench`` entry-point group every
third-party tracker uses::

    [project.entry-points.trackbench]
    condensation = "trackbench_condensation"

five trackers, one class with different parameters:

* ``condensation``: the thesis' settings (Table 5.1, 500 particles) with the
  departures :mod:`trackbench_condensation.params` documents (sharper
  weights, a larger angle-velocity variance, lost-cable test,
  re-detection, what is reported, a prior on the width, borders reported
  at the cable's outline, and Table 5.2's limits scaled to the frame);
* ``condensation-thesis``: exactly the thesis' tracker, for comparison
  (Table 5.2's limits in pixels as printed, whatever the frame);
* ``condensation-fast``: its high-speed settings, 300 particles and a 5 px
  filter (section 5.2.5, Fig. 5.9);
* ``condensation-8d``: velocities for width and skew as well, the
  eight-dimensional particle section 6.1 proposes;
* ``condensation-centre``: the brighter-centre term section 6.1 proposes,
  added to the border evidence.
"""

from benchmark import Registry, hookimpl
from trackbench_condensation.params import CondensationParams
from trackbench_condensation.tracker import CondensationTracker

__all__ = ["VARIANTS", "CondensationParams", "CondensationTracker", "trackbench_register_trackers"]

VARIANTS: dict[str, dict[str, object]] = {
    "condensation-thesis": {
        "weight_exponent": 1.0,
        "var_v_alpha_deg2": 0.005,
        "redetect_fraction": 0.0,
        "lost_threshold": 0.0,
        "width_prior_spread": 0.0,
        "max_spread_px": 0.0,
        "spread_share": 0.0,
        "report_mode": False,
        "outline_fraction": 0.0,
        "reference_width_px": 0.0,
        "init_w_px": (5.0, 100.0),
    },
    "condensation-fast": {"n_particles": 300, "filter_size_px": 5},
    "condensation-8d": {"width_skew_velocities": True},
    "condensation-centre": {"centre_weight": 1.0},
}
"""Registered variants of :class:`CondensationTracker` and their parameter overrides."""


@hookimpl
def trackbench_register_trackers(registry: Registry) -> None:
    """Register the condensation tracker and its variants."""
    registry.add_tracker(CondensationTracker)
    for name, params in VARIANTS.items():
        registry.add_tracker(CondensationTracker, name=name, params=params)
