"""Re-detection: candidate cables from a scan of straight lines, to propose particles.

The thesis' filter only searches near its particles, so once it has lost the
cable (sand over it, seeds/004 Fig. 14) or settled on the wrong pair of
edges (clutter, seeds/000 Fig. 5.2) nothing brings it back.  Section 6.1
proposes "some image processing based cable detection in advance to be
able to limit the initial distribution"; Isard and Blake's ICondensation
draws part of the particles from such a detector on every frame.  Here the
detector is the observation model itself, applied to a grid of lines:

1. every straight line at angles ``alpha`` spaced ``angle_step`` over the
   range of Table 5.2 and offsets every ``offset_step`` px across the image
   is scored like one border (summed derivative-of-Gaussian responses,
   :func:`~trackbench_condensation.measure.line_scores`);
2. at each angle the local extrema of the responses are paired, left line
   first, when their signs are opposite (the test of eq. 4.11) and their
   distance is a plausible width (Table 5.2); a pair scores
   ``|c_l| + |c_r|``, as eq. (4.11) would a parallel cable
   (:func:`~trackbench_condensation.measure.best_pairs`);
3. the strongest pairs become cable states ``(d, alpha, w, 0)``.

:func:`propose` draws particles around them.  Proposed particles are not
importance-weighted against the movement model: like the injected samples
of augmented Monte Carlo localisation they compete with the tracked
particles only through their eq. (4.11) weights, so a proposal survives
when its evidence beats that of the tracked cable.  When to scan, and which
candidates to propose, the tracker decides (:mod:`trackbench_condensation.tracker`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from trackbench_condensation.measure import best_pairs, line_scores
from trackbench_condensation.observation import as_grey_image


@dataclass(frozen=True)
class LineScan:
    """The grid of lines scanned for candidate cables.

    Parameters
    ----------
    alpha_range_deg : tuple of float
        Range of centreline angles, deg (Table 5.2: -45 to 45).
    width_range_px : tuple of float
        Range of cable widths, px (Table 5.2: 5 to 100).
    angle_step_deg : float
        Spacing of the scanned angles, deg.
    offset_step_px : float
        Spacing of the scanned offsets, px.
    pairs_per_angle : int
        Strongest pairs kept at each angle.
    """

    alpha_range_deg: tuple[float, float] = (-45.0, 45.0)
    width_range_px: tuple[float, float] = (5.0, 100.0)
    angle_step_deg: float = 2.0
    offset_step_px: float = 2.0
    pairs_per_angle: int = 3

    def __post_init__(self) -> None:
        if not (self.angle_step_deg > 0 and self.offset_step_px > 0 and self.pairs_per_angle >= 1):
            raise ValueError(f"line scan steps must be positive: {self}")

    def candidates(
        self,
        image: np.ndarray,
        taps: np.ndarray,
        spacing: float,
        count: int,
        around_alpha: float | None = None,
        window_deg: float = 10.0,
    ) -> tuple[np.ndarray, np.ndarray]:
        """The ``count`` strongest candidate cables of an image.

        Parameters
        ----------
        image : numpy.ndarray
            Grey image ``(H, W)``.
        taps : numpy.ndarray
            Filter taps of the observation model.
        spacing : float
            Sample point distance of the observation model, px.
        count : int
            Number of candidates wanted.
        around_alpha : float, optional
            Scan only the angles within ``window_deg`` of this angle (rad),
            clipped to the range; the whole range when None.
        window_deg : float
            Half-width of that window, deg.

        Returns
        -------
        states : numpy.ndarray
            ``(K, 4)`` states ``(d, alpha, w, 0)``, ``K <= count``, strongest first.
        scores : numpy.ndarray
            ``(K,)`` their pair scores (eq. 4.11 of a parallel cable), grey levels.

        References
        ----------
        seeds/000, eq. (4.11), Table 5.2 and section 6.1.
        """
        image = as_grey_image(image)
        height, width = image.shape
        low, high = (math.radians(v) for v in self.alpha_range_deg)
        step = math.radians(self.angle_step_deg)
        alphas = np.arange(low, high + 1e-9, step)
        if around_alpha is not None:
            window = math.radians(window_deg) + 1e-9
            alphas = alphas[np.abs(alphas - around_alpha) <= window]
            if alphas.size == 0:
                return np.zeros((0, 4)), np.zeros(0)
        reach = 0.5 * math.hypot(width, height)
        offsets = np.arange(-reach, reach + 1e-9, self.offset_step_px)
        responses = line_scores(image, taps, float(spacing), alphas, offsets)
        pairs, values = best_pairs(
            responses, offsets, float(self.width_range_px[0]), float(self.width_range_px[1]), int(self.pairs_per_angle)
        )
        order = np.argsort(-values, kind="stable")[:count]
        pairs, values = pairs[order], values[order]
        left, right = offsets[pairs[:, 1]], offsets[pairs[:, 2]]
        states = np.column_stack([0.5 * (left + right), alphas[pairs[:, 0]], right - left, np.zeros(len(pairs))])
        return states, values


def propose(
    candidates: np.ndarray, n: int, dims: int, spread: np.ndarray, rng: np.random.Generator
) -> np.ndarray:
    """``n`` particles drawn around candidate cable states.

    Parameters
    ----------
    candidates : numpy.ndarray
        ``(K, 4)`` candidate states, ``K >= 1``.
    n : int
        Number of particles.
    dims : int
        Particle dimension; velocities are 0.
    spread : numpy.ndarray
        ``(4,)`` standard deviations of the Gaussian jitter of
        ``(d, alpha, w, beta)``, px and rad.
    rng : numpy.random.Generator
        Source of the candidate choice and the jitter.

    Returns
    -------
    numpy.ndarray
        ``(n, dims)`` states: each a uniformly chosen candidate plus jitter.
    """
    chosen = candidates[rng.integers(0, len(candidates), size=n)]
    states = np.zeros((n, dims))
    states[:, :4] = chosen + rng.standard_normal((n, 4)) * spread
    return states
