"""The parameters of the sonar trackers and where their defaults come from.

seeds/003 gives the structure of the detector and the filter but almost no
numbers: the pipe's dimensions are "known" (the sequence's calibration
supplies its diameter), L2 carries "a constant weight" of unstated value,
the filter resamples by SIR at every update and injects "some rate J" of new
samples.  The defaults below are reasoned from the sonars and the pipes, and
measured on two sets of sequences, never on ``sonar-test``:

* the wide sonar world's training and dev splits (``sonar-train`` and
  ``sonar-dev``, 16 sequences of 300 pings each: 128-400 beams, 0.5-3 deg
  wide, 5-30 m up, footprints at nadir of 0.1-1.4 pipe diameters, rough
  bare seabed, trenches with spoil berms, spans over sand waves, drift
  across the swath at 0.2-1.2 m/s).  Figures are the mean over the
  sequences of the share of pings correct, ``train / dev``;
* the ``sonar`` suite modelled on the paper's data, ``sonar`` in the figures
  (the mean over its four sequences) or per sequence (autotracker, as-laid,
  concrete, second-pipe).

Each figure is for that one default set back, all else as shipped (the
detector over every ping, the filter over seeds 0-2, ``--init truth``).
As shipped: detector 97.4 / 96.0 %, sonar 90.5 % (93.2, 99.8, 100,
69.0 %); filter 99.2 / 98.2 %, sonar 98.7 % (94.9, 100, 100, 100 %).  The
paper's settings are registered as ``sonar_detector-paper`` and
``sonar_pf-paper`` (:data:`trackbench_sonar.PAPER_DETECTOR`,
:data:`trackbench_sonar.PAPER_FILTER`).  The first is the detector of the
version before this world, value for value: 62.1 / 65.6 %, sonar 88.4 %
(80.2, 93.6, 98.7, 81.2 %).  The second is eqs. (3)-(5) as printed over that
scan, without the departures argued below (it is not the filter of the
version before, which kept them): seed 0, dev 3.1 %, sonar 38.2 % (52.0,
3.3, 97.0, 0.6 %); the mean of all particles falls between the pipe and
the injected samples, and unweighted figures of merit let clutter hold
the weight.

The detector
------------

``likelihood`` ("footprint"; the paper draws an "ellipse").  Eq. (1) as the
paper draws it (:mod:`trackbench_sonar.likelihood`) fits the ellipse
through two consecutive points, which the scan of a wide beam does not
hold, averages its squared differences, which the few returns of the
swath's sparse edge cannot make large, and calls spoil berms proud.  The
default asks the same two questions of the cross-section as the beams'
footprints see it, as evidence over a seafloor with broad relief
(:mod:`trackbench_sonar.evidence`, :mod:`trackbench_sonar.footprint`):
97.4 / 96.0 % against 62.1 / 65.6 % (that is ``sonar_detector-paper``, whose
spike threshold and grid peak are the old ones too), sonar 90.5 % against
88.4 %.  It loses on one sequence of the sonar suite, second-pipe, 69.0 %
against 81.2 %: the new proud pipe beside the tracked half-buried one is the
stronger evidence of a pipe, and only the filter's memory tells them apart
(100 % for ``sonar_pf``).

``beam_width_deg`` (0: the calibration's, else ``unknown_width_spacings``).
The footprint smooths the cross-section by a Gaussian of the beam width at
the candidate's range and angle.  With the beams taken as rays
(``beam_width_deg = 1e-6``): 94.7 / 88.0 %, sonar 90.0 %; on the two dev
sequences whose footprint at nadir is 1.2-1.4 pipe diameters, 24.3 and
48.7 % against 81.7 and 91.3 %.

``unknown_width_spacings`` ((1, 2, 4)).  A swath file need not say how wide
its beams are.  Taking them as wide as they are apart then loses a footprint
of a few beam spacings (calibrations without the beam width: 95.7 / 90.2 %;
the two wide-footprint dev sequences 34.0 and 63.7 %); trying 1, 2 and 4
spacings on each ping and keeping the width whose best candidate has the
most evidence (:class:`trackbench_sonar.evidence.WidestEvidence`):
96.4 / 94.6 %, the two wide-footprint dev sequences 80.0 and 85.3 %, at
3.3 times the detector's time per ping (one run each, side by side, with
every calibration's beam width hidden).

``seabed_widths`` (2).  The seafloor is fitted over two pipe widths either
side of the pipe's span: enough for the mound of ``relief_widths`` to be
told from the pipe.  With 1: 88.0 / 86.0 %, sonar 86.3 %.

``relief_widths`` (2).  The seafloor may carry a mound or a hollow twice as
wide (standard deviation) as the pipe looks through the footprint
(``sqrt(a^2 + sigma^2)``): a berm, a sand wave, a trench's floor is seabed.
Narrower, it explains away the smoothed pipe too (1.5: 93.9 / 90.1 %, sonar
87.4 %); wider, it leaves berms to be taken for the pipe (3: 97.7 / 93.8 %,
sonar 91.2 %, but the dev sequence whose berms are as narrow as its 1.35 m
pipe falls from 100 to 51.3 %).

``robust_sigmas`` (10).  The fits' Cauchy loss of scale ten residual scales
keeps a trench wall, a boulder or a spike in the window from deciding them.
With least squares (``1e6``): 95.6 / 93.0 %, sonar 87.1 % (second-pipe 55.8 %).

``grid_m`` (0.05 m, at most a tenth of ``M_a``).  The resampling grid must
be at least as fine as the sonar at its best, so that resampling loses
nothing, and fine enough that an ellipse of the smallest pipe spans many
points, so that L1 judges a shape rather than its two defining points.  The
RESON-like sequences see the bottom every 0.07 m below the sonar at 8 m
altitude (0.5 deg beams), and their smallest pipe is 0.5 m: 0.05 m gives ten
points across it; a tenth of ``M_a`` keeps ten across the wide world's
0.3 m pipes.  The grid is where the candidates are; the footprint model
fits the returns themselves.

``refine_peak`` (True; the paper's detector reports a candidate).  The
detector reports the vertex of the parabola through the scan's maximum and
its neighbours: where the beams are 3-5 cm apart a grid step is more than
the tolerance.  At the grid point: 96.7 / 95.8 %, sonar 90.1 %.

``spike_window`` (5) and ``spike_heights`` (1; 0.5 before this world).  A
running median of the ranges over five returns follows the pipe wherever
it spans three returns or more, so the returns on a pipe differ from it by
a fraction of the pipe's height; a spike of more moves its return along
the beam (and, far from nadir, by metres across track) and is dropped.
Without the test one spike inside a pipe's span spoils the fit of the
right candidate, and one far out draws a slanted ramp into the profile
(ellipse, sonar suite: detector 4.64 m / 72 %, 4.11 m / 83 %, 1.93 m / 93 %,
4.05 m / 73 % RMSE / correct).  Over sand waves a pipe that spans a trough
stands its diameter and more above the seabed, and with sparse beams
shows one or two returns that a threshold of half its height drops as a
spike: with 0.5, 94.0 / 96.1 %, sonar 89.1 % (autotracker 87.8 %).

``model_sigma_m`` (0.01 m).  The residual scale is ``sqrt(range_sigma_m^2 +
model_sigma_m^2)`` (for the ellipse plus, point by point, the sagitta of
the profile's chord there, :mod:`trackbench_sonar.likelihood`);
``model_sigma_m`` is what the sonar's range noise does not explain: the
pipe's surface (coating joints, growth) and the seabed's finest roughness.
The evidence's maximum does not depend on the scale, only the Cauchy
loss's reach does (``robust_sigmas``).

The ellipse's own settings, measured before this world on the sonar suite
as RMSE / share of pings correct (autotracker, as-laid, concrete,
second-pipe; the filter's figures over eight seeds), with that version as
shipped at detector 3.92 m / 80 %, 3.02 m / 94 %, 0.022 m / 99 %, 2.71 m /
81 % and filter 2.36 m / 95 %, 0.46 m / 99.7 %, 0.014 m / 100 %, 0.18 m /
99.5 %:

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
autotracker, filter 7.10 m / 88 %.  (The footprint model needs no such
threshold: sparse returns carry little evidence.)

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

The filter weighs its particles by the detector's scan: with the default
footprint model, the evidence ``E >= 0``, a ratio scale on which ``E^6``
plays the part ``L^6`` played (``weight_exponent``).

``n_particles`` (300).  The state is one-dimensional; 300 particles over a
swath some 30-50 m wide still put several within a pipe's width of any
position when they are spread uniformly.

``walk_speed_mps`` (0.4 m/s) and ``walk_sigma_m`` (0: from the speed).  The
pipe's across-track position changes with the vehicle's cross-track motion
and the pipe's curvature.  An AUV correcting its track moves sideways at up
to about half a metre per second, so the walk's standard deviation per
ping is 0.4 m/s times the ping interval: 0.16 m for the EM2000-like sonar's
2.5 pings a second, 0.1 m at 4 pings a second.  A fixed 0.1 m per ping lags
behind the autotracker's fastest correction (ellipse: 2.60 m / 92 % there).

``drift_gain`` (0.9; the paper's walk does not drift) and ``max_drift_mps``
(2 m/s).  A walk tuned for a pipe that wanders lags one that drifts
steadily faster: the wide world drifts at up to 1.2 m/s, three times the
walk's speed.  Eq. (3) lets the importance density depend on the past,
``q(. | x_(0:k-1), z_(1:k))``; here the walk is shifted by the pipe's
across-track rate, smoothed from the filter's own estimates
(:class:`trackbench_sonar.particle_filter.AcrossTrackRate`), forgetting
moves faster than ``max_drift_mps`` (jumps between peaks) and moves made
while lost.  Without the drift: 82.2 / 71.5 %, the worst sequence 22.2 %
(sonar 98.5 %); a walk of 1 m/s instead: 94.3 / 96.6 % (worst 38.1 %).
Gains of 0.5 / 0.7: 95.0 / 97.8 % and 98.4 / 98.1 %; limits of 1 / 4 m/s:
94.5 / 93.2 % and 99.2 / 98.2 % (the world's drift plus its meander exceeds
1 m/s).

``inject_fraction`` (0.05) and ``lost_ratio`` (0.3; the paper injects
always).  Section 3.4 keeps "some noise in the system by generating some
rate J of new random samples as done in the initialization step".  With
``J N`` = 15 new samples per ping, one lands within a pipe's likelihood
peak (a few tenths of a metre of some 25 m where pipes are sought) every
six or seven pings, so that a lost pipe is found again within a few
seconds (without them the ellipse filter never found the autotracker's
pipe again after its covered stretch: 2.42 m / 81 %).  But a sample that
lands on a stronger rival is weighed up at once: the evidence of the proud
new pipe of second-pipe is twice that of the half-buried tracked one.  So
the rate follows how lost the filter is
(:func:`trackbench_sonar.particle_filter.injection_rate`): ``J (1 - r /
0.3)`` where ``r`` is the scan's best at the particles over its best
anywhere, none while the particles hold at least 0.3 of the best.  Always
``J``: 99.2 / 98.2 %, but sonar 91.7 % (second-pipe 73.1 %); thresholds
0.2 / 0.5: sonar 98.4 / 94.6 %; ``J`` = 0.1: no change (99.2 / 98.2 %,
sonar 98.6 %).

``init_sigma_m`` (0.1 m): the spread about a known start.

``weight_exponent`` (6; eq. 4 reads 1).  The scan of eq. (1) is a figure of
merit, not a probability.  Raised to the sixth power a candidate at 90 % of
the best still keeps half its weight (``0.9^6 = 0.53``) while clutter at
half the best's evidence keeps 2 %, the same reasoning as the condensation
tracker's weight exponent.  With 1: 96.7 / 97.3 % (the worst sequence 56.8 %),
sonar 98.1 %; with 3: 99.0 / 98.1 %.  (With the ellipse's scan, before this
world: 4.41 m / 82 %, 10.1 m / 59 %, 0.026 m / 99.7 %, 12.0 m / 40 %.)

``weight_floor`` (0.02; eq. 4 reads 0).  Every particle keeps at least 2 %
of the best particle's likelihood: a ping whose scan misses the pipe where
it is (a lost beam, the pipe's own shadow) then weakens the particles on it
fifty-fold instead of wiping them out for the samples injected elsewhere.
It also keeps the weights defined when the scan is zero at every particle.
Without it: 98.9 / 97.7 %, sonar 98.5 % (ellipse: 2.74 m / 94 %, 0.51 m /
99.6 %, 0.013 m / 100 %, 0.30 m / 99.8 %).

``peak_halfwidth`` (1 pipe width; 0 is eq. 5 as written).  The estimate
is eq. (5) over the particles of the heaviest peak
(:mod:`trackbench_sonar.estimate`): the mean of all particles falls
between the pipe and whatever else holds weight (the injected samples, a
second pipe), more than the sonar's resolution away from both.  Over all
particles: 98.6 / 98.0 %, the RMSE 0.11 / 0.08 m against 0.04 / 0.05 m
(sonar 98.5 %; autotracker 1.88 m against 2.52 m: a mean straddles its
covered stretch with smaller errors than a wrong peak).

All of the filter's departures set back at once, on the default scan
(exponent 1, no floor, the mean of all particles, no drift, injection at
J always): 69.1 / 63.9 %, sonar 83.5 %.

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
    :class:`pydantic.ValidationError`.  Fields marked (ellipse) or
    (footprint) serve only that form of eq. (1) (``likelihood``).
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
    """Share of the half-width M_a/2 about the centre whose points L1 compares with the ellipse, in (0, 1] (ellipse)."""

    min_pipe_returns: NonNegative = 2.0
    """Candidates are scored only where the beams land at most M_a / min_pipe_returns apart; 0: everywhere (ellipse)."""

    proud_weight: NonNegative = 1.0
    """The constant weight on L2 in eq. (1) (ellipse)."""

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
