"""One ping of a multibeam echo sounder: beams cast on the seabed and the pipes.

A multibeam echo sounder sends a fan of equiangular beams across the track
and measures, for each, the range to the bottom; the returns, converted to
across-track position and depth, are not evenly spaced across the track,
which is why the detector of seeds/003 (section 2) resamples them.  A
ping is simulated in three moves:

1. :func:`first_ranges`: each ray from the transducer stops at the first
   surface it meets: the seabed (a height field, linear between grid
   columns) or a pipe's elliptical cross-section, so a proud pipe hides
   the seabed behind it.  The seabed is cast exactly and fast: seen from
   the transducer, a point of a profile at across-track ``x >= 0`` and
   depth ``z`` lies at the angle ``atan2(x, z)`` from the vertical; the
   running maximum of that angle along the profile is the horizon, and a
   ray at angle ``theta`` first meets the profile in the segment where the
   horizon first reaches ``theta`` (a sorted search), inside which the
   crossing is linear.  Port rays are cast on the mirrored profile.
2. :func:`beam_ranges`: a beam is not a ray; its return mixes the ranges
   across its width, weighted by a Gaussian beam pattern and by the
   strength of each echo, which rounds off edges and puts returns into the
   shadow of a pipe, as real swaths show.
3. :func:`degrade_ranges`: range noise that grows as the echo weakens with
   the incidence angle (towards the outer beams, and on a pipe's flanks),
   outlier spikes, quantisation to the range resolution, and beams without
   a return, more of them where the echo is weak.

:func:`swath_from_ranges` turns the ranges into a
:class:`benchmark.modalities.sonar.model.Swath`.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from benchmark.modalities.sonar.model import Swath
from benchmark.modalities.sonar.scenes.spec import SonarSpec

SUB_RAYS = 5
"""Rays per beam that has a width: the axis and two on each side, out to the beam width."""


@dataclass(frozen=True)
class Ellipse:
    """A pipe's cross-section in the plane of one swath, in m.

    Attributes
    ----------
    across_m, depth_m : float
        Centre (the pipe's axis), depth below the transducer.
    half_width_m, half_height_m : float
        Horizontal and vertical semi-axes.
    """

    across_m: float
    depth_m: float
    half_width_m: float
    half_height_m: float


def beam_angles(n_beams: int, swath_angle: float) -> np.ndarray:
    """Angles of equiangular beams from the vertical, port (negative) to starboard.

    Parameters
    ----------
    n_beams : int
        Beams in the fan.
    swath_angle : float
        Full opening, rad.

    Returns
    -------
    numpy.ndarray
        ``n_beams`` angles spaced ``swath_angle / (n_beams - 1)`` apart.

    References
    ----------
    seeds/003, section 2: "the data sampling rate is not constant".
    """
    return np.linspace(-swath_angle / 2.0, swath_angle / 2.0, n_beams)


def _cast_side(x: np.ndarray, z: np.ndarray, theta: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Ranges and incidence cosines of rays at ``theta >= 0`` on a profile starting below the transducer."""
    ranges = np.full(theta.shape, np.nan)
    cos_incidence = np.full(theta.shape, np.nan)
    horizon = np.maximum.accumulate(np.arctan2(x, z))
    j = np.searchsorted(horizon, theta, side="left")
    hit = j < len(x)
    j = np.clip(j[hit], 1, len(x) - 1)
    sin, cos = np.sin(theta[hit]), np.cos(theta[hit])
    before = x[j - 1] * cos - z[j - 1] * sin
    after = x[j] * cos - z[j] * sin
    f = np.clip(before / np.where(before == after, -1.0, before - after), 0.0, 1.0)
    dx, dz = x[j] - x[j - 1], z[j] - z[j - 1]
    ranges[hit] = np.hypot(x[j - 1] + f * dx, z[j - 1] + f * dz)
    cos_incidence[hit] = np.abs(cos * dx - sin * dz) / np.hypot(dx, dz)
    return ranges, cos_incidence


def seabed_ranges(across: np.ndarray, depth: np.ndarray, angles: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Range along each ray to where it first meets the seabed, and the incidence there.

    Parameters
    ----------
    across : numpy.ndarray
        Grid columns, symmetric with the middle one at 0.
    depth : numpy.ndarray
        Seabed depth below the transducer at each column.
    angles : numpy.ndarray
        Ray angles from the vertical in the level frame, starboard
        positive.

    Returns
    -------
    ranges : numpy.ndarray
        ``nan`` where a ray leaves the grid without meeting the seabed.
    cos_incidence : numpy.ndarray
        Cosine of the angle between the ray and the seabed's normal at the
        hit (``nan`` where there is none).

    References
    ----------
    seeds/003, section 2: the scan whose points the detector fits.
    """
    middle = len(across) // 2
    ranges, cos_incidence = np.empty(angles.shape), np.empty(angles.shape)
    starboard = angles >= 0
    ranges[starboard], cos_incidence[starboard] = _cast_side(across[middle:], depth[middle:], angles[starboard])
    ranges[~starboard], cos_incidence[~starboard] = _cast_side(
        -across[middle::-1], depth[middle::-1], -angles[~starboard]
    )
    return ranges, cos_incidence


def ellipse_ranges(angles: np.ndarray, ellipse: Ellipse) -> tuple[np.ndarray, np.ndarray]:
    """Range along each ray to where it enters an ellipse, and the incidence there.

    Parameters
    ----------
    angles : numpy.ndarray
        Ray angles from the vertical, starboard positive.
    ellipse : Ellipse
        The cross-section, which must not contain the transducer.

    Returns
    -------
    ranges : numpy.ndarray
        ``inf`` where a ray misses.
    cos_incidence : numpy.ndarray
        Cosine of the angle between the ray and the ellipse's normal at the
        entry point (``nan`` where it misses).

    References
    ----------
    seeds/003, section 2: the pipe's cross-section, axes ``[M_a, M_i]``.
    """
    sin, cos = np.sin(angles), np.cos(angles)
    a2, b2 = ellipse.half_width_m**2, ellipse.half_height_m**2
    a = sin**2 / a2 + cos**2 / b2
    b = -2.0 * (sin * ellipse.across_m / a2 + cos * ellipse.depth_m / b2)
    c = ellipse.across_m**2 / a2 + ellipse.depth_m**2 / b2 - 1.0
    disc = b**2 - 4.0 * a * c
    t = (-b - np.sqrt(np.maximum(disc, 0.0))) / (2.0 * a)
    hit = (disc >= 0) & (t > 0)
    nx = (t * sin - ellipse.across_m) / a2
    nz = (t * cos - ellipse.depth_m) / b2
    cos_incidence = np.abs(sin * nx + cos * nz) / np.maximum(np.hypot(nx, nz), 1e-300)
    return np.where(hit, t, np.inf), np.where(hit, cos_incidence, np.nan)


def first_ranges(
    across: np.ndarray, depth: np.ndarray, angles: np.ndarray, ellipses: Sequence[Ellipse]
) -> tuple[np.ndarray, np.ndarray]:
    """Range along each ray to the first surface it meets, seabed or pipe, and the incidence there.

    Parameters
    ----------
    across, depth : numpy.ndarray
        The seabed profile of the ping (see :func:`seabed_ranges`).
    angles : numpy.ndarray
        Ray angles from the vertical, starboard positive.
    ellipses : sequence of Ellipse
        Cross-sections of the pipes that stand above the seabed.

    Returns
    -------
    ranges : numpy.ndarray
        ``nan`` where a ray meets nothing.
    cos_incidence : numpy.ndarray
        Cosine of the incidence angle at the hit, ``nan`` where none.

    References
    ----------
    seeds/003, section 2 and Figs. 1, 3-4: scans of proud pipes.
    """
    ranges, cos_incidence = seabed_ranges(across, depth, angles)
    for ellipse in ellipses:
        pipe, pipe_cos = ellipse_ranges(angles, ellipse)
        nearer = pipe < np.nan_to_num(ranges, nan=np.inf)
        ranges = np.where(nearer, pipe, ranges)
        cos_incidence = np.where(nearer, pipe_cos, cos_incidence)
    return ranges, cos_incidence


def beam_ranges(
    across: np.ndarray,
    depth: np.ndarray,
    axes: np.ndarray,
    ellipses: Sequence[Ellipse],
    beam_width: float,
    max_range_m: float,
) -> tuple[np.ndarray, np.ndarray]:
    """The range each beam reports: its rays' ranges weighted by beam pattern and echo strength.

    Each beam is :data:`SUB_RAYS` rays out to ``beam_width`` on either side
    of its axis, weighted by a Gaussian whose full width at half maximum is
    ``beam_width`` times the strength of the echo, which follows Lambert's
    law, ``cos^2`` of the incidence angle (a pipe's flank echoes less than
    its crown).  Rays beyond ``max_range_m`` or without a hit drop out, and
    a beam whose axis has no hit has no return.

    Parameters
    ----------
    across, depth : numpy.ndarray
        The seabed profile of the ping.
    axes : numpy.ndarray
        Beam axes from the vertical in the level frame.
    ellipses : sequence of Ellipse
        The pipes that stand above the seabed.
    beam_width : float
        Across-track beam width, rad; 0 casts the axis alone.
    max_range_m : float
        Range gate.

    Returns
    -------
    ranges : numpy.ndarray
        One range per beam, ``nan`` for no return.
    incidence : numpy.ndarray
        Incidence angle of each beam's axis on the surface it meets, rad
        (``nan`` for no return).

    References
    ----------
    seeds/003, sections 4.1-4.2: the EM2000's and the RESON 8125's beams.
    """
    if beam_width > 0:
        offsets = np.linspace(-1.0, 1.0, SUB_RAYS) * beam_width
        sigma = beam_width / (2.0 * math.sqrt(2.0 * math.log(2.0)))
        pattern = np.exp(-0.5 * (offsets / sigma) ** 2)
    else:
        offsets, pattern = np.zeros(1), np.ones(1)
    rays, cos_incidence = first_ranges(across, depth, (axes[:, None] + offsets[None, :]).ravel(), ellipses)
    shape = (len(axes), len(offsets))
    rays, cos_incidence = rays.reshape(shape), cos_incidence.reshape(shape)
    hit = np.isfinite(rays) & (rays <= max_range_m)
    weights = np.where(hit, pattern * np.maximum(cos_incidence, 1e-3) ** 2, 0.0)
    total = np.sum(weights, axis=1)
    mean = np.sum(np.where(hit, rays, 0.0) * weights, axis=1) / np.where(total > 0, total, 1.0)
    axis = len(offsets) // 2
    incidence = np.arccos(np.clip(cos_incidence[:, axis], 0.0, 1.0))
    return np.where(hit[:, axis], mean, np.nan), np.where(hit[:, axis], incidence, np.nan)


def degrade_ranges(
    ranges: np.ndarray,
    incidence: np.ndarray,
    sonar: SonarSpec,
    noise_rng: np.random.Generator,
    missing_rng: np.random.Generator,
    outlier_rng: np.random.Generator,
) -> np.ndarray:
    """The ranges as the sonar reports them: noisy, spiky, quantised, with gaps.

    The weaker the echo, the noisier the range and the likelier it is lost;
    the echo weakens with the incidence angle ``i`` on the surface, so
    that on a level seabed the outer beams are the worst, but so are a
    pipe's flanks and the far walls of a trench.  The range error has the
    standard deviation ``range_sigma_m (1 + (outer_sigma_factor - 1)
    sin^2(i) / sin^2(h))`` and a beam is lost with probability
    ``missing_nadir + (missing_outer - missing_nadir) (i / h)^4`` (at most
    0.95), where ``h`` is the half opening: at ``i = h`` they are the
    settings' values for the outermost beams.

    Parameters
    ----------
    ranges : numpy.ndarray
        True ranges of the beams (``nan`` for none).
    incidence : numpy.ndarray
        Incidence angle of each beam on the surface it meets, rad.
    sonar : SonarSpec
        Noise, resolution, spike and gap settings.
    noise_rng, missing_rng, outlier_rng : numpy.random.Generator
        Independent sources of the range noise, the gaps and the spikes;
        each is consumed the same way for a given number of beams.

    Returns
    -------
    numpy.ndarray
        Reported ranges, ``nan`` for beams without a return.

    References
    ----------
    seeds/003, section 2: the detector resamples the scan and must cope
    with what the sonar gets wrong.
    """
    n = len(ranges)
    half = sonar.half_swath
    incidence = np.nan_to_num(incidence, nan=half)
    growth = (np.sin(incidence) / math.sin(half)) ** 2
    sigma = sonar.range_sigma_m * (1.0 + (sonar.outer_sigma_factor - 1.0) * growth)
    noisy = ranges + sigma * noise_rng.standard_normal(n)
    spike = outlier_rng.random(n) < sonar.outlier_rate
    jump = outlier_rng.laplace(0.0, sonar.outlier_scale_m, n)
    noisy = np.where(spike, ranges + jump, noisy)
    noisy = np.maximum(noisy, 0.2 * ranges)
    if sonar.range_resolution_m > 0:
        noisy = np.round(noisy / sonar.range_resolution_m) * sonar.range_resolution_m
    p_missing = sonar.missing_nadir + (sonar.missing_outer - sonar.missing_nadir) * (incidence / half) ** 4
    missing = missing_rng.random(n) < np.minimum(p_missing, 0.95)
    noisy[missing] = np.nan
    return noisy


def swath_from_ranges(ranges: np.ndarray, axes: np.ndarray) -> Swath:
    """Returns at ``ranges`` along beams at ``axes`` (level frame) as a :class:`Swath`.

    Parameters
    ----------
    ranges : numpy.ndarray
        One per beam, ``nan`` for none.
    axes : numpy.ndarray
        Beam angles from the vertical, port to starboard.

    Returns
    -------
    Swath
        ``nan`` in both arrays where a beam has no return.
    """
    return Swath(across_m=ranges * np.sin(axes), depth_m=ranges * np.cos(axes))
