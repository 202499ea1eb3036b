"""trackbench_sonar: pipe detection and tracking in multibeam echo-sounder swaths (seeds/003).

Tena Ruiz, Petillot and de Saint-Pern detect a pipe in each swath of a
multibeam echo sounder by fitting its known cross-section to every two
consecutive points of the resampled scan and scoring each fit by eq. (1),
which gives a likelihood over across-track position (section 2); a particle
filter then tracks the pipe from scan to scan with that likelihood as its
measurement (section 3).  The modules follow the paper:

* :mod:`~trackbench_sonar.profile`: cleaning and resampling a swath;
* :mod:`~trackbench_sonar.cross_section`: the ellipse through two points;
* :mod:`~trackbench_sonar.likelihood`: eq. (1) and the likelihood scan;
* :mod:`~trackbench_sonar.detection`: from a ping to its scan;
* :mod:`~trackbench_sonar.importance`: the importance density of eq. (3)
  with the injected samples of section 3.4;
* :mod:`~trackbench_sonar.estimate`: peak extraction, eq. (5);
* :mod:`~trackbench_sonar.params`: the parameters and their defaults.

The plugin registers, through the ``trackbench`` entry-point group every
third-party tracker uses::

    [project.entry-points.trackbench]
    sonar = "trackbench_sonar"

two trackers of modality ``sonar``:

* ``sonar_detector`` (:mod:`~trackbench_sonar.detector`): the most likely
  position of each scan on its own, as the paper measures its detector;
* ``sonar_pf`` (:mod:`~trackbench_sonar.particle_filter`): the particle
  filter over that likelihood.
"""

from benchmark import Registry, hookimpl
from trackbench_sonar.detector import SonarDetector
from trackbench_sonar.params import DetectorParams, ParticleFilterParams
from trackbench_sonar.particle_filter import SonarParticleFilter

__all__ = [
    "DetectorParams",
    "ParticleFilterParams",
    "SonarDetector",
    "SonarParticleFilter",
    "trackbench_register_trackers",
]


@hookimpl
def trackbench_register_trackers(registry: Registry) -> None:
    """Register the detector baseline and the particle filter."""
    registry.add_tracker(SonarDetector)
    registry.add_tracker(SonarParticleFilter)
