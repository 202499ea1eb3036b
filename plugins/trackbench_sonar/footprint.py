"""The pipe's cross-section as wide beams see it.

seeds/003 (section 2) fits the pipe's known cross-section to the scan.  A
multibeam return is not a point of the bottom but the range averaged over
the beam's footprint: a beam of (-3 dB) width ``phi`` meets a level
bottom at depth ``z`` and angle ``theta`` on a strip ``z phi / cos^2
theta`` wide across the track
(:func:`benchmark.modalities.sonar.model.beam_footprint` with the beam
width for the spacing).  Once that strip is half the pipe's diameter or
more the scan no longer shows the pipe's arc but a smooth bump, lower and
wider than the pipe, with sloping sides where the arc met the seabed.

This module gives that bump.  Across the track, the height of a proud pipe
above the seafloor it stands on is, at offset ``u`` from its axis, the
*pedestal* ``s`` (the height of its centre above the seafloor) plus the
upper half of its cross-section,

    H(u) = s box(u / a) + b sqrt(1 - (u / a)^2)       for |u| < a, else 0,

with ``a = M_a / 2`` and ``b = M_i / 2`` (the sides below the widest point
are hidden from above, so the profile drops straight down there).  A pipe
suspended over a trough has a taller pedestal; a pipe buried to its centre
none.  The beams see ``H`` convolved with the footprint, taken as a
Gaussian whose full width at half maximum is the footprint at the pipe:

* ``box * G`` is ``Phi((v + 1) / r) - Phi((v - 1) / r)`` (``v = u / a``,
  ``r = sigma / a``, ``Phi`` the normal distribution);
* the semi-ellipse ``* G`` has no closed form; it is tabulated once for the
  unit semicircle over ``v`` and ``r`` and interpolated
  (:class:`SeenCrossSection`).

Both are linear in the pipe's unknowns (the pedestal and the seafloor), so
the model stays a linear least-squares fit (:mod:`trackbench_sonar.evidence`).
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np

from benchmark.modalities.sonar.model import beam_footprint
from trackbench_sonar.cross_section import CrossSection

FWHM_PER_SIGMA = 2.0 * math.sqrt(2.0 * math.log(2.0))
"""Full width at half maximum of a Gaussian in standard deviations."""

TABLE_OFFSET_STEP = 0.02
"""Step of the table of the smoothed semicircle in offsets ``u / a``."""

TABLE_SIGMA_STEP = 0.05
"""Step of the table in footprints ``sigma / a``."""

TABLE_MAX_SIGMA = 4.0
"""Largest footprint ``sigma / a`` tabulated (a footprint 4.7 diameters wide); wider ones use the widest."""

TABLE_REACH = 1.0 + 6.0 * TABLE_MAX_SIGMA
"""Largest offset ``|u| / a`` tabulated; beyond it the smoothed semicircle is taken as 0."""


def footprint_sigma(across_m: np.ndarray, depth_m: np.ndarray, beam_width: float) -> np.ndarray:
    """Standard deviation of a beam's across-track footprint at points of the swath plane, m.

    Parameters
    ----------
    across_m, depth_m : numpy.ndarray
        Points, depth positive down.
    beam_width : float
        The beam's -3 dB width across the track, rad; 0 gives 0.

    Returns
    -------
    numpy.ndarray
        ``z phi / cos^2 theta`` (the footprint's full width at half
        maximum) over :data:`FWHM_PER_SIGMA`; ``inf`` at or above the
        transducer.

    References
    ----------
    seeds/003, section 4 (the EM2000's 1.5 deg and the RESON 8125's 0.5 deg
    beams); :func:`benchmark.modalities.sonar.model.beam_footprint`.
    """
    if beam_width <= 0.0:
        return np.zeros(np.broadcast(np.asarray(across_m), np.asarray(depth_m)).shape)
    return beam_footprint(across_m, depth_m, beam_width) / FWHM_PER_SIGMA


def _semicircle_area(t: np.ndarray) -> np.ndarray:
    """``integral_{-1}^{t} sqrt(1 - x^2) dx`` for ``t`` clipped to [-1, 1]."""
    x = np.clip(t, -1.0, 1.0)
    return 0.5 * (x * np.sqrt(1.0 - x * x) + np.arcsin(x)) + 0.25 * math.pi


@functools.cache
def semicircle_table() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Offsets ``v``, footprints ``r`` and ``(sqrt(1 - t^2) * N(0, r))(v)`` on their grid (computed once).

    Each row is the semicircle averaged over the cells of the offset grid
    (exact, from its area), smoothed by a Gaussian through the Fourier
    transform, on a grid padded so that nothing wraps around.
    """
    sigmas = np.arange(0.0, TABLE_MAX_SIGMA + TABLE_SIGMA_STEP / 2, TABLE_SIGMA_STEP)
    offsets = np.arange(-TABLE_REACH, TABLE_REACH + TABLE_OFFSET_STEP / 2, TABLE_OFFSET_STEP)
    half = TABLE_OFFSET_STEP / 2.0
    cells = (_semicircle_area(offsets + half) - _semicircle_area(offsets - half)) / TABLE_OFFSET_STEP
    size = 1 << int(math.ceil(math.log2(2 * offsets.size)))
    spectrum = np.fft.rfft(cells, size)
    frequency = np.fft.rfftfreq(size, TABLE_OFFSET_STEP)
    gain = np.exp(-2.0 * (math.pi * frequency[None, :] * sigmas[:, None]) ** 2)
    table = np.fft.irfft(spectrum[None, :] * gain, size, axis=1)[:, : offsets.size]
    table[0] = np.sqrt(np.clip(1.0 - offsets * offsets, 0.0, None))
    return offsets, sigmas, np.clip(table, 0.0, 1.0)


def smoothed_semicircle(offset: np.ndarray, sigma: np.ndarray) -> np.ndarray:
    """The unit semicircle ``sqrt(1 - v^2)`` (0 outside ``|v| < 1``) convolved with ``N(0, sigma^2)``.

    Parameters
    ----------
    offset, sigma : numpy.ndarray
        Offsets ``v`` and footprints ``r >= 0``, in units of the
        semicircle's radius; broadcast together.

    Returns
    -------
    numpy.ndarray
        Bilinear in a table (:data:`TABLE_OFFSET_STEP`, :data:`TABLE_SIGMA_STEP`);
        footprints beyond :data:`TABLE_MAX_SIGMA` use the widest row, and
        offsets beyond :data:`TABLE_REACH` give 0.
    """
    offsets, sigmas, table = semicircle_table()
    v, r = np.broadcast_arrays(np.asarray(offset, dtype=float), np.asarray(sigma, dtype=float))
    row = np.clip(r / TABLE_SIGMA_STEP, 0.0, sigmas.size - 1.000001)
    column = np.clip((v - offsets[0]) / TABLE_OFFSET_STEP, 0.0, offsets.size - 1.000001)
    i, j = row.astype(np.int64), column.astype(np.int64)
    fi, fj = row - i, column - j
    near = table[i, j] * (1.0 - fj) + table[i, j + 1] * fj
    far = table[i + 1, j] * (1.0 - fj) + table[i + 1, j + 1] * fj
    return np.where(np.abs(v) < TABLE_REACH, near * (1.0 - fi) + far * fi, 0.0)


def smoothed_box(offset: np.ndarray, sigma: np.ndarray) -> np.ndarray:
    """The unit box (1 for ``|v| < 1``) convolved with ``N(0, sigma^2)``: ``Phi((v+1)/r) - Phi((v-1)/r)``."""
    v = np.asarray(offset, dtype=float)
    r = np.maximum(np.asarray(sigma, dtype=float), 1e-9)
    from scipy.special import ndtr  # here, so that loading the plugin does not import SciPy

    return ndtr((v + 1.0) / r) - ndtr((v - 1.0) / r)


@dataclass(frozen=True)
class SeenCrossSection:
    """A pipe's cross-section as beams with a Gaussian footprint see it from above.

    Parameters
    ----------
    section : CrossSection
        The pipe's axes ``[M_a, M_i]``.

    References
    ----------
    seeds/003, section 2 (the cross-section of axes ``[M_a, M_i]`` drawn on
    the scan).
    """

    section: CrossSection

    def arc(self, offset_m: np.ndarray, sigma_m: np.ndarray) -> np.ndarray:
        """Height of the upper half of the cross-section above its centre, as seen, m.

        Parameters
        ----------
        offset_m : numpy.ndarray
            Across-track offsets from the pipe's axis, m.
        sigma_m : numpy.ndarray
            Footprint standard deviation (:func:`footprint_sigma`), m;
            broadcast against ``offset_m``.
        """
        a, b = self.section.half_width_m, self.section.half_height_m
        return b * smoothed_semicircle(np.asarray(offset_m) / a, np.asarray(sigma_m) / a)

    def pedestal(self, offset_m: np.ndarray, sigma_m: np.ndarray) -> np.ndarray:
        """The pipe's span ``|u| < M_a / 2`` as seen: the share of a unit pedestal each offset shows."""
        a = self.section.half_width_m
        return smoothed_box(np.asarray(offset_m) / a, np.asarray(sigma_m) / a)

    def seen_half_width(self, sigma_m: np.ndarray) -> np.ndarray:
        """``sqrt(a^2 + sigma^2)``: the scale of the pipe as seen, m."""
        return np.hypot(self.section.half_width_m, np.asarray(sigma_m, dtype=float))
