"""The parameters of the sonar trackers and where their defaults come from.

seeds/003 gives the structure of the detector and the filter but almost no
numbers: the pipe's dimensions are "known" (the sequence's calibration
supplies its diameter), L2 carries "a constant weight" of unstated value,
the filter resamples by SIR at every update and injects "some rate J" of new
samples.  The defaults below are reasoned from the sonars and the pipes;
where the sonar suite was consulted, the evidence is quoted as RMSE / share
of pings correct per sequence (autotracker, as-laid, concrete,
second-pipe; ``--init truth``; the filter's figures are means over eight
seeds) when that one default is set back, all else as shipped.  As shipped:
detector 3.92 m / 80 %, 3.02 m / 94 %, 0.022 m / 99 %, 2.71 m / 81 %;
filter 2.36 m / 95 %, 0.46 m / 99.7 %, 0.014 m / 100 %, 0.18 m / 99.5 %.

The detector
------------

``grid_m`` (0.05 m).  The resampling grid must be at least as fine as the
sonar at its best, so that resampling loses nothing, and fine enough that
an ellipse of the smallest pipe spans many points, so that L1 judges a
shape rather than its two defining points.  The RESON-like sequences see
the bottom every 0.07 m below the sonar at 8 m altitude (0.5 deg beams), and
the smallest pipe is 0.5 m: 0.05 m gives ten points across it.

``spike_window`` (5) and ``spike_heights`` (0.5).  A running median of the
ranges over five returns follows the pipe wherever it spans three returns
or more, which is everywhere a cross-section is fitted (``min_pipe_returns``),
so the returns on a pipe differ from it by a fraction of the pipe's height.
A spike of half the pipe's height or more moves its return by more than
that along the beam (and, far from nadir, by metres across track); it is
dropped.  Without the test one spike inside a pipe's span spoils L1 of the
right candidate, and one far out draws a slanted ramp into the profile:
detector 4.64 m / 72 %, 4.11 m / 83 %, 1.93 m / 93 %, 4.05 m / 73 %.

``model_sigma_m`` (0.01 m).  L1's residual scale is ``sqrt(range_sigma_m^2
+ model_sigma_m^2)`` plus, point by point, the sagitta of the profile's
chord there (:mod:`trackbench_sonar.likelihood`); ``model_sigma_m`` is what
neither the sonar's range noise nor the chords explain: the pipe's surface
(coating joints, growth) and the seabed's finest roughness.

``fit_span`` (0.8).  L1 compares the profile with the ellipse only where
``|x - C_x| <= 0.8 M_a / 2``, the upper part of the arc facing the sonar.
Nearer the ends the profile is where the pipe meets the seabed, shadowed,
undercut and bridged by a straight line between the last return on the
pipe and the first on the seabed, and a single grid point there landing on
the pipe or on the seabed would halve L1 of the right candidate.  With the
whole span the filter is drawn to the second pipe more often (second-pipe
1.21 m / 95.5 %).

``min_pipe_returns`` (2).  A cross-section is fitted only where the
sonar's beams land no more than half a pipe width apart (the calibration's
beam spacing at the candidate's range and angle), so that at least two
intervals between beams cross the pipe.  Where they are sparser the pipe
falls between the beams and the profile shows nothing of its shape, and a
wide plateau of bare seabed scores as high as a pipe.  For the EM2000-like
sonar at 12.5 m over a 0.9 m pipe this keeps the swath within about 43 deg
of nadir (12 m either side); for the RESON-like sonar at 9 m over a 0.55 m
pipe within about 57 deg (14 m).  Without it: detector 7.65 m / 72 % on
autotracker, filter 7.10 m / 88 %.

``proud_weight`` (1).  Eq. (1) adds L1 and L2; both lie in ``[0, 1]`` here,
so a unit weight gives the shape of the arc and the pipe's protrusion equal
say, and a perfectly fitting, proud pipe scores 2.  L2 is what tells a pipe
from bare seabed where the shape cannot (with ``proud_weight = 0`` the
detector finds the pipe in 1-68 % of the pings); a weight of 2 helps the
detector on three sequences (2.60 m / 86 %, 1.04 m / 98 %, 0.022 m / 99 %)
but draws it to the proud new pipe while the tracked one is half buried
(second-pipe 2.47 m / 66 %).

``flank_widths`` (1).  The local seafloor is read on each side over one
pipe width ``M_a``: close enough to be the seabed the pipe rests on, wide
enough for the median to ignore a spike or a boulder edge.

The filter
----------

``n_particles`` (300).  The state is one-dimensional; 300 particles over a
swath some 30-50 m wide still put several within a pipe's width of any
position when they are spread uniformly.

``walk_speed_mps`` (0.4 m/s) and ``walk_sigma_m`` (0: from the speed).  The
pipe's across-track position changes with the vehicle's cross-track motion
and the pipe's curvature.  An AUV correcting its track moves sideways at up
to about half a metre per second, so the walk's standard deviation per
ping is 0.4 m/s times the ping interval: 0.16 m for the EM2000-like sonar's
2.5 pings a second, 0.1 m at 4 pings a second.  A fixed 0.1 m per ping lags
behind the autotracker's fastest correction (2.60 m / 92 % there).

``inject_fraction`` (0.05).  Section 3.4 keeps "some noise in the system by
generating some rate J of new random samples as done in the initialization
step".  With ``J N`` = 15 new samples per ping, one lands within a pipe's
likelihood peak (a few tenths of a metre of some 25 m where pipes are
sought) every six or seven pings, so that a lost pipe is found again within
a few seconds.  Without them the filter never finds the autotracker's pipe
again after its covered stretch (2.42 m / 81 %); but they are also what can
carry it to the second pipe.

``init_sigma_m`` (0.1 m): the spread about a known start.

``weight_exponent`` (6; eq. 4 reads 1).  The scan of eq. (1) is a figure of
merit, not a probability: a pipe scores up to 2 and bare seabed, where the
beams are too sparse for L1 to object, up to 1.  Read as a likelihood it
would let one ping tell a pipe from bare seabed by a factor of two only,
and samples on clutter keep much of the weight.  Raised to the sixth power
the factor is 64, and a candidate at 90 % of the best still keeps half its
weight (``0.9^6 = 0.53``), the same reasoning as the condensation
tracker's weight exponent.  With 1: 4.41 m / 82 %, 10.1 m / 59 %, 0.026 m /
99.7 %, 12.0 m / 40 %.

``weight_floor`` (0.02; eq. 4 reads 0).  Every particle keeps at least 2 %
of the best particle's likelihood: a ping whose scan misses the pipe where
it is (a lost beam, the pipe's own shadow) then weakens the particles on it
fifty-fold instead of wiping them out for the samples injected elsewhere.
It also keeps the weights defined when the scan is zero at every particle.
Without it: 2.74 m / 94 %, 0.51 m / 99.6 %, 0.013 m / 100 %, 0.30 m / 99.8 %.

``peak_halfwidth`` (1 pipe width; 0 is eq. 5 as written).  The estimate
is eq. (5) over the particles of the heaviest peak
(:mod:`trackbench_sonar.estimate`): the mean of all particles falls
between the pipe and whatever else holds weight (the injected samples, a
second pipe), more than the sonar's resolution away from both.  Over all
particles: 1.74 m / 91 %, 0.61 m / 85 %, 0.022 m / 100 %, 0.22 m / 85 %
(a lower RMSE on the autotracker, whose covered stretch a mean straddles
with smaller errors than a wrong peak, but fewer pings correct everywhere).

``resampler`` ("multinomial"): SIR as in Gordon et al. (seeds/003, ref. [4]).
"""

from __future__ import annotations

from typing import Annotated, Literal

import pydantic
from annotated_types import Ge, Interval, MinLen

from benchmark.filters import ResamplerName
from benchmark.parameters import NonNegative, Positive


@pydantic.dataclasses.dataclass(frozen=True)
class DetectorParams:
    """Parameters of the pipe detector of seeds/003, section 2 (``sonar_detector``).

    Each field's type declares its domain; a value outside it is a
    :class:`pydantic.ValidationError`.
    """

    likelihood: Literal["footprint", "ellipse"] = "footprint"
    """Form of eq. (1): the cross-section as the beams see it, as evidence, or the ellipse through two points."""

    grid_m: Positive = 0.05
    """Spacing of the across-track grid the swath is resampled on, m (section 2); at most M_a / 10."""

    spike_window: Annotated[int, Ge(0)] = 5
    """Returns in the running median of the spike test, odd; below 3: no spike test."""

    spike_heights: NonNegative = 1.0
    """A return whose range is off the running median by more than this many pipe heights M_i is a spike; 0: no test."""

    min_beams: Annotated[int, Ge(0)] = 5
    """Fewest valid returns for a scan; fewer leave the ping without a detection."""

    major_axis_m: NonNegative = 0.0
    """M_a, the pipe cross-section's horizontal axis, m (section 2); 0: the calibration's pipe diameter."""

    minor_axis_m: NonNegative = 0.0
    """M_i, the pipe cross-section's vertical axis, m (section 2); 0: the calibration's pipe diameter."""

    model_sigma_m: NonNegative = 0.01
    """Model part of the residual scale of L1, added in quadrature to the calibration's range sigma, m."""

    fit_span: Annotated[float, Interval(gt=0, le=1)] = 0.8
    """Share of the half-width M_a/2 about the centre whose points L1 compares with the ellipse, in (0, 1]."""

    min_pipe_returns: NonNegative = 2.0
    """Candidates are scored only where the sonar's beams land at most M_a / min_pipe_returns apart; 0: everywhere."""

    proud_weight: NonNegative = 1.0
    """The constant weight on L2 in eq. (1)."""

    flank_widths: Positive = 1.0
    """Width of each flank read as local seafloor in L2, in major axes M_a (ellipse)."""

    beam_width_deg: NonNegative = 0.0
    """Across-track width of a beam, deg (footprint); 0: the calibration's, else see ``unknown_width_spacings``."""

    unknown_width_spacings: Annotated[tuple[Positive, ...], MinLen(1)] = (1.0, 2.0, 4.0)
    """Beam widths tried on each ping when none is known, in angles between beams; the best is kept (footprint)."""

    seabed_widths: Positive = 2.0
    """Seafloor fitted either side of the pipe's span, in major axes M_a (footprint)."""

    relief_widths: Positive = 2.0
    """Width of the seafloor's mound or hollow, in half-widths of the pipe as the beams see it (footprint)."""

    robust_sigmas: Positive = 10.0
    """Scale of the fits' Cauchy loss, in the residual scale (footprint)."""

    refine_peak: bool = True
    """The detector reports the scan's maximum refined between grid points by a parabola; False: the grid point."""


@pydantic.dataclasses.dataclass(frozen=True)
class ParticleFilterParams(DetectorParams):
    """Parameters of the pipe particle filter of seeds/003, section 3 (``sonar_pf``), and its detector's."""

    n_particles: Annotated[int, Ge(1)] = 300
    """Number of particles N (section 3)."""

    walk_speed_mps: NonNegative = 0.4
    """Standard deviation of the random walk of eq. (3) per second, m/s: per ping, times the ping interval."""

    walk_sigma_m: NonNegative = 0.0
    """Standard deviation of the random walk per ping, m, when set; 0: ``walk_speed_mps`` times the ping interval."""

    drift_gain: Annotated[float, Interval(ge=0, le=1)] = 0.9
    """Gain of the smoothed across-track rate of the estimates that shifts the walk of eq. (3); 0: no drift."""

    max_drift_mps: NonNegative = 2.0
    """Largest across-track drift the walk is shifted by, m/s."""

    inject_fraction: Annotated[float, Interval(ge=0, le=1)] = 0.05
    """J: share of the particles re-drawn uniformly over the swath at an update of a lost filter (section 3.4)."""

    lost_ratio: NonNegative = 0.3
    """Fewer samples are injected as the scan's best at the particles nears this share of its best; 0: always J."""

    init_sigma_m: NonNegative = 0.1
    """Spread of the initial particles about a known start position, m."""

    weight_exponent: Positive = 6.0
    """gamma: the particles are weighed by the scan raised to this power (eq. 4 as written: 1; see the notes)."""

    weight_floor: NonNegative = 0.02
    """Each particle's likelihood is at least this share of the best particle's (eq. 4 as written: 0)."""

    peak_halfwidth: NonNegative = 1.0
    """Half-width of the peak whose particles eq. (5) averages, in major axes M_a (section 3.3); 0: all particles."""

    resampler: ResamplerName = "multinomial"
    """Resampling scheme at every update: multinomial (SIR, section 3.4), systematic, stratified or residual."""
