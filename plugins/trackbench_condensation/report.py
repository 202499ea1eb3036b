"""What the tracker reports for a frame the lost test let through.

The thesis reports the weighted mean of the particles, eq. (3.11).  The mean
is the best estimate of a posterior with one peak; in clutter the particles
often hold a second group on an algae edge, or spread along a border the
clutter blurs, and the mean then lies between the groups, on no pair of
edges.  Two rules, taken after the lost test
(:mod:`trackbench_condensation.lost`), make the reported state honest:

1. **Too wide to say.**  When half the central 68 % interval of the
   particles' ``d`` (the ``0.16`` to ``0.84`` weighted quantiles: one standard
   deviation for a Gaussian) exceeds ``max_spread_px``, the particles do not
   agree on where the cable is to within the 5 px the detection rule
   allows, and the frame is reported as no detection.  Quantiles rather than
   a standard deviation, because re-detection puts a tenth of the particles
   on other candidates every ten frames: those few light particles far off
   would inflate a standard deviation on frames whose bulk is on the cable.
2. **The mode beside the mean.**  A local ascent of eq. (4.11) from the mean
   (:class:`~trackbench_condensation.detect.LocalAscent`) finds the peak the
   mean lies below.  It is reported instead of the mean when it scores at
   least ``mode_gain`` times as much; with the weights raised to the power
   6 (``weight_exponent``) a score 1.2 times higher is a weight 3 times
   higher.  On a soft-edged cable (S5) the peak of eq. (4.11) lies off the
   true cable by a few pixels of width, and a smaller gain traded correct
   frames for false ones there (see :mod:`trackbench_condensation.params`).

Neither rule acts on the particles: the lost test and re-detection judge
the mean, and only the width prior (:mod:`trackbench_condensation.width`)
follows the reported state.  Treating a wide frame as lost
(re-detection over all angles, proposals only above the lost threshold)
dropped the clutter family from 82 to 66 % correct (seeds 0-2).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from benchmark.filters import ParticleSet
from trackbench_condensation.detect import LocalAscent

DISTANCE = 0
"""Column of ``d`` in a particle state ``(d, alpha, w, beta, ...)``."""

CENTRAL_SHARE = 0.68
"""Share of the weight inside the interval whose half-width measures the spread (one sigma of a Gaussian)."""


_CENTRAL_BOUNDS = np.array([(1.0 - CENTRAL_SHARE) / 2.0, 1.0 - (1.0 - CENTRAL_SHARE) / 2.0])
"""The weighted quantiles that bound the central interval."""


def spread_of_distance(particles: ParticleSet) -> float:
    """Half the central 68 % weighted interval of the particles' ``d`` (column 0), px."""
    low, high = particles.quantiles(_CENTRAL_BOUNDS, DISTANCE)
    return float(high - low) / 2.0


@dataclass(frozen=True)
class Report:
    """The two reporting rules of this module.

    Parameters
    ----------
    max_spread_px : float
        Report no cable when :func:`spread_of_distance` exceeds this; 0 turns the rule off.
    mode_gain : float or None
        Report the local maximum of eq. (4.11) above the mean when it scores
        at least this multiple of the mean; None reports the mean (eq. 3.11).
    ascent : LocalAscent
        The search for the local maximum.
    """

    max_spread_px: float
    mode_gain: float | None
    ascent: LocalAscent = field(default_factory=LocalAscent)
    spread_share: float = 0.0

    def spread_limit(self, width: float) -> float:
        """The spread allowed a cable ``width`` px wide: ``max(max_spread_px, spread_share * width)``, px."""
        return max(self.max_spread_px, self.spread_share * width)

    def too_wide(self, particles: ParticleSet, width: float) -> bool:
        """True when the particles disagree on ``d`` by more than :meth:`spread_limit` of ``width`` (rule 1)."""
        return self.max_spread_px > 0 and spread_of_distance(particles) > self.spread_limit(width)

    def state(
        self,
        mean: np.ndarray,
        mean_score: float,
        score: Callable[[np.ndarray], np.ndarray],
        low: np.ndarray,
        high: np.ndarray,
    ) -> np.ndarray:
        """The state to report: the mean ``(d, alpha, w, beta)``, or the peak above it (rule 2).

        Parameters
        ----------
        mean : numpy.ndarray
            ``(4,)`` MMSE estimate, eq. (3.11).
        mean_score : float
            Its eq. (4.11) score.
        score : callable
            ``(N, 4)`` states to ``(N,)`` eq. (4.11) scores.
        low, high : numpy.ndarray
            ``(4,)`` bounds of the ascent.

        References
        ----------
        seeds/000, eqs. (3.11) and (4.11).
        """
        if self.mode_gain is None:
            return mean
        peaks, values = self.ascent.refine(mean[None, :], score, low, high)
        return peaks[0] if values[0] >= self.mode_gain * mean_score else mean
