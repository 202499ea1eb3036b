"""The ``sonar_detector`` baseline: each ping's most likely pipe position on its own.

seeds/003 measures its detector scan by scan: "the detector matched the
actual position of the pipe with the most likely pipe position in over 75%
of scans" (section 4.1; over 90 % on the concrete section, section 4.2).
This tracker reports exactly that, the position of the largest value of the
likelihood scan of eq. (1) (:mod:`trackbench_sonar.detection`; between grid
points by a parabola through the maximum and its neighbours unless
``refine_peak`` is off), with no memory from ping to ping, so that the leaderboard shows what the particle
filter ``sonar_pf`` adds.  A ping whose scan is empty (too few returns) or
zero everywhere (no cross-section fits anywhere) reports no detection.  The
detector uses no randomness and ignores ``init``.
"""

from __future__ import annotations

from benchmark.modalities.sonar.model import PipeEstimate, SonarFrame
from trackbench_sonar.detection import ScanTracker
from trackbench_sonar.params import DetectorParams


class SonarDetector(ScanTracker):
    """The most likely pipe position of each scan (argmax of eq. 1).

    References
    ----------
    seeds/003, section 2 (eq. 1, Figs. 1-2) and section 4.
    """

    name = "sonar_detector"
    version = "2.0"
    deterministic = True
    Params = DetectorParams

    def step(self, frame: SonarFrame) -> PipeEstimate | None:
        """The position of the scan's maximum, or None for an empty or all-zero scan.

        Raises
        ------
        DataError
            If the observation is not a Swath (the message names the frame).
        RuntimeError
            If called before :meth:`reset`.
        """
        _, scan = self.scan(frame)
        peak = scan.peak(refine=bool(self.params.refine_peak))
        return None if peak is None else PipeEstimate(peak)
