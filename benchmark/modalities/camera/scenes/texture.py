"""Albedo maps of the seabed and of the pipe's surface.

Both maps are computed once per sequence, before the first frame, and
sampled per pixel by the renderer.

The seabed map lives in world coordinates ``(X, Z)`` of the plane
``Y = -r`` (seeds/004, section II), one texel per ``cell`` metres (1 cm by
default); rows run along ``Z``, columns along ``X``.  It combines

* sand: Gaussian-filtered noise at three scales (patches, detail, grain);
* ripples: parallel crests with a sawtooth profile whose sharp drop gives
  long straight edges, the kind of clutter that tempts a Hough detector
  (seeds/000, section 2.1; seeds/004, section IV);
* rocks: shaded ellipses with a dark contact rim;
* algae: tufts of thin dark strands.

The pipe map lives in cylinder coordinates ``(psi, Z)``, ``psi`` the angle
around the axis measured from the top of the pipe towards ``+X``.  It holds
the pipe's albedo and texture and the marine growth on its flanks, which
blurs the borders a tracker looks for.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import cv2
import numpy as np

from benchmark.modalities.camera.scenes.spec import CableLook, Clutter, DensityProfile, Ripples, SeabedSpec, ZRange

PSI_CELLS = 128
"""Texels around the pipe's circumference."""

FFT_SIGMA = 4.0
"""Filter width (texels) from which noise is filtered in the Fourier domain."""


@dataclass(frozen=True)
class TextureGrid:
    """Placement of a seabed map: texel ``(row, col)`` is at ``X = x0 + col cell``, ``Z = z0 + row cell``."""

    x0: float
    z0: float
    cell: float
    nx: int
    nz: int

    @property
    def shape(self) -> tuple[int, int]:
        """``(nz, nx)``: rows along ``Z``, columns along ``X``."""
        return self.nz, self.nx

    def x_coords(self) -> np.ndarray:
        return self.x0 + self.cell * np.arange(self.nx)

    def z_coords(self) -> np.ndarray:
        return self.z0 + self.cell * np.arange(self.nz)


def lowpass_noise(rng: np.random.Generator, shape: tuple[int, int], sigma: tuple[float, float]) -> np.ndarray:
    """Gaussian-filtered white noise with unit standard deviation.

    Parameters
    ----------
    rng : numpy.random.Generator
        Source of the white noise.
    shape : tuple of int
        ``(rows, cols)``.
    sigma : tuple of float
        Standard deviation of the Gaussian filter along rows and columns, in
        texels; below half a texel the noise stays white.

    Returns
    -------
    numpy.ndarray
        ``float32`` array.  Fields smoother than :data:`FFT_SIGMA` texels are
        filtered in the Fourier domain on a grid coarsened to keep about
        :data:`FFT_SIGMA` texels per standard deviation, then resized: they
        tile seamlessly.  Finer fields are filtered with
        :func:`cv2.GaussianBlur`.
    """
    if max(sigma) < 0.5:
        return rng.standard_normal(shape, dtype=np.float32)
    if min(sigma) < FFT_SIGMA:
        white = rng.standard_normal(shape, dtype=np.float32)
        field = cv2.GaussianBlur(white, (0, 0), sigmaX=max(sigma[1], 0.3), sigmaY=max(sigma[0], 0.3))
    else:
        factor = max(1, int(min(sigma) / FFT_SIGMA))
        small = (-(-shape[0] // factor), -(-shape[1] // factor))
        spectrum = np.fft.rfft2(rng.standard_normal(small, dtype=np.float32))
        f_rows = np.fft.fftfreq(small[0]).astype(np.float32)[:, None] * np.float32(sigma[0] / factor)
        f_cols = np.fft.rfftfreq(small[1]).astype(np.float32)[None, :] * np.float32(sigma[1] / factor)
        spectrum *= np.exp(np.float32(-2.0 * math.pi**2) * (f_rows**2 + f_cols**2))
        field = np.fft.irfft2(spectrum, s=small).astype(np.float32)
        if factor > 1:
            # Pad one period so that the interpolation wraps, then cut back.
            wrapped = np.pad(field, ((0, 1), (0, 1)), mode="wrap")
            big = cv2.resize(wrapped, (small[1] * factor + 1, small[0] * factor + 1), interpolation=cv2.INTER_LINEAR)
            field = np.ascontiguousarray(big[: shape[0], : shape[1]])
    field -= np.float32(field.mean())
    field /= np.float32(max(float(field.std()), 1e-12))
    return field


def zone_weight(z: np.ndarray, zone: ZRange, fade: float) -> np.ndarray:
    """1 inside a stretch of ``Z``, 0 outside, with raised-cosine ends of length ``fade``."""
    lo, hi = zone
    if fade <= 0:
        return ((z >= lo) & (z <= hi)).astype(np.float32)
    rise = np.clip((z - lo) / fade + 0.5, 0.0, 1.0)
    fall = np.clip((hi - z) / fade + 0.5, 0.0, 1.0)
    return (0.5 - 0.5 * np.cos(math.pi * np.minimum(rise, fall))).astype(np.float32)


def profile_factor(z: np.ndarray | float, profile: DensityProfile) -> np.ndarray:
    """A density profile's factor at positions ``z`` along the pipe.

    Parameters
    ----------
    z : numpy.ndarray or float
        Positions in m.
    profile : DensityProfile
        Points ``(Z, factor)``, interpolated linearly and held beyond the
        ends; empty for 1 everywhere.

    Returns
    -------
    numpy.ndarray
        Factors, ``float64``, of the shape of ``z``.
    """
    z = np.asarray(z, dtype=float)
    if not profile:
        return np.ones_like(z)
    zs, factors = (np.array(column, dtype=float) for column in zip(*profile))
    values = np.interp(z, zs, factors)
    if np.all(np.isfinite(values)):
        return values
    # np.interp's slope overflows between points closer than about 1e-308 m; a share of the gap does not.
    flat_z, flat = np.atleast_1d(z), np.atleast_1d(np.array(values, dtype=float))
    overflowed = ~np.isfinite(flat)
    left = np.clip(np.searchsorted(zs, flat_z[overflowed], side="right") - 1, 0, len(zs) - 2)
    share = (flat_z[overflowed] - zs[left]) / (zs[left + 1] - zs[left])
    flat[overflowed] = factors[left] + share * (factors[left + 1] - factors[left])
    return flat.reshape(z.shape)


def profile_peak(profile: DensityProfile, lo: float, hi: float) -> float:
    """Largest factor of a density profile over the stretch ``[lo, hi]`` of ``Z``."""
    inside = [f for z, f in profile if lo <= z <= hi]
    return float(max([*inside, *profile_factor(np.array([lo, hi]), profile)]))


def _add_ripples(albedo: np.ndarray, grid: TextureGrid, ripples: Ripples, rng: np.random.Generator) -> None:
    x = grid.x_coords().astype(np.float32)[None, :]
    z = grid.z_coords().astype(np.float32)[:, None]
    angle = math.radians(ripples.angle_deg)
    # Phase grows across the crests, whose direction is at ``angle`` to the Z axis.
    phase = (x * math.cos(angle) - z * math.sin(angle)) / ripples.wavelength_m
    wander = lowpass_noise(rng, grid.shape, (12.0, 12.0))
    phase = phase + (ripples.waviness_m / ripples.wavelength_m) * wander
    frac = phase - np.floor(phase)
    saw = 2.0 * frac - 1.0
    sine = np.sin(2.0 * math.pi * frac)
    profile = ripples.sharpness * saw + (1.0 - ripples.sharpness) * sine
    weight = zone_weight(z, ripples.z_m, ripples.fade_m)
    albedo *= 1.0 + ripples.amplitude * profile * weight


def _zone_draws(
    grid: TextureGrid, clutter: Clutter, per_m2: float, rng: np.random.Generator
) -> tuple[tuple[float, float, float, float], float, int] | None:
    """The clutter zone's box in the grid, its peak density and a Poisson count of items in it."""
    z_lo = max(clutter.z_m[0], grid.z0)
    z_hi = min(clutter.z_m[1], grid.z0 + grid.cell * (grid.nz - 1))
    x_half = min(clutter.x_m, -grid.x0 - grid.cell)
    if z_hi <= z_lo or x_half <= 0 or per_m2 <= 0:
        return None
    peak = profile_peak(clutter.density, z_lo, z_hi)
    count = int(rng.poisson(per_m2 * peak * (2.0 * x_half) * (z_hi - z_lo)))
    return (-x_half, x_half, z_lo, z_hi), peak, count


def _add_rocks(albedo: np.ndarray, grid: TextureGrid, clutter: Clutter, rng: np.random.Generator) -> None:
    draws = _zone_draws(grid, clutter, clutter.rocks_per_m2, rng)
    if draws is None:
        return
    (x_lo, x_hi, z_lo, z_hi), peak, count = draws
    for _ in range(count):
        cx, cz = rng.uniform(x_lo, x_hi), rng.uniform(z_lo, z_hi)
        if clutter.density and rng.uniform(0.0, peak) >= profile_factor(cz, clutter.density):
            continue
        size = clutter.rock_size_m * float(rng.lognormal(0.0, 0.35))
        semi_a = 0.5 * size * rng.uniform(0.8, 1.25) / grid.cell
        semi_b = semi_a * rng.uniform(0.45, 1.0)
        turn = rng.uniform(0.0, math.pi)
        shade = clutter.rock_albedo * rng.uniform(0.7, 1.3)
        mottle = rng.uniform(0.0, 0.15)
        col, row = (cx - grid.x0) / grid.cell, (cz - grid.z0) / grid.cell
        reach = int(math.ceil(1.4 * semi_a)) + 2
        r0, r1 = max(int(row) - reach, 0), min(int(row) + reach + 1, grid.nz)
        c0, c1 = max(int(col) - reach, 0), min(int(col) + reach + 1, grid.nx)
        if r0 >= r1 or c0 >= c1:
            continue
        dr = np.arange(r0, r1, dtype=np.float32)[:, None] - row
        dc = np.arange(c0, c1, dtype=np.float32)[None, :] - col
        along = (dc * math.cos(turn) + dr * math.sin(turn)) / semi_a
        across = (-dc * math.sin(turn) + dr * math.cos(turn)) / semi_b
        rho = np.sqrt(along**2 + across**2)
        patch = albedo[r0:r1, c0:c1]
        rim = 1.0 - 0.4 * np.exp(-(((rho - 1.0) / 0.18) ** 2)) * (rho > 0.9)
        patch *= rim.astype(np.float32)
        dome = np.sqrt(np.clip(1.0 - rho**2, 0.0, 1.0))
        texture = 1.0 + mottle * np.sin(7.0 * along + 3.0 * across + turn)
        rock = shade * (0.55 + 0.45 * dome) * texture
        cover = np.clip((1.0 - rho) * semi_b, 0.0, 1.0)
        patch += (cover * (rock - patch)).astype(np.float32)


def _add_algae(albedo: np.ndarray, grid: TextureGrid, clutter: Clutter, rng: np.random.Generator) -> None:
    draws = _zone_draws(grid, clutter, clutter.algae_per_m2, rng)
    if draws is None or draws[2] == 0:
        return
    (x_lo, x_hi, z_lo, z_hi), peak, count = draws
    mask = np.zeros(grid.shape, dtype=np.uint8)
    scale = 4  # sub-texel precision of cv2.polylines (shift = 2)
    for _ in range(count):
        cx, cz = rng.uniform(x_lo, x_hi), rng.uniform(z_lo, z_hi)
        if clutter.density and rng.uniform(0.0, peak) >= profile_factor(cz, clutter.density):
            continue
        length = clutter.algae_size_m * float(rng.lognormal(0.0, 0.3)) / grid.cell
        heading0 = rng.uniform(0.0, 2 * math.pi)
        for _ in range(int(rng.integers(6, 15))):
            col = (cx - grid.x0) / grid.cell + rng.normal(0.0, 0.08 * length)
            row = (cz - grid.z0) / grid.cell + rng.normal(0.0, 0.08 * length)
            heading = heading0 + rng.normal(0.0, 0.9)
            points = [(col, row)]
            segments = int(rng.integers(5, 10))
            step = length / segments * rng.uniform(0.6, 1.2)
            for _ in range(segments):
                heading += rng.normal(0.0, 0.35)
                col, row = col + step * math.cos(heading), row + step * math.sin(heading)
                points.append((col, row))
            poly = np.round(np.array(points) * scale).astype(np.int32)
            strength = int(rng.integers(150, 256))
            cv2.polylines(mask, [poly], False, strength, int(rng.integers(1, 4)), cv2.LINE_AA, shift=2)
    cover = mask.astype(np.float32) / 255.0
    weed = clutter.algae_albedo * (1.0 + 0.3 * lowpass_noise(rng, grid.shape, (2.0, 2.0)))
    albedo += cover * (weed - albedo)


def seabed_map(spec: SeabedSpec, grid: TextureGrid, rng: np.random.Generator) -> np.ndarray:
    """The seabed albedo map.

    Parameters
    ----------
    spec : SeabedSpec
        Sand, ripples and clutter.
    grid : TextureGrid
        Where the map lies on the seabed.
    rng : numpy.random.Generator
        Source of every random choice; one child generator is spawned per
        layer.

    Returns
    -------
    numpy.ndarray
        ``float32`` albedo in ``[0.01, 1]``, shape ``grid.shape``.

    References
    ----------
    seeds/004, section II (the seabed plane) and section VI-A, Fig. 13
    (sandy and rocky bottoms, seaweed); seeds/000, section 5.2.3 (clutter of
    stones and algae in sequence S1).
    """
    streams = iter(rng.spawn(3 + len(spec.ripples) + 2 * len(spec.clutter)))
    patch = spec.patch_scale_m / grid.cell
    albedo = (
        1.0
        + spec.patchiness * lowpass_noise(next(streams), grid.shape, (patch, patch))
        + spec.detail * lowpass_noise(next(streams), grid.shape, (2.5, 2.5))
        + spec.grain * lowpass_noise(next(streams), grid.shape, (0.0, 0.0))
    )
    albedo *= np.float32(spec.albedo)
    for ripples in spec.ripples:
        _add_ripples(albedo, grid, ripples, next(streams))
    for clutter in spec.clutter:
        _add_rocks(albedo, grid, clutter, next(streams))
        _add_algae(albedo, grid, clutter, next(streams))
    return np.clip(albedo, 0.01, 1.0).astype(np.float32)


def coarse_level(albedo: np.ndarray, factor: int = 4) -> np.ndarray:
    """A pre-filtered copy of a map at ``1/factor`` of its resolution, for distant texels."""
    blurred = cv2.GaussianBlur(albedo, (0, 0), 0.5 * factor)
    return cv2.resize(
        blurred, (albedo.shape[1] // factor, albedo.shape[0] // factor), interpolation=cv2.INTER_AREA
    )


def cable_map(look: CableLook, nz: int, cell: float, radius: float, rng: np.random.Generator) -> np.ndarray:
    """Albedo of the pipe's surface in cylinder coordinates.

    Parameters
    ----------
    look : CableLook
        Albedo, texture and marine growth.
    nz : int
        Rows along ``Z``, on the same rows as the seabed map.
    cell : float
        Row spacing along ``Z`` in m.
    radius : float
        Pipe radius in m, to make texture features round rather than
        stretched around the circumference.
    rng : numpy.random.Generator
        Source of every random choice.

    Returns
    -------
    numpy.ndarray
        ``float32`` albedo, shape ``(nz, PSI_CELLS)``; column ``j`` is at
        ``psi = -pi + 2 pi j / PSI_CELLS``, ``psi = 0`` on top of the pipe.

    References
    ----------
    seeds/004, section IV and Fig. 13 (encrustations and seaweed on the pipe
    borders).
    """
    first, second, third = rng.spawn(3)
    shape = (nz, PSI_CELLS)
    around = 2 * math.pi * radius / PSI_CELLS
    albedo = look.albedo * (1.0 + look.texture * lowpass_noise(first, shape, (1.5, 1.5 * cell / around)))
    if look.growth_coverage > 0:
        psi = np.linspace(-math.pi, math.pi, PSI_CELLS, endpoint=False, dtype=np.float32)
        centre, spread = math.radians(look.growth_angle_deg), math.radians(look.growth_spread_deg)
        band = np.exp(-0.5 * ((np.abs(psi) - centre) / spread) ** 2)[None, :]
        field = lowpass_noise(second, shape, (4.0, 0.04 / around))
        threshold = float(np.quantile(field, 1.0 - look.growth_coverage))
        cover = band * np.clip((field - threshold) / 0.4 + 0.5, 0.0, 1.0)
        growth = look.growth_albedo * (1.0 + 0.3 * lowpass_noise(third, shape, (1.0, 1.0)))
        albedo = albedo + cover * (growth - albedo)
    return np.clip(albedo, 0.01, 1.0).astype(np.float32)
