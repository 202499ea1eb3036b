"""The world round the boats in the stereo images: the sea and the shoreline.

Everything here is built once per sequence from a
:class:`~benchmark.modalities.stereo.scenes.image_spec.StereoRenderSpec` and a random
generator, and sampled per pixel by :mod:`benchmark.modalities.stereo.scenes.render`.

* The sea is the plane ``camera_height_m`` below the cameras.  Its
  brightness comes from a wave field in North-East coordinates, so the
  pattern sits on the water and shows the disparity of the distance it is
  at.  The field is filtered white noise with a directional spectrum of
  wind waves around ``wave_length_m`` and a swell eight times longer
  (both running down-sun), tiling seamlessly;
  :class:`SeaTexture` holds it as a pyramid whose level ``L`` keeps only
  wavelengths longer than ``2^(L+1)`` texels, so a distant row samples a
  level whose texels match its pixel footprint.  The shading is the wave
  slope towards the sun; the steepest sun-facing slopes glitter.
* The shoreline is a ring ``shore_distance_m`` about the North-East origin,
  with a height profile round it (hills, stretches of open horizon, and a
  town of blocks with rows of windows) and a colour map over
  ``(azimuth, height)`` (:class:`Shore`).  It is kilometres away, so its
  disparity is a small fraction of a pixel: clutter for the colour tracker
  and the block matcher, not range.

The target boat is :mod:`benchmark.modalities.stereo.scenes.boat`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import cv2
import numpy as np

from benchmark.modalities.stereo.scenes.image_spec import StereoRenderSpec

SEA_TEXELS = 512
"""The wave field is ``SEA_TEXELS`` x ``SEA_TEXELS`` texels and tiles the plane."""

SEA_TEXELS_PER_WAVE = 10.0
"""Texels per dominant wave length at the finest level."""

SWELL_TEXELS = 80.0
"""Texels per swell length at the finest level (eight wind waves)."""

SWELL_SHARE = 0.3
"""Share of the slope variance in the swell; the rest is in the wind waves."""

SEA_LEVELS = 7
"""Pyramid levels of the wave field (level ``L`` has texels ``2^L`` times larger)."""

GLINT_THRESHOLD = 1.6
"""Wave slopes (in standard deviations) above which the sea glitters."""

SHORE_BINS = 4096
"""Azimuth bins of the shoreline round the full circle."""

SHORE_ROWS = 128
"""Height bins of the shoreline colour map, from the waterline to the tallest hill."""

SHORE_SMOOTH_BINS = 2.0
"""Azimuthal blur of the shoreline (bins): a pixel there spans several bins."""


@dataclass(frozen=True)
class SeaTexture:
    """The wave field as a pyramid of brightness maps.

    Attributes
    ----------
    levels : tuple of numpy.ndarray
        Level ``L`` has shape ``(n / 2^L, n / 2^L)``, ``float32``: the wave
        slope towards the sun, in standard deviations of level 0.  The
        renderer brightens the sea by it and makes slopes above
        :data:`GLINT_THRESHOLD` glitter.
    texel_m : float
        Texel size of level 0, m; level ``L`` has ``texel_m * 2^L``.
    """

    levels: tuple[np.ndarray, ...]
    texel_m: float

    @property
    def period_m(self) -> float:
        """Length after which the pattern repeats, m."""
        return self.texel_m * self.levels[0].shape[0]


def sea_texture(spec: StereoRenderSpec, rng: np.random.Generator) -> SeaTexture:
    """The wave field of a sequence.

    Parameters
    ----------
    spec : StereoRenderSpec
        ``wave_length_m`` and ``sun_azimuth_deg`` (waves run down-sun and are
        shaded by their slope towards it).
    rng : numpy.random.Generator
        Source of the white noise (``SEA_TEXELS^2`` normal draws).

    Returns
    -------
    SeaTexture
        Rows of the maps run North (``X``), columns East (``Y``).
    """
    n = SEA_TEXELS
    texel = spec.wave_length_m / SEA_TEXELS_PER_WAVE
    white = np.fft.rfft2(rng.standard_normal((n, n)))
    k_north = np.fft.fftfreq(n)[:, None]
    k_east = np.fft.rfftfreq(n)[None, :]
    k = np.maximum(np.hypot(k_north, k_east), 1e-12)
    sun = math.radians(spec.sun_azimuth_deg)
    toward_sun = k_north * math.cos(sun) + k_east * math.sin(sun)
    # Most energy in waves running along the sun's azimuth; the slope towards the sun is i 2 pi k_sun times the height.
    spread = 0.3 + (toward_sun / k) ** 4
    slope_spectrum = np.zeros_like(white)
    for texels, share in ((SEA_TEXELS_PER_WAVE, 1.0 - SWELL_SHARE), (SWELL_TEXELS, SWELL_SHARE)):
        band = np.exp(-0.5 * (np.log(k * texels) / 0.5) ** 2)
        part = white * band * spread * (2j * math.pi) * toward_sun
        part[0, 0] = 0.0
        # Scale each band to its share of the slope variance (Parseval: the rfft2 sum counts most terms twice).
        slope_spectrum += part * math.sqrt(share / max(float(np.fft.irfft2(part, s=(n, n)).var()), 1e-30))
    slope = np.fft.irfft2(slope_spectrum, s=(n, n))
    scale = 1.0 / max(float(slope.std()), 1e-12)
    levels = [(slope * scale).astype(np.float32)]
    for level in range(1, SEA_LEVELS):
        size = n >> level
        coarse = np.fft.irfft2(_crop_spectrum(slope_spectrum, size), s=(size, size)) * (size / n) ** 2
        levels.append((coarse * scale).astype(np.float32))
    return SeaTexture(levels=tuple(levels), texel_m=texel)


def _crop_spectrum(spectrum: np.ndarray, size: int) -> np.ndarray:
    """The ``rfft2`` spectrum of a field resampled to ``size`` x ``size``: low frequencies, tapered."""
    half = size // 2
    rows = np.concatenate((spectrum[:half], spectrum[-half:]))[:, : half + 1].copy()
    k_rows = np.abs(np.fft.fftfreq(size))[:, None] * 2.0
    k_cols = np.fft.rfftfreq(size)[None, :] * 2.0
    # Fade out towards the new Nyquist frequency so the coarse level does not ring.
    rows *= np.exp(-0.5 * (np.hypot(k_rows, k_cols) / 0.55) ** 4)
    return rows


@dataclass(frozen=True)
class Shore:
    """The shoreline ring: heights and colours round the North-East origin.

    Attributes
    ----------
    radius_m : float
        Distance of the shoreline from the origin.
    heights_m : numpy.ndarray
        Shape ``(SHORE_BINS,)``: height of the skyline at azimuth bin ``i``
        (azimuth ``2 pi i / SHORE_BINS`` clockwise from north); 0 where the
        horizon is open sea.
    colours : numpy.ndarray
        Shape ``(SHORE_ROWS, SHORE_BINS, 3)``, ``float32`` BGR: the colour
        at height row ``j`` (``j / (SHORE_ROWS - 1)`` of ``top_m``), before
        haze.
    top_m : float
        Height of the top row of ``colours``.
    """

    radius_m: float
    heights_m: np.ndarray
    colours: np.ndarray
    top_m: float


def _periodic_noise(rng: np.random.Generator, n: int, correlation_bins: float) -> np.ndarray:
    """Smooth periodic 1-D noise with unit standard deviation."""
    spectrum = np.fft.rfft(rng.standard_normal(n))
    frequency = np.fft.rfftfreq(n)
    spectrum *= np.exp(-0.5 * (frequency * 2.0 * math.pi * correlation_bins) ** 2)
    spectrum[0] = 0.0
    field = np.fft.irfft(spectrum, n)
    return field / max(float(field.std()), 1e-12)


def _blur_round(image: np.ndarray, sigma: float) -> np.ndarray:
    """Gaussian blur along the columns of a map that wraps round the full circle."""
    pad = int(math.ceil(4.0 * sigma))
    wrapped = np.concatenate((image[:, -pad:], image, image[:, :pad]), axis=1)
    blurred = cv2.GaussianBlur(wrapped, (0, 0), sigmaX=sigma, sigmaY=1e-3, borderType=cv2.BORDER_REPLICATE)
    return np.ascontiguousarray(blurred[:, pad:-pad])


def shoreline(spec: StereoRenderSpec, rng: np.random.Generator) -> Shore:
    """The shoreline of a sequence: hills, gaps of open sea and a town.

    Parameters
    ----------
    spec : StereoRenderSpec
        ``shore_distance_m`` and ``shore_height_m``.
    rng : numpy.random.Generator
        Source of the profile, the buildings and the colour noise.

    Returns
    -------
    Shore
    """
    n, rows = SHORE_BINS, SHORE_ROWS
    top = spec.shore_height_m
    ridge = _periodic_noise(rng, n, 40.0) + 0.5 * _periodic_noise(rng, n, 8.0)
    land = _periodic_noise(rng, n, 150.0)
    hills = top * np.clip(0.45 + 0.25 * ridge, 0.0, 1.0) * np.clip(2.0 * (land + 0.6), 0.0, 1.0)
    town = _periodic_noise(rng, n, 120.0) > 0.7
    z = np.linspace(0.0, top, rows)[:, None]
    greens = np.array((60.0, 95.0, 85.0)) + 25.0 * rng.standard_normal((1, n, 1)).clip(-2, 2)
    greens = np.broadcast_to(greens, (rows, n, 3)).copy()
    greens += 12.0 * rng.standard_normal((rows, n, 1))
    greens += np.array((20.0, 10.0, 0.0)) * (z / top)[..., None]
    heights = hills.copy()
    colours = greens
    start = 0
    while start < n:
        width = int(rng.integers(2, 12))
        stop = min(start + width, n)
        if town[start]:
            building = float(rng.uniform(0.04, 0.25)) * top
            if building > heights[start:stop].min():
                heights[start:stop] = np.maximum(heights[start:stop], building)
                facade = rng.uniform(110.0, 225.0) * np.array((1.0, 0.97, 0.93))
                block = np.broadcast_to(facade, (rows, stop - start, 3)).copy()
                floors = (z[:, 0] % 3.5) < 1.4
                block[floors, :: 2] *= 0.45
                block[z[:, 0] > building] = colours[z[:, 0] > building, start:stop]
                colours[:, start:stop] = block
        start = stop + int(rng.integers(0, 3))
    colours = _blur_round(np.clip(colours, 0.0, 255.0).astype(np.float32), SHORE_SMOOTH_BINS)
    heights = _blur_round(heights.reshape(1, -1).astype(np.float32), SHORE_SMOOTH_BINS)
    return Shore(radius_m=spec.shore_distance_m, heights_m=heights.ravel(), colours=colours, top_m=top)


