"""The ``sonar_pf`` tracker: the adapted particle filter of seeds/003, section 3.

The state is one number, the pipe's across-track position in the swath
(section 3).  Each ping runs one step of the shared particle filter core
(:class:`benchmark.filters.condensation.Condensation`) with

* resampling at every update (SIR, section 3.4): the core resamples at the
  start of a step, which is the same as resampling at the end of the
  previous one, and does so whatever the effective sample size;
* the importance density of :mod:`trackbench_sonar.importance` (eq. 3): a
  random walk (:func:`walk_sigma`) shifted by the drift the filter has
  seen (:class:`AcrossTrackRate`), then a share of the particles re-drawn
  uniformly over the swath (section 3.4), ``J`` when the filter has lost
  the pipe and less as the scan at its particles nears the scan's best
  (:func:`injection_rate`);
* weights by eq. (4), ``w_k^i ~ w_(k-1)^i L_k^i``, where ``L_k^i`` is the
  likelihood scan of eq. (1) (:mod:`trackbench_sonar.detection`, the scan
  ``sonar_detector`` reports the maximum of) at the particle's position,
  raised to a power and floored (:class:`ScanWeights`), normalised by
  :func:`benchmark.filters.normalise_weights`;
* the estimate of eq. (5), the weighted mean of the particles of the
  heaviest peak (:mod:`trackbench_sonar.estimate`, section 3.3).

Five departures from the letter of section 3, each explained with the
evidence in :mod:`trackbench_sonar.params`: the scan is raised to a power
before it weighs the particles, every weight keeps a small share of the
best one, eq. (5) averages the heaviest peak rather than all particles,
the walk drifts with the pipe's across-track rate, and the rate of
injected samples follows how lost the filter is.  ``sonar_pf-paper`` sets
all of them back.

Start: with ``init`` (the first ping's
:class:`~benchmark.modalities.sonar.model.SonarTruth`) the particles are
drawn about its position with ``init_sigma_m``; without it they are drawn
uniformly over the first swath that has returns, as the injected samples
are.  Until then the tracker reports no detection.

A ping without a usable scan (too few returns, or a likelihood of zero
everywhere) carries no information about the pipe: the filter then only
predicts, moving the particles by the random walk and keeping their
weights (no injection: the extent to inject over is unknown, and samples
that no measurement weighs would only scatter the set), and reports the
predicted estimate of eq. (5), coasting through the gap.

Every random number comes from the generator handed to :meth:`SonarParticleFilter.reset`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from benchmark.errors import DataError
from benchmark.filters import RESAMPLERS, Condensation, ParticleSet
from benchmark.filters.particles import ParticleBeliefView
from benchmark.modalities.sonar.model import PipeEstimate, SonarFrame, SonarTruth
from benchmark.model import SequenceInfo
from trackbench_sonar.detection import ScanTracker
from trackbench_sonar.estimate import peak_mean
from trackbench_sonar.importance import RandomWalkInjection, uniform_positions
from trackbench_sonar.likelihood import Scan
from trackbench_sonar.params import ParticleFilterParams


@dataclass(frozen=True)
class ScanWeights:
    """Observation model: each particle's likelihood read off the scan, sharpened, with a floor.

    Parameters
    ----------
    floor : float
        Every particle's likelihood is at least this share of the largest
        among the particles, so that a ping whose scan misses the pipe
        where it is (a lost beam, a spike) weakens the particles there
        instead of wiping them out.
    exponent : float
        ``gamma``: the scan's values are raised to this power.

    References
    ----------
    seeds/003, section 3.2 ("the filter ... uses the likelihood scan produced
    in the previous section to weight the particles"), eq. (4).
    """

    floor: float
    exponent: float = 1.0

    def likelihood(self, states: np.ndarray, observation: Scan) -> np.ndarray:
        """``max(L_k^i ^ gamma, floor * max_j L_k^j ^ gamma)`` for every particle of ``states`` (shape ``(N, 1)``)."""
        values = observation.at(np.asarray(states, dtype=float)[:, 0]) ** self.exponent
        return np.maximum(values, self.floor * values.max(initial=0.0))


@dataclass
class AcrossTrackRate:
    """The pipe's across-track rate, m per ping, smoothed from the filter's own estimates.

    After each estimate ``x_k`` the rate becomes ``(1 - g) rate + g (x_k -
    x_(k-1))``; it shifts the random walk of the next ping
    (:class:`trackbench_sonar.importance.RandomWalkInjection`).  A move
    beyond ``limit_m``, faster than the pipe can drift across the swath, is
    a jump (the filter leaving one peak of the scan for another), and so
    is every move while the filter has lost the pipe (:func:`injection_rate`
    is injecting): the rate is set back to 0 rather than learnt from them.
    The estimates are functions of the pings so far, so the importance
    density stays one of eq. (3)'s, ``q(. | x_(0:k-1), z_(1:k))``.

    Parameters
    ----------
    gain : float
        ``g`` in ``[0, 1]``; 0 keeps the rate at 0 (the paper's walk).
    limit_m : float
        Largest move per ping taken for a drift, m.
    """

    gain: float
    limit_m: float = math.inf
    rate_m: float = 0.0
    last_m: float | None = None

    def update(self, estimate_m: float, trusted: bool = True) -> None:
        """Take in the estimate of the ping just filtered; an estimate not ``trusted`` zeroes the rate."""
        if self.last_m is not None and self.gain > 0.0:
            move = estimate_m - self.last_m
            jump = not trusted or abs(move) > self.limit_m
            self.rate_m = 0.0 if jump else (1.0 - self.gain) * self.rate_m + self.gain * move
        self.last_m = estimate_m


SETTLED = 1.0 - 1e-12
"""Share of ``here / lost_ratio`` the scan's best may reach for :func:`injection_rate` to be 0 without it."""
NORMAL = 1e-290
"""Smallest ``lost_ratio * here`` (and inverse of the largest ``here / lost_ratio``) :func:`nothing_lost` decides on."""


def nothing_lost(lost_ratio: float, here: float, scan: Scan) -> bool:
    """Whether ``here >= lost_ratio * scan.maximum()`` rounds so, decided without the scan's best where it can be.

    True when no value of the scan exceeds ``here / lost_ratio`` less a
    relative margin of ``1e-12`` (:data:`SETTLED`), which fits only the
    candidates that could exceed it (:meth:`~trackbench_sonar.likelihood.Scan.exceeds`).
    With the best ``M`` at most that level, ``lost_ratio M`` rounds below
    ``here`` (three roundings move it by a relative ``1.1e-16`` each), so
    ``here / (lost_ratio M)`` rounds to 1 or more and :func:`injection_rate`'s
    formula to 0.  Every product stays a normal number (:data:`NORMAL`);
    otherwise, or when the level is exceeded, the answer is False and the
    formula decides.
    """
    level = here / lost_ratio * SETTLED if lost_ratio > 0.0 else math.inf
    return lost_ratio * here >= NORMAL and level * NORMAL < 1.0 and not scan.exceeds(level)


def injection_rate(fraction: float, lost_ratio: float, scan: Scan, here: float) -> float:
    """The share of particles re-drawn this ping: ``J max(0, 1 - r / lost_ratio)``.

    ``r`` is the scan's best value at the particles (``here``, read where
    the drift takes them) over its best value anywhere: near 1 while the
    particles sit on the most likely pipe, near 0 when they have lost it.
    Where ``r`` reaches ``lost_ratio`` the rate is 0, which
    :func:`nothing_lost` finds without the scan's best.

    Parameters
    ----------
    fraction : float
        ``J``, the rate of a lost filter (section 3.4).
    lost_ratio : float
        ``r`` at and above which nothing is injected; 0 injects ``J`` always.
    scan : Scan
        This ping's scan, not empty.
    here : float
        The scan's best value at the particles' positions.

    References
    ----------
    seeds/003, section 3.4 ("generating some rate J of new random samples").
    """
    if nothing_lost(lost_ratio, here, scan):
        return 0.0
    threshold = lost_ratio * scan.maximum()
    if not threshold > 0.0:
        return fraction
    return fraction * max(0.0, 1.0 - here / threshold)


def walk_sigma(params: ParticleFilterParams, info: SequenceInfo, tracker: str) -> float:
    """The random walk's standard deviation per ping, m.

    ``walk_sigma_m`` when set; otherwise ``walk_speed_mps`` times the
    sequence's ping interval, so that pings farther apart in time allow the
    pipe to move farther across the swath.

    Raises
    ------
    DataError
        If ``walk_sigma_m`` is 0 and the sequence has no positive
        ``frame_interval_s``.
    """
    if params.walk_sigma_m > 0.0:
        return float(params.walk_sigma_m)
    interval = info.frame_interval_s
    if interval is None or not 0.0 < interval < math.inf:
        raise DataError(
            f"{tracker}: sequence {info.name!r} has no ping interval (frame_interval_s {interval!r}); "
            "set the parameter walk_sigma_m"
        )
    return float(params.walk_speed_mps) * float(interval)


class SonarParticleFilter(ParticleBeliefView, ScanTracker):
    """Particle filter over the pipe's across-track position, weighted by the likelihood scan.

    The belief is exposed as a :class:`~benchmark.testing.beliefs.ParticleBelief`
    (:attr:`particles`, :attr:`weights`), and the samples each ping weighed as a
    :class:`~benchmark.testing.beliefs.ParticleUpdate` (:attr:`prior_particles`).

    Attributes
    ----------
    particle_set : ParticleSet or None
        The weighted particles ``(N, 1)`` after the last step; None until
        the filter has a start.
    prior_set : ParticleSet or None
        The samples of eq. (3) the last ping weighed by eq. (4): walked,
        drifted, with the injected ones (section 3.4); None when the ping
        had no usable scan, and so no update.

    References
    ----------
    seeds/003, section 3, eqs. (2)-(5) and section 3.4.
    """

    name = "sonar_pf"
    version = "2.0"
    Params = ParticleFilterParams

    def __init__(self, params: ParticleFilterParams | None = None) -> None:
        super().__init__(params)
        self._observation = ScanWeights(float(self.params.weight_floor), float(self.params.weight_exponent))
        self._walk_sigma = 0.0
        self._rate = AcrossTrackRate(float(self.params.drift_gain))
        self._rng: np.random.Generator | None = None
        self.particle_set: ParticleSet | None = None
        self.prior_set: ParticleSet | None = None

    def reset(self, info: SequenceInfo, rng: np.random.Generator, init: SonarTruth | None = None) -> None:
        """Set up the detector and, given a start, the particles.

        Parameters
        ----------
        info : SequenceInfo
            Its SonarCalibration gives the pipe's dimensions.
        rng : numpy.random.Generator
            The tracker's only source of randomness.
        init : SonarTruth, optional
            The pipe's position at the first ping; the particles start
            normally distributed about it.  Otherwise, or when its
            ``across_m`` is not finite (no pipe in view), they start
            uniformly over the first swath with returns.

        Raises
        ------
        DataError
            If the pipe's dimensions are neither in the calibration nor in
            the parameters, or the walk's sigma per ping is not set and the
            sequence has no ping interval.
        """
        super().reset(info, rng, init)
        self._walk_sigma = walk_sigma(self.params, info, self.name)
        interval = info.frame_interval_s
        known = interval is not None and 0.0 < interval < math.inf
        limit = float(self.params.max_drift_mps) * float(interval) if known else math.inf
        self._rng = rng
        self.particle_set = None
        self.prior_set = None
        start = init.across_m if init is not None else math.nan
        self._rate = AcrossTrackRate(float(self.params.drift_gain), limit, 0.0, start if math.isfinite(start) else None)
        if math.isfinite(start):
            n = int(self.params.n_particles)
            states = start + self.params.init_sigma_m * rng.standard_normal((n, 1))
            self.particle_set = ParticleSet.equally_weighted(states)

    def step(self, frame: SonarFrame) -> PipeEstimate | None:
        """One update of the filter on a ping and the estimate of eq. (5).

        Returns
        -------
        PipeEstimate or None
            The weighted mean of the particles; None while the filter has no
            start (no ``init`` and no swath with returns yet).

        Raises
        ------
        DataError
            If the observation is not a Swath (the message names the frame).
        RuntimeError
            If called before :meth:`reset`.

        References
        ----------
        seeds/003, eqs. (3)-(5) and section 3.4.
        """
        if self._rng is None:
            raise RuntimeError(f"{self.name}: step() called before reset()")
        p = self.params
        profile, scan = self.scan(frame)
        extent = None if profile.is_empty else (float(profile.across_m[0]), float(profile.across_m[-1]))
        if self.particle_set is None:
            if extent is None:
                return None
            self.particle_set = ParticleSet.equally_weighted(uniform_positions(int(p.n_particles), extent, self._rng))
        drift = self._rate.rate_m
        lost = False
        self.prior_set = None
        # The scan at the particles first: their evidence, when positive, tells the scan is not empty.
        here = float(scan.at(self.particle_set.states[:, 0] + drift).max(initial=0.0))
        if not here > 0.0 and scan.is_empty:
            movement = RandomWalkInjection(self._walk_sigma, 0.0, None, drift)
            walked = movement.walk(self.particle_set.states, self._rng)
            self.particle_set = ParticleSet(walked, self.particle_set.weights)
        else:
            rate = injection_rate(p.inject_fraction, p.lost_ratio, scan, here)
            lost = p.lost_ratio > 0.0 and rate > 0.0
            ping = Condensation(
                movement=RandomWalkInjection(self._walk_sigma, rate, extent, drift),
                observation=self._observation,
                resample=RESAMPLERS[p.resampler],
                ess_fraction=math.inf,
                carry_weights=True,
            )
            self.prior_set = ping.predict(self.particle_set, self._rng)
            self.particle_set = ping.update(self.prior_set, scan)
        halfwidth = p.peak_halfwidth * self.detector.likelihood.section.major_m
        estimate = peak_mean(self.particle_set.states[:, 0], self.particle_set.weights, halfwidth)
        self._rate.update(estimate, trusted=not lost)
        return PipeEstimate(estimate)
