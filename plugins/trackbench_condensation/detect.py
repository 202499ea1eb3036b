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
3. the strongest pairs become cable states ``(d, alpha, w, 0)``;
4. each is refined by a local ascent of eq. (4.11) over ``(d, alpha, w,
   beta)`` (:class:`LocalAscent`), so that a candidate is judged, and its
   particles drawn, at its own best skew and not at the scan's ``beta = 0``.
   The tracker compares candidates with the eq. (4.11) score of its skewed
   estimate; without the ascent a parallel pair loses 35-45 % of its score
   against a cable of ``beta`` 1.6-1.8 deg, and the true cable can lose the
   comparison to a wrong state that the filter already holds.

:func:`propose` draws particles around them.  Proposed particles are not
importance-weighted against the movement model: like the injected samples
of augmented Monte Carlo localisation they compete with the tracked
particles only through their eq. (4.11) weights, so a proposal survives
when its evidence beats that of the tracked cable.  When to scan, and which
candidates to propose, the tracker decides (:mod:`trackbench_condensation.tracker`).
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from benchmark.lazy import lazy_module
from trackbench_condensation.observation import ImageScore, as_grey_image

# The numba kernels load on the first frame, so that listing the trackers does not import numba.
measure = lazy_module("trackbench_condensation.measure")


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
        responses = measure.line_scores(image, taps, float(spacing), alphas, offsets)
        pairs, values = measure.best_pairs(
            responses, offsets, float(self.width_range_px[0]), float(self.width_range_px[1]), int(self.pairs_per_angle)
        )
        order = np.argsort(-values, kind="stable")[:count]
        pairs, values = pairs[order], values[order]
        left, right = offsets[pairs[:, 1]], offsets[pairs[:, 2]]
        states = np.column_stack([0.5 * (left + right), alphas[pairs[:, 0]], right - left, np.zeros(len(pairs))])
        return states, values


@dataclass(frozen=True)
class LocalAscent:
    """A compass search of the eq. (4.11) score around candidate cables.

    From each state, the eight moves of ``+-step`` along one of ``d``,
    ``alpha``, ``w`` and ``beta`` are scored; the best one is taken if it
    scores higher, otherwise the candidate's steps are halved, until they
    are ``1 / 2**halvings`` of the first ones.  All candidates move in one
    vectorised score call per round.

    Parameters
    ----------
    first_steps : tuple of float
        First steps of ``(d, alpha, w, beta)``: px, deg, px, deg.
    halvings : int
        How often the steps are halved before a candidate stops.
    max_rounds : int
        Upper bound on the rounds.
    """

    first_steps: tuple[float, float, float, float] = (2.0, 1.0, 2.0, 0.5)
    halvings: int = 3
    max_rounds: int = 40

    @functools.cached_property
    def _first_steps(self) -> tuple[np.ndarray, float]:
        """The first steps of ``(d, alpha, w, beta)`` in px and rad, and the ``d`` step at which a candidate stops."""
        first = np.array(self.first_steps, dtype=float)
        first[[1, 3]] = np.radians(first[[1, 3]])
        return first, first[0] / 2.0**self.halvings

    def refine(
        self,
        states: np.ndarray,
        score: Callable[[np.ndarray], np.ndarray],
        low: np.ndarray,
        high: np.ndarray,
    ) -> tuple[np.ndarray, np.ndarray]:
        """Move each ``(d, alpha, w, beta)`` state uphill on ``score`` within ``[low, high]``.

        Parameters
        ----------
        states : numpy.ndarray
            ``(K, 4)`` starting states, px and rad.
        score : callable
            ``(N, 4)`` states to ``(N,)`` scores, higher better (eq. 4.11).
            An :class:`~trackbench_condensation.observation.ImageScore` runs
            the whole search in one compiled call
            (:func:`~trackbench_condensation.measure.compass_ascent`), with
            the same result bit for bit.
        low, high : numpy.ndarray
            ``(4,)`` bounds of the states (``-inf`` / ``inf`` for none).

        Returns
        -------
        states : numpy.ndarray
            ``(K, 4)`` refined states; none scores lower than where it started.
        scores : numpy.ndarray
            ``(K,)`` their scores.

        References
        ----------
        seeds/000, section 4.5, eq. (4.11).
        """
        first, smallest = self._first_steps
        if isinstance(score, ImageScore):
            starts = np.array(states, dtype=float).reshape(-1, 4)
            low, high = np.asarray(low, dtype=float), np.asarray(high, dtype=float)
            return score.ascend(starts, low, high, first, smallest, self.max_rounds)
        current = np.clip(np.array(states, dtype=float).reshape(-1, 4), low, high)
        values = np.asarray(score(current), dtype=float)
        count = len(current)
        if count == 0:
            return current, values
        steps = np.tile(first, (count, 1))
        moves = np.concatenate([np.eye(4), -np.eye(4)])
        rows = np.arange(count)
        for _ in range(self.max_rounds):
            active = steps[:, 0] >= smallest
            if not active.any():
                break
            trial = np.clip(current[:, None, :] + moves[None, :, :] * steps[:, None, :], low, high)
            trial_values = np.asarray(score(trial.reshape(-1, 4)), dtype=float).reshape(count, len(moves))
            best = np.argmax(trial_values, axis=1)
            improved = active & (trial_values[rows, best] > values)
            current[improved] = trial[rows[improved], best[improved]]
            values[improved] = trial_values[rows[improved], best[improved]]
            steps[active & ~improved] *= 0.5
        return current, values


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
