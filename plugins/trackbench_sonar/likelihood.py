"""The likelihood of a pipe over across-track position: eq. (1) of seeds/003.

For every two consecutive points of the resampled profile
(:mod:`trackbench_sonar.profile`) the detector draws the pipe's
cross-section through them, centre below (:mod:`trackbench_sonar.cross_section`),
and scores the candidate with

    L = L1 + w L2                                                   (eq. 1)

where ``w`` is the paper's "constant weight on L2" and:

* ``L1`` tests how close the model is to the data, from the sum of squared
  differences between the profile and the ellipse over the profile points
  under the upper part of the arc, ``|x - C_x| <= fit_span M_a / 2``.  The
  ends of the span are left out because there the profile is not the pipe:
  where the pipe meets the seabed the sonar's view is cut by shadow and
  undercut, and the profile runs straight from the last return on the pipe
  to the first on the seabed, so whether a grid point near the end falls
  on the pipe or on the seabed depends on where the beams happened to
  fall.  A difference is a point's distance from the ellipse along the ray
  from its centre (:meth:`~trackbench_sonar.cross_section.CrossSection.residual`),
  not its difference in depth, which would grow without bound where the
  arc steepens.  The squared differences are read as Gaussian residuals
  whose variance at a point is ``sigma^2 + (g^2 / (8 rho))^2``: the noise of
  the data, ``sigma``, and the sagitta of the straight line the profile
  draws between two returns ``g`` apart across a pipe whose top has the
  radius of curvature ``rho = (M_a/2)^2 / (M_i/2)``.  Where the beams are
  dense the profile must follow the arc closely; where they are sparse (far
  from nadir, across a gap of missing beams) it cannot, and is not asked
  to.  ``L1 = exp(-mean(d_i^2 / (2 var_i)))``: 1 for a perfect fit,
  ``exp(-1/2)`` when the data scatter about the ellipse as expected.  The
  mean rather than the sum keeps pipes of every size, and spans of every
  number of points, on one scale.
* ``L2`` tests whether the pipe sits proud on the seabed, from the distance
  ``s = z_floor - C_z`` between the candidate's centre and the local seafloor
  returns: ``z_floor`` is the mean of the medians of the profile depths on
  the two flanks just outside the ellipse's span, each ``flank_m`` wide
  (the mean of both sides follows a sloping seabed; a median ignores a
  boulder or a spike on a flank).  Behind an object far from nadir the
  far flank is the straight line the profile draws across the object's
  shadow, which raises the floor and lowers L2 of every object off nadir,
  pipe and clutter alike.  A proud pipe rests on the seabed, so its
  centre is half its height ``M_i / 2`` above the seafloor; ``L2 = max(0,
  1 - |s - M_i/2| / M_i)`` is 1 there, 1/2 for a pipe half buried (centre at
  the seafloor), 0 for a circle fitted to the seafloor itself (centre
  ``M_i/2`` below it) and 0 for an object twice as tall as the pipe.

A candidate is scored only when its whole span lies inside the profile (at
the swath's ends the arc could otherwise be judged on its two defining
points alone) and where the sonar resolves the pipe: its beams must land
close enough at the candidate's centre for ``min_pipe_returns`` intervals
between them to cross the pipe (:func:`benchmark.modalities.sonar.model.beam_footprint`, the sonar's own
spacing; the gap between returns would not do, as a lost beam or the
pipe's own shadow widens it without making the sonar any coarser).  Far
from nadir the beams spread until a pipe falls between two of them; there
the profile is a straight line across it, any ellipse "fits" within the
chords' sagitta, and L1 would be near 1 over metres of bare seabed: a wide
plateau of false evidence that the detector's maximum and the filter's
particles would both be drawn to.  Candidates not scored, and pairs too far
apart for the ellipse, score 0.

The scan (Fig. 2 of the paper) is over the profile's grid: the value at a
grid position is the largest ``L`` of the candidates whose centre ``C_x``
is nearest to it, 0 where no candidate is centred.  Every value is finite
and non-negative.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Protocol

import numpy as np

from benchmark.modalities.sonar.model import beam_footprint
from trackbench_sonar.cross_section import CrossSection
from trackbench_sonar.profile import Profile


class Scan(Protocol):
    """What the trackers read of a likelihood scan: :class:`LikelihoodScan`, or one computed where read.

    :class:`trackbench_sonar.evidence.EvidenceScan` computes its values only
    where they are read; both give the same readings to the last bit.
    """

    positions: np.ndarray

    @property
    def values(self) -> np.ndarray:
        """``L`` at every position."""
        ...

    @property
    def is_empty(self) -> bool:
        """True when the scan has no positions or no positive value."""
        ...

    def maximum(self) -> float:
        """The largest value, 0 for a scan without positions."""
        ...

    def exceeds(self, level: float) -> bool:
        """Whether some value is above ``level``: ``maximum() > level``."""
        ...

    def at(self, across_m: np.ndarray) -> np.ndarray:
        """``L`` at arbitrary positions: linear between grid positions, 0 outside the scan."""
        ...

    def peak(self, refine: bool = False) -> float | None:
        """The most likely position, or None for an empty scan (first of equal maxima)."""
        ...


@dataclass(frozen=True, eq=False)
class LikelihoodScan:
    """The pipe likelihood ``L`` of eq. (1) over across-track position (seeds/003, Fig. 2).

    Attributes
    ----------
    positions : numpy.ndarray
        Increasing, equally spaced across-track positions, m, shape ``(n,)``.
    values : numpy.ndarray
        Finite, non-negative ``L`` at each position, shape ``(n,)``.
    """

    positions: np.ndarray
    values: np.ndarray

    def __post_init__(self) -> None:
        positions = np.asarray(self.positions, dtype=float)
        values = np.asarray(self.values, dtype=float)
        if positions.ndim != 1 or positions.shape != values.shape:
            raise ValueError(f"scan positions {positions.shape} and values {values.shape} differ")
        if not (np.all(np.isfinite(values)) and np.all(values >= 0.0)):
            raise ValueError("scan values must be finite and non-negative")
        object.__setattr__(self, "positions", positions)
        object.__setattr__(self, "values", values)

    @classmethod
    def empty(cls) -> LikelihoodScan:
        """A scan without positions: nothing was measured."""
        return cls(np.empty(0), np.empty(0))

    @property
    def is_empty(self) -> bool:
        """True when the scan has no positions or no positive value."""
        return self.values.size == 0 or not self.values.max() > 0.0

    def maximum(self) -> float:
        """The scan's largest value, 0 for a scan without positions."""
        return float(self.values.max(initial=0.0))

    def exceeds(self, level: float) -> bool:
        """Whether some value is above ``level``: ``maximum() > level``."""
        return self.maximum() > level

    def at(self, across_m: np.ndarray) -> np.ndarray:
        """``L`` at arbitrary positions: linear between grid positions, 0 outside the scan.

        Parameters
        ----------
        across_m : numpy.ndarray
            Across-track positions, m, any shape.

        Returns
        -------
        numpy.ndarray
            Finite, non-negative values of the shape of ``across_m``
            (0 at non-finite positions).
        """
        return interpolate(self.positions, self.values, across_m)

    def peak(self, refine: bool = False) -> float | None:
        """The most likely position, or None for an empty scan (first of equal maxima).

        Parameters
        ----------
        refine : bool
            Move the grid position of the maximum to the vertex of the
            parabola through it and its two neighbours (by at most half a
            grid step), where the scan is higher there than on both sides.
        """
        if self.is_empty:
            return None
        return peak_position(self.positions, self.values, int(np.argmax(self.values)), refine)


def interpolate(positions: np.ndarray, values: np.ndarray, across_m: np.ndarray) -> np.ndarray:
    """A scan's ``values`` over ``positions`` at arbitrary positions (:meth:`LikelihoodScan.at`).

    Reads ``values`` only on both sides of each finite position within the scan.
    """
    across = np.asarray(across_m, dtype=float)
    if values.size == 0:
        return np.zeros(across.shape)
    finite = np.isfinite(across)
    inside = np.interp(np.where(finite, across, positions[0] - 1.0), positions, values, 0.0, 0.0)
    return np.where(finite, inside, 0.0)


def peak_position(positions: np.ndarray, values: np.ndarray, best: int, refine: bool) -> float:
    """The position of the scan's maximum ``values[best]`` (:meth:`LikelihoodScan.peak`), read with its neighbours."""
    position = float(positions[best])
    if not refine or not 0 < best < values.size - 1:
        return position
    left, top, right = values[best - 1 : best + 2]
    curvature = left - 2.0 * top + right
    if not curvature < 0.0:
        return position
    step = float(positions[best + 1] - positions[best])
    return position + float(np.clip(0.5 * (left - right) / curvature, -0.5, 0.5)) * step


@dataclass(frozen=True, eq=False)
class Candidates:
    """The pipe cross-sections drawn through consecutive profile points and their scores.

    Attributes
    ----------
    across_m, depth_m : numpy.ndarray
        Centre ``[C_x, C_y]`` of each candidate (``nan`` where none exists).
    fit : numpy.ndarray
        ``L1`` of each candidate.
    proud : numpy.ndarray
        ``L2`` of each candidate.
    value : numpy.ndarray
        ``L = L1 + w L2`` (eq. 1); 0 for a candidate that is not scored.
    """

    across_m: np.ndarray
    depth_m: np.ndarray
    fit: np.ndarray
    proud: np.ndarray
    value: np.ndarray


@dataclass(frozen=True)
class PipeLikelihood:
    """Eq. (1) of seeds/003 for a pipe of known cross-section.

    Parameters
    ----------
    section : CrossSection
        The pipe's axes ``[M_a, M_i]``.
    sigma_m : float
        Noise of the data about the pipe's surface in ``L1``, m (the sagitta
        of the profile's chords is added per point).
    proud_weight : float
        The constant weight ``w`` on ``L2``.
    flank_m : float
        Width of each flank whose returns are the local seafloor in ``L2``, m.
    fit_span : float
        Share of the half-width ``M_a / 2`` about the centre whose points
        ``L1`` compares with the ellipse, in ``(0, 1]``.
    beam_angle : float
        Angle between neighbouring beams of the sonar, rad; with
        ``min_pipe_returns``, where the sonar can resolve the pipe.
    min_pipe_returns : float
        A candidate is scored only where the sonar's beams are at most
        ``M_a / min_pipe_returns`` apart across track at its centre; 0: everywhere.

    References
    ----------
    seeds/003, section 2, eq. (1) and Fig. 2.
    """

    section: CrossSection
    sigma_m: float
    proud_weight: float
    flank_m: float
    fit_span: float = 0.8
    beam_angle: float = 0.0
    min_pipe_returns: float = 0.0

    def __post_init__(self) -> None:
        if not 0.0 < self.sigma_m < math.inf:
            raise ValueError(f"sigma_m must be a positive finite number, got {self.sigma_m!r}")
        if not 0.0 <= self.proud_weight < math.inf:
            raise ValueError(f"proud_weight must be finite and non-negative, got {self.proud_weight!r}")
        if not 0.0 < self.flank_m < math.inf:
            raise ValueError(f"flank_m must be a positive finite number, got {self.flank_m!r}")
        if not 0.0 < self.fit_span <= 1.0:
            raise ValueError(f"fit_span must be in (0, 1], got {self.fit_span!r}")
        if not 0.0 <= self.beam_angle < math.pi:
            raise ValueError(f"beam_angle must be in [0, pi), got {self.beam_angle!r}")
        if not 0.0 <= self.min_pipe_returns < math.inf:
            raise ValueError(f"min_pipe_returns must be finite and non-negative, got {self.min_pipe_returns!r}")

    def candidates(self, profile: Profile) -> Candidates:
        """Draw and score the cross-section through every two consecutive profile points.

        Parameters
        ----------
        profile : Profile
            A resampled scan; fewer than two points give no candidates.

        Returns
        -------
        Candidates
            ``N_C = N_p - 1`` candidates (seeds/003, section 2).

        References
        ----------
        seeds/003, section 2, eq. (1).
        """
        x, z, step = profile.across_m, profile.depth_m, profile.spacing_m
        if x.size < 2:
            nothing = np.empty(0)
            return Candidates(nothing, nothing, nothing, nothing, nothing)
        section = self.section
        a, b = section.half_width_m, section.half_height_m
        cx, cz, ok = section.centres_below(x[:-1], z[:-1], x[1:], z[1:])
        ok &= (cx - a >= x[0] - 1e-9 * step) & (cx + a <= x[-1] + 1e-9 * step)
        cx = np.where(ok, cx, x[0])
        cz = np.where(ok, cz, 0.0)

        span, near = _window(x, cx, -self.fit_span * a, self.fit_span * a, step)
        residual = section.residual(x[span], z[span], cx[:, None], cz[:, None])
        sagitta = profile.gap_m**2 * b / (8.0 * a * a)
        variance = self.sigma_m**2 + sagitta[span] ** 2
        scaled = np.where(near, residual**2 / (2.0 * variance), 0.0)
        count = near.sum(axis=1)
        fit = np.where(count > 0, np.exp(-scaled.sum(axis=1) / np.maximum(count, 1)), 0.0)
        if self.beam_angle > 0.0 and self.min_pipe_returns > 0.0:
            ok &= beam_footprint(cx, cz, self.beam_angle) * self.min_pipe_returns <= section.major_m

        left, on_left = _window(x, cx, -a - self.flank_m, -a, step, open_high=True)
        right, on_right = _window(x, cx, a, a + self.flank_m, step, open_low=True)
        floor_left = _masked_median(z[left], on_left)
        floor_right = _masked_median(z[right], on_right)
        # Both flanks where both exist, else the one that does (nan: neither).
        both = 0.5 * (floor_left + floor_right)
        floor = np.where(np.isnan(floor_left), floor_right, np.where(np.isnan(floor_right), floor_left, both))
        distance = floor - cz
        proud = np.where(np.isfinite(distance), np.clip(1.0 - np.abs(distance - b) / (2.0 * b), 0.0, None), 0.0)

        fit = np.where(ok & np.isfinite(fit), fit, 0.0)
        proud = np.where(ok, proud, 0.0)
        value = fit + self.proud_weight * proud
        value = np.where(np.isfinite(value), value, 0.0)
        return Candidates(np.where(ok, cx, np.nan), np.where(ok, cz, np.nan), fit, proud, value)

    def scan(self, profile: Profile) -> LikelihoodScan:
        """The likelihood over the profile's grid (seeds/003, Fig. 2).

        Parameters
        ----------
        profile : Profile
            A resampled scan.

        Returns
        -------
        LikelihoodScan
            At each grid position the largest ``L`` of the candidates centred
            nearest to it; empty for an empty profile.
        """
        if profile.is_empty:
            return LikelihoodScan.empty()
        found = self.candidates(profile)
        values = np.zeros(profile.size)
        scored = np.isfinite(found.across_m) & (found.value > 0.0)
        if np.any(scored):
            bins = np.rint((found.across_m[scored] - profile.across_m[0]) / profile.spacing_m).astype(np.int64)
            np.maximum.at(values, np.clip(bins, 0, profile.size - 1), found.value[scored])
        return LikelihoodScan(profile.across_m, values)


def _window(
    x: np.ndarray,
    centre: np.ndarray,
    low: float,
    high: float,
    step: float,
    *,
    open_low: bool = False,
    open_high: bool = False,
) -> tuple[np.ndarray, np.ndarray]:
    """Indices of the grid points at offsets ``[low, high]`` from each centre, and which of them count.

    Returns
    -------
    index : numpy.ndarray
        Shape ``(len(centre), width)``, clipped into the grid.
    mask : numpy.ndarray
        True where the point lies in the grid and within the offsets (an
        open end excludes its bound).
    """
    width = int(math.ceil((high - low) / step)) + 2
    first = np.floor((centre + low - x[0]) / step).astype(np.int64)
    index = first[:, None] + np.arange(width)[None, :]
    inside = (index >= 0) & (index < x.size)
    index = np.clip(index, 0, x.size - 1)
    offset = x[index] - centre[:, None]
    above = offset > low if open_low else offset >= low
    below = offset < high if open_high else offset <= high
    return index, inside & above & below


def _masked_median(values: np.ndarray, mask: np.ndarray) -> np.ndarray:
    """Median of each row's masked entries; ``nan`` for a row without any."""
    stacked = np.where(mask, values, np.inf)
    stacked.sort(axis=1)
    count = mask.sum(axis=1)
    rows = np.arange(values.shape[0])
    low = stacked[rows, np.maximum(count - 1, 0) // 2]
    high = stacked[rows, count // 2]
    return np.where(count > 0, 0.5 * (low + high), np.nan)
