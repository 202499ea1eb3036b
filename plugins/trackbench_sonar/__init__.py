"""trackbench_sonar: pipe detection and tracking in multibeam echo-sounder swaths (seeds/003).

Tena Ruiz, Petillot and de Saint-Pern detect a pipe in each swath of a
multibeam echo sounder by fitting its known cross-section to every two
consecutive points of the resampled scan and scoring each fit by eq. (1),
which gives a likelihood over across-track position (section 2); a particle
filter then tracks the pipe from scan to scan with that likelihood as its
measurement (section 3).  The modules follow the paper:

* :mod:`~trackbench_sonar.profile`: cleaning and resampling a swath;
* :mod:`~trackbench_sonar.cross_section`: the ellipse through two points;
* :mod:`~trackbench_sonar.likelihood`: eq. (1) as the paper draws it and
  the likelihood scan;
* :mod:`~trackbench_sonar.footprint`: the cross-section as wide beams see it;
* :mod:`~trackbench_sonar.evidence`: eq. (1) for that cross-section, as
  evidence over the local seafloor (the default);
* :mod:`~trackbench_sonar.detection`: from a ping to its scan;
* :mod:`~trackbench_sonar.importance`: the importance density of eq. (3)
  with the injected samples of section 3.4;
* :mod:`~trackbench_sonar.estimate`: peak extraction, eq. (5);
* :mod:`~trackbench_sonar.params`: the parameters and their defaults.

The plugin registers, through the ``trackbench`` entry-point group every
third-party tracker uses::

    [project.entry-points.trackbench]
    sonar = "trackbench_sonar"

two trackers of modality ``sonar`` and their variants as printed:

* ``sonar_detector`` (:mod:`~trackbench_sonar.detector`): the most likely
  position of each scan on its own, as the paper measures its detector;
* ``sonar_pf`` (:mod:`~trackbench_sonar.particle_filter`): the particle
  filter over that likelihood;
* ``sonar_detector-paper`` and ``sonar_pf-paper``: the same with eq. (1)
  as the paper draws it (the ellipse through two points) and, for the
  filter, eqs. (3)-(5) as printed (:data:`PAPER_DETECTOR`,
  :data:`PAPER_FILTER`; why the defaults depart:
  :mod:`~trackbench_sonar.params`).
"""

from benchmark import Registry, hookimpl
from trackbench_sonar.detector import SonarDetector
from trackbench_sonar.params import DetectorParams, ParticleFilterParams
from trackbench_sonar.particle_filter import SonarParticleFilter

__all__ = [
    "PAPER_DETECTOR",
    "PAPER_FILTER",
    "DetectorParams",
    "ParticleFilterParams",
    "SonarDetector",
    "SonarParticleFilter",
    "trackbench_register_trackers",
]


PAPER_DETECTOR = {"likelihood": "ellipse", "spike_heights": 0.5, "refine_peak": False}
"""Parameters that give the detector of seeds/003, section 2: eq. (1) with the ellipse through two points."""

PAPER_FILTER = {
    **PAPER_DETECTOR,
    "weight_exponent": 1.0,
    "weight_floor": 0.0,
    "peak_halfwidth": 0.0,
    "drift_gain": 0.0,
    "inject_fraction": 0.05,
    "lost_ratio": 0.0,
}
"""Parameters that give the filter of seeds/003, section 3 as printed: eqs. (3)-(5), a fixed rate J of injection."""


@hookimpl
def trackbench_register_trackers(registry: Registry) -> None:
    """Register the detector baseline, the particle filter and both as the paper prints them."""
    registry.add_tracker(SonarDetector)
    registry.add_tracker(SonarParticleFilter)
    registry.add_tracker(SonarDetector, name="sonar_detector-paper", params=PAPER_DETECTOR)
    registry.add_tracker(SonarParticleFilter, name="sonar_pf-paper", params=PAPER_FILTER)
