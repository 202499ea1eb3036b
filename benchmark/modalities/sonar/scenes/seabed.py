"""The seabed below a sonar track, as depths on a grid of (ping, across-track position).

The detector of seeds/003 (section 2) fits a pipe's cross-section to pairs
of consecutive returns and checks that its centre sits near the local
seafloor, so what it can be fooled by is relief of the pipe's size: trench
walls, spoil heaps, boulders, ripples.  This module builds that relief.
Rows of the grid are pings (along-track, ``ping_spacing_m`` apart), columns
across-track positions ``cell_m`` apart, symmetric about the track with a
column at nadir; values are depths below the transducer, positive down.
Between columns the surface is linear.

The depth at ping ``k`` and across-track position ``x`` is the sum of

* the vehicle's altitude above the mean seabed and the across-track slope,
  ``altitude_k + x tan(slope_k)``;
* roughness: for each :class:`~benchmark.modalities.sonar.scenes.spec.Roughness`, white
  noise smoothed by a Gaussian over both axes (:func:`smoothed_field`, the
  2-D form of :func:`benchmark.scenes.noise.smoothed_noise`), so that a
  bump seen in one ping is still there in the next;
* ripples;
* trenches along the pipes, with their spoil heaps (:func:`trench_relief`);
* boulders, half-ellipsoids scattered at random but kept off the pipes
  (:func:`scatter_boulders`, :func:`boulder_caps`).

The pipes rest on everything but the boulders
(:mod:`benchmark.modalities.sonar.scenes.pipes`), and the sonar casts its beams on the
sum (:mod:`benchmark.modalities.sonar.scenes.swath`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from benchmark.modalities.sonar.scenes.spec import BoulderField, Ripples, Roughness, TrenchSpec


def across_grid(half_width_m: float, cell_m: float) -> np.ndarray:
    """Across-track positions ``j * cell_m`` for ``|j| <= ceil(half_width_m / cell_m)``.

    Parameters
    ----------
    half_width_m : float
        Reach of the grid on each side of the track.
    cell_m : float
        Spacing.

    Returns
    -------
    numpy.ndarray
        Increasing, odd length, its middle element exactly 0.
    """
    half = int(math.ceil(half_width_m / cell_m))
    return np.arange(-half, half + 1) * cell_m


def _unit_kernel(smooth: float) -> np.ndarray:
    """Gaussian taps of standard deviation ``smooth`` scaled to unit energy."""
    half = int(math.ceil(4 * smooth))
    taps = np.arange(-half, half + 1, dtype=float)
    kernel = np.exp(-0.5 * (taps / smooth) ** 2)
    return kernel / math.sqrt(float(np.sum(kernel**2)))


def smoothed_field(rng: np.random.Generator, shape: tuple[int, int], smooth: tuple[float, float]) -> np.ndarray:
    """Unit-variance Gaussian noise on a grid, smoothed by a separable Gaussian.

    The 2-D counterpart of :func:`benchmark.scenes.noise.smoothed_noise`:
    white noise on a grid padded by four standard deviations on each side,
    convolved with a unit-energy Gaussian along each axis, so that the
    field is stationary with unit variance.

    Parameters
    ----------
    rng : numpy.random.Generator
        Source of the white noise.
    shape : tuple of int
        ``(rows, columns)`` of the result.
    smooth : tuple of float
        Standard deviation of the kernel along each axis, in cells; 0 leaves
        that axis white.

    Returns
    -------
    numpy.ndarray
        Shape ``shape``.
    """
    kernels = [_unit_kernel(s) if s > 0 else np.ones(1) for s in smooth]
    padded = tuple(n + len(k) - 1 for n, k in zip(shape, kernels))
    field = rng.standard_normal(padded)
    for axis, kernel in enumerate(kernels):
        n = shape[axis]
        out = np.zeros(field.shape[:axis] + (n,) + field.shape[axis + 1 :])
        for tap, weight in enumerate(kernel):
            out += weight * (field[tap : tap + n] if axis == 0 else field[:, tap : tap + n])
        field = out
    return field


def roughness_relief(
    rng: np.random.Generator, roughness: Roughness, n_rows: int, ping_spacing_m: float, across: np.ndarray
) -> np.ndarray:
    """One scale of roughness on the grid, in m.

    Along the track the field is smoothed ping by ping (the pings are its
    samples); across the track it is built on columns no closer than a
    third of ``length_m`` and interpolated linearly onto ``across``.

    Parameters
    ----------
    rng : numpy.random.Generator
        Source of the field.
    roughness : Roughness
        Its height and length scale.
    n_rows : int
        Pings.
    ping_spacing_m : float
        Along-track distance between pings.
    across : numpy.ndarray
        Grid columns (from :func:`across_grid`).

    Returns
    -------
    numpy.ndarray
        Shape ``(n_rows, len(across))``, zero mean, standard deviation
        ``roughness.std_m``.
    """
    cell = float(across[1] - across[0])
    coarse_cell = max(cell, roughness.length_m / 3.0)
    coarse = np.arange(across[0] - coarse_cell, across[-1] + 2 * coarse_cell, coarse_cell)
    unit = smoothed_field(
        rng, (n_rows, len(coarse)), (roughness.length_m / ping_spacing_m, roughness.length_m / coarse_cell)
    )
    position = (across - coarse[0]) / coarse_cell
    left = np.minimum(np.floor(position).astype(int), len(coarse) - 2)
    weight = position - left
    return roughness.std_m * (unit[:, left] * (1.0 - weight) + unit[:, left + 1] * weight)


def ripple_relief(ripples: Ripples, along: np.ndarray, across: np.ndarray) -> np.ndarray:
    """Sand ripples on the grid: depth change in m (negative on the crests).

    Parameters
    ----------
    ripples : Ripples
        Height, wavelength and crest direction.
    along : numpy.ndarray
        Along-track position of each ping.
    across : numpy.ndarray
        Grid columns.

    Returns
    -------
    numpy.ndarray
        Shape ``(len(along), len(across))``.
    """
    if ripples.height_m == 0:
        return np.zeros((len(along), len(across)))
    crest = math.radians(ripples.crest_deg)
    normal = across[None, :] * math.cos(crest) - along[:, None] * math.sin(crest)
    return -0.5 * ripples.height_m * np.sin(2 * math.pi * normal / ripples.wavelength_m)


def trench_relief(trench: TrenchSpec, depth_m: np.ndarray, pipe_across_m: np.ndarray, across: np.ndarray) -> np.ndarray:
    """A trench along a pipe and its spoil heaps: depth change in m (positive deeper).

    Parameters
    ----------
    trench : TrenchSpec
        Cross-section of the trench.
    depth_m : numpy.ndarray
        Its depth at each ping (values below 0 count as 0).
    pipe_across_m : numpy.ndarray
        The pipe's across-track position at each ping.
    across : numpy.ndarray
        Grid columns.

    Returns
    -------
    numpy.ndarray
        Shape ``(len(depth_m), len(across))``.

    References
    ----------
    seeds/003, section 2: the term ``L_2`` of eq. (1) compares a candidate's
    centre with the local seafloor, which trench walls and spoil heaps
    disturb.
    """
    depth = np.maximum(depth_m, 0.0)[:, None]
    distance = np.abs(across[None, :] - (pipe_across_m[:, None] + trench.offset_m))
    half_bottom, half_top = trench.bottom_width_m / 2.0, trench.top_width_m / 2.0
    wall = np.clip((half_top - distance) / (half_top - half_bottom), 0.0, 1.0)
    crest = half_top + trench.berm_width_m
    berm = np.exp(-0.5 * ((distance - crest) / trench.berm_width_m) ** 2)
    return depth * (wall - trench.berm_ratio * berm)


@dataclass(frozen=True)
class Boulders:
    """Boulders of one field: centres and half-axes, in m.

    Attributes
    ----------
    along_m, across_m : numpy.ndarray
        Centre of each boulder's footprint.
    half_along_m, half_across_m : numpy.ndarray
        Half-axes of the footprint.
    height_m : numpy.ndarray
        Height above the seabed.
    """

    along_m: np.ndarray
    across_m: np.ndarray
    half_along_m: np.ndarray
    half_across_m: np.ndarray
    height_m: np.ndarray

    def __len__(self) -> int:
        return len(self.along_m)


def scatter_boulders(
    rng: np.random.Generator,
    field: BoulderField,
    along: np.ndarray,
    across: np.ndarray,
    pipe_across_m: np.ndarray,
    pipe_half_width_m: np.ndarray,
) -> Boulders:
    """Scatter a field's boulders uniformly over its stretch, keeping them off the pipes.

    Parameters
    ----------
    rng : numpy.random.Generator
        Source of the count, positions and sizes; always consumed in the
        same order.
    field : BoulderField
        Density, sizes, clearance and stretch.
    along : numpy.ndarray
        Along-track position of each ping.
    across : numpy.ndarray
        Grid columns: boulders are scattered across their whole width.
    pipe_across_m : numpy.ndarray
        Across-track position of each pipe's axis at each ping, shape
        ``(n_pipes, n_pings)``.
    pipe_half_width_m : numpy.ndarray
        Half-width of each pipe at each ping, same shape.

    Returns
    -------
    Boulders

    References
    ----------
    seeds/003, section 2: the detector fits a pipe's cross-section to any
    two consecutive returns, so pipe-sized boulders are candidates too.
    """
    spacing = float(along[1] - along[0]) if len(along) > 1 else 1.0
    lo = max(field.start_frame, -1.0) * spacing + along[0]
    hi = min(field.stop_frame, len(along)) * spacing + along[0]
    width = float(across[-1] - across[0])
    count = rng.poisson(field.per_100m2 * max(hi - lo, 0.0) * width / 100.0)
    along_m = rng.uniform(lo, hi, count) if hi > lo else np.zeros(count)
    across_m = rng.uniform(across[0], across[-1], count)
    small, large = field.diameter_m
    diameter = np.exp(rng.uniform(math.log(small), math.log(large), count))
    height = diameter * rng.uniform(*field.height_ratio, count)
    length = diameter * rng.uniform(*field.elongation, count)
    keep = np.ones(count, dtype=bool)
    for centre, half_width in zip(pipe_across_m, pipe_half_width_m):
        axis = np.interp(along_m, along, centre)
        reach = np.interp(along_m, along, half_width) + diameter / 2.0 + field.clearance_m
        keep &= np.abs(across_m - axis) > reach
    return Boulders(along_m[keep], across_m[keep], length[keep] / 2.0, diameter[keep] / 2.0, height[keep])


def boulder_caps(boulders: Boulders, along: np.ndarray, across: np.ndarray, caps: np.ndarray) -> None:
    """Raise ``caps`` (shape ``(len(along), len(across))``) to each boulder's height above the seabed.

    Where boulders overlap, the higher one counts.

    Parameters
    ----------
    boulders : Boulders
    along : numpy.ndarray
        Along-track position of each ping (evenly spaced).
    across : numpy.ndarray
        Grid columns (evenly spaced).
    caps : numpy.ndarray
        Heights above the seabed, updated in place.
    """
    spacing = float(along[1] - along[0]) if len(along) > 1 else math.inf
    cell = float(across[1] - across[0])
    for y, x, ry, rx, h in zip(
        boulders.along_m, boulders.across_m, boulders.half_along_m, boulders.half_across_m, boulders.height_m
    ):
        if math.isinf(spacing):
            rows = np.array([0]) if abs(y - along[0]) < ry else np.array([], dtype=int)
        else:
            first = max(int(math.ceil((y - ry - along[0]) / spacing)), 0)
            last = min(int(math.floor((y + ry - along[0]) / spacing)), len(along) - 1)
            rows = np.arange(first, last + 1)
        lo = max(int(math.floor((x - rx - across[0]) / cell)), 0)
        hi = min(int(math.ceil((x + rx - across[0]) / cell)), len(across) - 1)
        if rows.size == 0 or hi < lo:
            continue
        dy = (along[rows] - y)[:, None] / ry
        dx = (across[lo : hi + 1] - x)[None, :] / rx
        cap = h * np.sqrt(np.clip(1.0 - dy**2 - dx**2, 0.0, None))
        block = caps[rows, lo : hi + 1]
        caps[rows, lo : hi + 1] = np.maximum(block, cap)
