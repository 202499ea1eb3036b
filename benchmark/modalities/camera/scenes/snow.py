"""Marine snow: particles in the water column, lit by the lamps, seen in and out of focus.

The particles are placed once per sequence in the water the camera passes
through (a Poisson number, uniform in a box around the trajectory), with
log-normal diameters, and sink slowly, so the vehicle flies through them
and they stream past as in real footage instead of flickering from frame to
frame.  A particle is a small grey scatterer: it sends back a share
:data:`SNOW_ALBEDO` of the light that reaches it (the lamps' and the
daylight), attenuated on the way to the camera like any surface.  Its image
is a disc of the projected diameter blurred by the lens's defocus, which
grows as ``|focus / z - 1|`` away from the focus distance: particles near
the camera are large, faint blobs, those near the focus small bright dots.

The particles of a frame are splatted in a few groups of similar blur: each
group's coverage and light are deposited on two images (bilinear), blurred
once with the group's kernel, and laid over the frame as
``image (1 - coverage) + light``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import cv2
import numpy as np

SNOW_ALBEDO = 0.5
"""Share of the light on a particle it sends back."""

SNOW_RANGE_M = 5.0
"""Particles farther than this from the camera are too small and faint to matter."""

SNOW_SINK_MPS = (0.002, 0.02)
"""Range of the particles' sinking speeds."""

MAX_PARTICLES = 400_000
"""Cap on the particles of one sequence."""

BLUR_GROUPS = (0.7, 1.5, 3.0, 6.0, 12.0)
"""Blur (px) of the groups particles are splatted in; each takes the nearest."""


@dataclass(frozen=True)
class SnowCloud:
    """The particles of one sequence.

    Attributes
    ----------
    positions : numpy.ndarray
        Shape ``(3, n)``: world ``(X, Y, Z)`` at time 0, m.
    diameters : numpy.ndarray
        m.
    sink : numpy.ndarray
        Sinking speed, m/s.
    """

    positions: np.ndarray
    diameters: np.ndarray
    sink: np.ndarray

    @classmethod
    def draw(
        cls, rng: np.random.Generator, box: tuple[tuple[float, float], ...], per_m3: float, size_mm: float
    ) -> SnowCloud:
        """A Poisson number of particles, uniform in ``box = ((x0, x1), (y0, y1), (z0, z1))``."""
        volume = math.prod(max(hi - lo, 0.0) for lo, hi in box)
        count = min(int(rng.poisson(per_m3 * volume)), MAX_PARTICLES)
        positions = np.stack([rng.uniform(lo, hi, count) for lo, hi in box])
        diameters = 1e-3 * size_mm * rng.lognormal(0.0, 0.5, count)
        sink = rng.uniform(*SNOW_SINK_MPS, count)
        return cls(positions, diameters, sink)

    def __len__(self) -> int:
        return int(self.diameters.size)


def splat(
    image: np.ndarray,
    pixels: np.ndarray,
    sizes_px: np.ndarray,
    blur_px: np.ndarray,
    radiance: np.ndarray,
) -> None:
    """Lay particles over ``image`` in place.

    Parameters
    ----------
    image : numpy.ndarray
        ``float32`` ``(H, W)``.
    pixels : numpy.ndarray
        Shape ``(2, n)``: ``(u, v)`` of each particle's centre.
    sizes_px : numpy.ndarray
        Projected diameters, px.
    blur_px : numpy.ndarray
        Defocus blur (standard deviation), px.
    radiance : numpy.ndarray
        What each particle sends to the camera, in the image's units.
    """
    height, width = image.shape
    if pixels.shape[1] == 0:
        return
    spread = np.sqrt(blur_px**2 + (0.3 * sizes_px) ** 2 + 0.25)
    area = 0.25 * math.pi * sizes_px**2
    coverage = np.minimum(area, 2 * math.pi * spread**2)
    groups = np.argmin(np.abs(np.log(spread[:, None] / np.array(BLUR_GROUPS)[None, :])), axis=1)
    cover_total = np.zeros_like(image)
    light_total = np.zeros_like(image)
    for group, sigma in enumerate(BLUR_GROUPS):
        chosen = groups == group
        if not chosen.any():
            continue
        # Wide kernels are applied on a grid ``factor`` times coarser, then enlarged.
        factor = max(1, round(sigma / 1.5))
        shape = (-(-height // factor), -(-width // factor))
        layers = np.zeros((*shape, 2), dtype=np.float32)
        u = (pixels[0, chosen] + 0.5) / factor - 0.5
        v = (pixels[1, chosen] + 0.5) / factor - 0.5
        u0, v0 = np.floor(u).astype(np.int64), np.floor(v).astype(np.int64)
        fu, fv = u - u0, v - v0
        amount = coverage[chosen] / factor**2
        lit = amount * radiance[chosen]
        for du, dv, share in ((0, 0, (1 - fu) * (1 - fv)), (1, 0, fu * (1 - fv)), (0, 1, (1 - fu) * fv), (1, 1, fu * fv)):
            cols, rows = u0 + du, v0 + dv
            inside = (cols >= 0) & (cols < shape[1]) & (rows >= 0) & (rows < shape[0])
            where = (rows[inside], cols[inside])
            np.add.at(layers[..., 0], where, (amount * share)[inside].astype(np.float32))
            np.add.at(layers[..., 1], where, (lit * share)[inside].astype(np.float32))
        blurred = cv2.GaussianBlur(layers, (0, 0), sigma / factor)
        if factor > 1:
            blurred = cv2.resize(blurred, (shape[1] * factor, shape[0] * factor), interpolation=cv2.INTER_LINEAR)
            blurred = blurred[:height, :width]
        cover_total += blurred[..., 0]
        light_total += blurred[..., 1]
    np.minimum(cover_total, 1.0, out=cover_total)
    image *= 1.0 - cover_total
    image += light_total


__all__ = ["SnowCloud", "splat"]
