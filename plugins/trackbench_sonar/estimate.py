"""Peak extraction: the filter's estimate from its weighted particles (seeds/003, section 3.3).

Eq. (5) estimates the pipe's position as the weighted mean of all the
particles, ``x_k = sum_i w_k^i x_k^i``.  Under the section's own title,
"peak extraction", that mean is what is wanted only while the particles
form one peak.  They often do not: the samples injected at every update
(section 3.4) are spread over the whole swath, and a second pipe, a spoil
heap or a boulder holds particles of its own.  The mean of two peaks lies
between them, where there is nothing; a few per cent of the weight ten
metres away moves it by decimetres, more than the sonar's resolution.

:func:`peak_mean` therefore applies eq. (5) to the particles of the
heaviest peak: of all windows ``[x_i - h, x_i + h]`` centred on a particle,
the one holding the most weight, and the weighted mean of the particles
inside it.  With ``h`` infinite (or 0, by convention) it is eq. (5) over all
particles.
"""

from __future__ import annotations

import math

import numpy as np

from benchmark.lazy import lazy_module

estimate_kernel = lazy_module("trackbench_sonar.estimate_kernel")


def peak_mean(positions: np.ndarray, weights: np.ndarray, halfwidth: float) -> float:
    """The weighted mean of the particles in the heaviest window of half-width ``halfwidth``.

    Parameters
    ----------
    positions : numpy.ndarray
        Particle positions ``x_k^i``, shape ``(N,)``, finite.
    weights : numpy.ndarray
        Normalised weights ``w_k^i``, shape ``(N,)``.
    halfwidth : float
        ``h``, m; ``0`` or ``inf`` takes all particles (eq. 5 as written).

    Returns
    -------
    float
        ``sum w_i x_i / sum w_i`` over the particles within ``h`` of the
        particle whose window holds the most weight (the first such
        particle from port on a tie).

    References
    ----------
    seeds/003, section 3.3, eq. (5).
    """
    positions = np.asarray(positions, dtype=float)
    weights = np.asarray(weights, dtype=float)
    if halfwidth <= 0.0 or math.isinf(halfwidth):
        return float(weights @ positions / weights.sum())
    window, estimate = estimate_kernel.heaviest_window_mean(positions, weights, float(halfwidth))
    return float(estimate) if window > 0.0 else float(np.mean(positions))
