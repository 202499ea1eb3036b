"""Eq. (1) of seeds/003 as evidence: how much better the pipe, as the beams see it, explains the returns.

The paper scores a candidate cross-section by ``L = L1 + w L2`` (eq. 1):
``L1`` from the squared differences between the scan and the ellipse,
``L2`` from the distance between the ellipse's centre and the local
seafloor returns.  On the sonars of the paper (beams a fraction of the
pipe wide, section 4) that works (:mod:`trackbench_sonar.likelihood`).  On
a wider world of sonars it fails in three ways, each measured in
:mod:`trackbench_sonar.params`:

* wide beams show no arc.  Once a beam's footprint is half the pipe's
  diameter or more the scan shows a smooth bump, and the ellipse through
  two of its points fits it worse than a bump of rough seabed;
* sparse beams show no disagreement.  Far from nadir a mean of squared
  differences over a few returns is small for any ellipse, so rough
  seabed at the swath's edge scores like a pipe (the old model only
  stopped scoring where the beams were too sparse, by a threshold);
* spoil berms beside a trench are pipe-sized bumps whose flanks are lower
  than their crest, so ``L2`` calls them proud.

Here the same two questions, the fit of the pipe's cross-section and its
place on the local seafloor, are asked of the returns themselves (one per
beam, :attr:`trackbench_sonar.profile.Profile.returns_across_m`) in a
window of ``seabed_widths`` pipe widths either side of each candidate
centre ``c`` on the profile's grid, by two models fitted by least squares:

* the *seafloor*: ``z = f0 + f1 u + f2 g(u)``, ``u = x - c``: a sloping
  seabed with a mound or a hollow ``g(u) = exp(-u^2 / 2 l^2)`` centred on the
  candidate, ``l`` being ``relief_widths`` times the pipe's half-width as
  the beams see it (:meth:`~trackbench_sonar.footprint.SeenCrossSection.seen_half_width`).
  Relief that broad (a spoil berm, a sand wave, a trench's floor) is
  seabed, not pipe;
* the *pipe on that seafloor*: ``z = f0 + f1 u + f2 g(u) - s P(u) - A(u)``,
  where ``A`` is the upper half of the cross-section and ``P`` its span,
  both convolved with the beam footprint at ``c``
  (:class:`~trackbench_sonar.footprint.SeenCrossSection`), and ``s >= 0``
  the height of the pipe's centre above the seafloor: ``L2``'s distance,
  fitted (``s = M_i / 2`` for a pipe resting on the seabed, more over a
  free span, 0 for a pipe buried to its centre).

Each is fitted with a Cauchy loss of scale ``robust_sigmas`` times the
noise ``sigma_m`` (iteratively reweighted least squares, ``iterations``
rounds), so that a spike, a boulder or a trench wall in the window does
not decide the fit.  The candidate's score is the evidence

    E = C(seafloor) - C(pipe on seafloor),     C = sum_i k^2 log(1 + r_i^2 / k^2) / sigma^2

(for a Gaussian loss, the log-likelihood ratio of the two models times
two), floored at 0.  It grows with the number of returns that the pipe
explains better than the seabed does, so a fit over the few returns of
the swath's sparse edge cannot win because few of them disagree; a bump of
rough seabed scores only as far as it has the pipe's shape as the beams
see it; a spoil berm is explained by the seafloor's mound.  A candidate
whose window holds fewer than :data:`MIN_RETURNS` returns, or none beyond
the pipe's span on one side, scores 0.

The scan (Fig. 2 of the paper) holds ``E`` at every grid position.  It is
computed where it is read (:class:`EvidenceScan`): the straight line
through a candidate's window bounds its seafloor's cost, which bounds its
evidence, so the scan's maximum needs the seafloor fitted only where the
line's bound reaches the best evidence found and the pipe only where the
seafloor's does, and a particle filter's weights only where its particles
are.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from benchmark.lazy import lazy_module
from trackbench_sonar.cross_section import CrossSection
from trackbench_sonar.footprint import (
    FWHM_PER_SIGMA,
    TABLE_OFFSET_STEP,
    TABLE_REACH,
    TABLE_SIGMA_STEP,
    semicircle_table,
)
from trackbench_sonar.likelihood import LikelihoodScan, interpolate, peak_position
from trackbench_sonar.profile import Profile

evidence_kernel = lazy_module("trackbench_sonar.evidence_kernel")

MIN_RETURNS = 6
"""Fewest returns in a candidate's window for it to be scored (the pipe model has four unknowns)."""

SECTION_NUMBERS = 8
"""How many of the scan's numbers (:attr:`FootprintLikelihood.settings`) come before the semicircle table's."""


@dataclass(frozen=True, eq=False)
class Evidence:
    """The candidates of one profile and what the two models made of them.

    Attributes
    ----------
    across_m : numpy.ndarray
        Candidate centres ``C_x`` (the profile's grid positions).
    evidence : numpy.ndarray
        ``E``, floored at 0; 0 where a candidate is not scored.
    pedestal_m : numpy.ndarray
        Fitted height ``s`` of the pipe's centre above the seafloor
        (``nan`` where not scored).
    returns : numpy.ndarray
        Returns in each candidate's window.
    scored : numpy.ndarray
        Where the candidate was scored.
    """

    across_m: np.ndarray
    evidence: np.ndarray
    pedestal_m: np.ndarray
    returns: np.ndarray
    scored: np.ndarray


@dataclass(frozen=True)
class FootprintLikelihood:
    """Eq. (1) of seeds/003 for a pipe seen through the beams' footprints, as evidence over the seafloor.

    Parameters
    ----------
    section : CrossSection
        The pipe's axes ``[M_a, M_i]``.
    sigma_m : float
        Noise of a return about the model, m (the sonar's range noise and
        what the model leaves out).
    beam_width : float
        The beams' across-track width, rad (0: rays).
    seabed_widths : float
        The window reaches this many widths ``M_a`` beyond the pipe's span
        on either side.
    relief_widths : float
        Width ``l`` of the seafloor's mound or hollow, in half-widths of the
        pipe as seen.
    robust_sigmas : float
        Scale of the Cauchy loss, in ``sigma_m``.
    iterations : int
        Rounds of reweighting.

    References
    ----------
    seeds/003, section 2, eq. (1) and Fig. 2.
    """

    section: CrossSection
    sigma_m: float
    beam_width: float = 0.0
    seabed_widths: float = 2.0
    relief_widths: float = 2.0
    robust_sigmas: float = 10.0
    iterations: int = 3

    def __post_init__(self) -> None:
        for label in ("sigma_m", "seabed_widths", "relief_widths", "robust_sigmas"):
            value = getattr(self, label)
            if not 0.0 < value < math.inf:
                raise ValueError(f"{label} must be a positive finite number, got {value!r}")
        if not 0.0 <= self.beam_width < math.pi:
            raise ValueError(f"beam_width must be in [0, pi), got {self.beam_width!r}")
        if self.iterations < 1:
            raise ValueError(f"iterations must be >= 1, got {self.iterations!r}")

    def candidates(self, profile: Profile) -> Evidence:
        """Fit both models about every grid position of the profile and score each.

        Parameters
        ----------
        profile : Profile
            A resampled scan with its returns.

        Returns
        -------
        Evidence
            One candidate per grid position.

        References
        ----------
        seeds/003, section 2, eq. (1).
        """
        centre = profile.across_m
        x, z = profile.returns_across_m, profile.returns_depth_m
        count = centre.size
        if count == 0 or x.size < MIN_RETURNS:
            nothing = np.zeros(count)
            return Evidence(centre, nothing, np.full(count, np.nan), nothing.astype(np.int64), nothing.astype(bool))
        low, high, sigma_f = self.windows(profile)
        _, _, table = semicircle_table()
        numbers = self._numbers
        evidence, pedestal, scored = evidence_kernel.footprint_evidence(
            x, z, centre, sigma_f, low, high, *numbers[:SECTION_NUMBERS], table, *numbers[SECTION_NUMBERS:]
        )
        return Evidence(centre, evidence, pedestal, high - low, scored)

    @property
    def reach_m(self) -> float:
        """Half-width of a candidate's window: the pipe's half-width and ``seabed_widths`` widths ``M_a``, m."""
        return self.section.half_width_m + self.seabed_widths * self.section.major_m

    def windows(self, profile: Profile) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Each grid position's window of returns, ``returns[low:high]``, and the footprint's sigma there, m.

        In one compiled call (:func:`~trackbench_sonar.evidence_kernel.candidate_windows`), to the last bit
        what :func:`numpy.searchsorted` and :func:`~trackbench_sonar.footprint.footprint_sigma` give.
        """
        return evidence_kernel.candidate_windows(
            profile.returns_across_m,
            profile.across_m,
            profile.depth_m,
            self.reach_m,
            float(self.beam_width),
            FWHM_PER_SIGMA,
        )

    @cached_property
    def settings(self) -> np.ndarray:
        """The numbers of :func:`~trackbench_sonar.evidence_kernel.footprint_evidence`, as :func:`~trackbench_sonar.evidence_kernel.seabed_costs` takes them."""
        return np.array(self._numbers, dtype=float)

    @cached_property
    def _numbers(self) -> tuple[float, ...]:
        """The scan's numbers in the kernels' order: the section's and the fit's, then the semicircle table's."""
        offsets, _, _ = semicircle_table()
        return (
            self.section.half_width_m,
            self.section.half_height_m,
            self.reach_m,
            self.relief_widths,
            self.robust_sigmas * self.sigma_m,
            self.sigma_m,
            self.iterations,
            MIN_RETURNS,
            float(offsets[0]),
            TABLE_OFFSET_STEP,
            TABLE_SIGMA_STEP,
            TABLE_REACH,
        )

    def scan(self, profile: Profile) -> EvidenceScan | LikelihoodScan:
        """The evidence over the profile's grid (seeds/003, Fig. 2), computed where read; empty for an empty profile."""
        if profile.is_empty:
            return LikelihoodScan.empty()
        return EvidenceScan(self, profile)


class EvidenceScan:
    """The evidence of a :class:`FootprintLikelihood` over a profile's grid, candidate by candidate where it is read.

    A :class:`~trackbench_sonar.likelihood.LikelihoodScan` whose values are
    computed when asked for.  Each candidate's evidence is bounded from
    above in three steps, each tighter and dearer than the one before: by
    the straight line through its window (every candidate at once, from
    running sums over the returns: :func:`~trackbench_sonar.evidence_kernel.line_bounds`),
    by the cost of its seafloor's fit, and by its evidence itself once its
    pipe is fitted.  The scan's maximum (:meth:`maximum`, :meth:`peak`) and
    whether some value is above a level (:meth:`exceeds`, :attr:`is_empty`)
    tighten only the candidates whose bound reaches the best found or the
    level (:func:`~trackbench_sonar.evidence_kernel.evidence_maximum`,
    :func:`~trackbench_sonar.evidence_kernel.evidence_exceeds`), and the
    values at a few positions (:meth:`at`, a particle filter's weights)
    need only the grid positions either side of them.  Every value is the
    one :meth:`FootprintLikelihood.candidates` gives, to the last bit.

    Parameters
    ----------
    model : FootprintLikelihood
        The pipe and the sonar.
    profile : Profile
        A profile with points.

    References
    ----------
    seeds/003, section 2, eq. (1) and Fig. 2.
    """

    def __init__(self, model: FootprintLikelihood, profile: Profile) -> None:
        self.positions = profile.across_m
        self._spacing = profile.spacing_m
        count = self.positions.size
        self._values = np.zeros(count)
        self._known = np.zeros(count, dtype=bool)
        self._best: int | None = None
        self._state: tuple[np.ndarray, ...] | None = None
        x, z = profile.returns_across_m, profile.returns_depth_m
        if x.size < MIN_RETURNS:
            self._known[:] = True
            self._best = -1
            return
        low, high, sigma_f = model.windows(profile)
        self._table = semicircle_table()[2]
        self._settings = model.settings
        self._data = (x, z, self.positions, sigma_f, low, high)
        bounds = evidence_kernel.line_bounds(x, z, self.positions, low, high, self._settings)
        self._state = (self._values, self._known, np.full(count, evidence_kernel.UNFITTED), bounds)

    def _evaluate(self, wanted: np.ndarray) -> None:
        if not np.all(self._known[wanted]):
            evidence_kernel.evidence_at(wanted, self._data, self._state, self._settings, self._table)

    def _strongest(self) -> int:
        """The first grid index of the largest value, -1 when every value is 0."""
        if self._best is None:
            self._best = int(evidence_kernel.evidence_maximum(self._data, self._state, self._settings, self._table))
        return self._best

    @property
    def evaluated(self) -> int:
        """Grid positions whose evidence is computed so far."""
        return int(np.count_nonzero(self._known))

    @property
    def values(self) -> np.ndarray:
        """The evidence at every grid position (all of it computed)."""
        self._evaluate(np.flatnonzero(~self._known))
        return self._values

    @property
    def is_empty(self) -> bool:
        """True when no value is positive."""
        return not self.exceeds(0.0)

    def exceeds(self, level: float) -> bool:
        """Whether some value is above ``level`` (``maximum() > level``), fitting no more than that takes."""
        if self._best is not None or self._state is None:
            return self.maximum() > level
        exceeded = evidence_kernel.evidence_exceeds(float(level), self._data, self._state, self._settings, self._table)
        return bool(exceeded)

    def maximum(self) -> float:
        """The largest value."""
        best = self._strongest()
        return 0.0 if best < 0 else float(self._values[best])

    def at(self, across_m: np.ndarray) -> np.ndarray:
        """The evidence at arbitrary positions, as :meth:`LikelihoodScan.at <trackbench_sonar.likelihood.LikelihoodScan.at>` reads it."""
        across = np.asarray(across_m, dtype=float)
        if self._state is not None:
            evidence_kernel.evidence_around(
                across.ravel(), float(self.positions[0]), self._spacing, self._data, self._state, self._settings,
                self._table,
            )
        return interpolate(self.positions, self._values, across)

    def peak(self, refine: bool = False) -> float | None:
        """The most likely position (first of equal maxima), as :meth:`LikelihoodScan.peak <trackbench_sonar.likelihood.LikelihoodScan.peak>` finds it."""
        best = self._strongest()
        if best < 0:
            return None
        self._evaluate(np.arange(max(best - 1, 0), min(best + 2, self.positions.size)))
        return peak_position(self.positions, self._values, best, refine)


@dataclass(frozen=True)
class WidestEvidence:
    """Eq. (1) for a sonar whose beam width nobody gave: the best of a few widths, ping by ping.

    Each ping is scored by every model and the scan whose best candidate
    holds the most evidence is kept: assumed too narrow, the footprint
    leaves a smoothed pipe unexplained; assumed too wide, it blurs the
    pipe's arc away, and either way the true pipe's evidence falls.

    Parameters
    ----------
    models : tuple of FootprintLikelihood
        The same pipe and sonar under different beam widths, at least one.

    References
    ----------
    seeds/003, section 2, eq. (1).
    """

    models: tuple[FootprintLikelihood, ...]

    def __post_init__(self) -> None:
        if not self.models:
            raise ValueError("WidestEvidence needs at least one model")

    @property
    def section(self) -> CrossSection:
        """The pipe's axes (the same in every model)."""
        return self.models[0].section

    def scan(self, profile: Profile) -> EvidenceScan | LikelihoodScan:
        """The scan, among the models', whose maximum is largest (the first of equals)."""
        scans = [model.scan(profile) for model in self.models]
        return max(scans, key=lambda scan: scan.maximum())
