"""Algae and stones on the pipe and against its sides: the overgrowth layer.

In the thesis' sequence S1 "the cable is surrounded by very much clutter
(stones and algae)" (seeds/000, Fig. 5.2), and plants "growing on top and
nearby cables" are what makes border detection followed by line
extraction fail (seeds/000, abstract; seeds/004, section IV).  Clutter
painted on the seabed beside the pipe (:mod:`benchmark.modalities.camera.scenes.texture`)
never touches its borders; this layer does.

The layer lives on a band of the seabed grid around the pipe axis, in
world coordinates ``(X, Z)``, and holds per texel

* ``alpha``: how much of the texel the overgrowth covers;
* ``paint``: its albedo times ``alpha`` (premultiplied, so that bilinear
  sampling does not darken the edges);
* ``height``: the height of its top above the seabed.

Seen from above, mats and fronds drape over whatever is beneath them: their
top follows the seabed beside the pipe and the pipe's upper surface over
it, ``height = r + sqrt(r^2 - X^2) + gap`` for ``|X| < r``.  Stones beside
the pipe are domes on the seabed, so they hide only the part of the flank
below their top; stones on the pipe sit on its surface.

The seabed map gets the layer composited over it once per sequence; the
renderer samples the layer again where a ray meets the pipe, and shows the
overgrowth instead of the pipe wherever its top is above the pipe point
(:class:`benchmark.modalities.camera.scenes.render.Renderer`).  Its density along the pipe
follows a profile (:data:`benchmark.modalities.camera.scenes.spec.DensityProfile`): mat
cover and the numbers of fronds and stones scale with it.
"""

from __future__ import annotations

import math
import statistics
from collections.abc import Sequence as SequenceOf
from dataclasses import dataclass

import cv2
import numpy as np

from benchmark.modalities.camera.scenes.spec import Overgrowth
from benchmark.modalities.camera.scenes.texture import (
    TextureGrid,
    lowpass_noise,
    profile_factor,
    profile_peak,
    zone_weight,
)

SURFACE_GAP_M = 0.012
"""Thickness of mats and fronds over the surface they lie on."""

PIPE_MARGIN_CELLS = 2
"""Columns kept beyond ``|X| = r`` in the band the renderer samples on the pipe."""

MAT_EDGE = 0.35
"""Width of a mat's soft edge, in standard deviations of its noise field."""

MAT_RAGGEDNESS = 0.2
"""Weight of the fine noise that frays the edges of the mats."""


@dataclass(frozen=True)
class CoverLayer:
    """Overgrowth on a band of columns of a seabed grid.

    Attributes
    ----------
    grid : TextureGrid
        The seabed grid the band belongs to.
    col0 : int
        First column of the band in ``grid``.
    alpha, paint, height : numpy.ndarray
        Shape ``(grid.nz, ncols)``, ``float32``: cover, albedo times cover
        and top height above the seabed (m).
    """

    grid: TextureGrid
    col0: int
    alpha: np.ndarray
    paint: np.ndarray
    height: np.ndarray

    @property
    def x0(self) -> float:
        """``X`` of the band's first column, m."""
        return self.grid.x0 + self.col0 * self.grid.cell

    def composite(self, seabed: np.ndarray) -> np.ndarray:
        """The seabed map with the overgrowth over it.

        Parameters
        ----------
        seabed : numpy.ndarray
            Albedo on ``grid``, shape ``grid.shape``.

        Returns
        -------
        numpy.ndarray
            A new ``float32`` map, clipped to ``[0.01, 1]``.
        """
        out = np.array(seabed, dtype=np.float32, copy=True)
        band = out[:, self.col0 : self.col0 + self.alpha.shape[1]]
        band *= 1.0 - self.alpha
        band += self.paint
        np.clip(out, 0.01, 1.0, out=out)
        return out

    def pipe_band(self, radius: float) -> tuple[np.ndarray, float]:
        """The columns over the pipe, stacked for :func:`benchmark.modalities.camera.scenes.render.remap_flat`.

        Parameters
        ----------
        radius : float
            Pipe radius in m.

        Returns
        -------
        stack : numpy.ndarray
            Shape ``(grid.nz, ncols, 3)``: alpha, paint and height over
            ``|X| <= r`` and :data:`PIPE_MARGIN_CELLS` columns beyond.
        x0 : float
            ``X`` of its first column, m.
        """
        cell = self.grid.cell
        first = max(int(math.floor((-radius - self.x0) / cell)) - PIPE_MARGIN_CELLS, 0)
        last = min(int(math.ceil((radius - self.x0) / cell)) + PIPE_MARGIN_CELLS + 1, self.alpha.shape[1])
        stack = np.stack(
            (self.alpha[:, first:last], self.paint[:, first:last], self.height[:, first:last]), axis=-1
        )
        return np.ascontiguousarray(stack, dtype=np.float32), self.x0 + first * cell


def drape_height(x: np.ndarray, radius: float) -> np.ndarray:
    """Height above the seabed of what lies on the seabed or over the pipe, at ``X = x``.

    Parameters
    ----------
    x : numpy.ndarray
        Lateral positions in m.
    radius : float
        Pipe radius ``r`` in m; the pipe's axis is at ``X = 0``, one radius
        above the seabed (seeds/004, section II).

    Returns
    -------
    numpy.ndarray
        ``r + sqrt(r^2 - x^2)`` over the pipe, 0 beside it.
    """
    x = np.asarray(x, dtype=np.float64)
    inside = np.abs(x) < radius
    return np.where(inside, radius + np.sqrt(np.clip(radius * radius - x * x, 0.0, None)), 0.0)


class _Canvas:
    """The layer under construction: premultiplied "over" compositing of items."""

    def __init__(self, grid: TextureGrid, col0: int, ncols: int, radius: float) -> None:
        self.grid, self.col0, self.radius = grid, col0, radius
        shape = (grid.nz, ncols)
        self.alpha = np.zeros(shape, dtype=np.float32)
        self.paint = np.zeros(shape, dtype=np.float32)
        self.height = np.zeros(shape, dtype=np.float32)
        self.x = (grid.x0 + grid.cell * np.arange(col0, col0 + ncols)).astype(np.float32)
        self.z = grid.z_coords()
        self.surface = drape_height(self.x, radius).astype(np.float32)

    def put(self, rows: slice, cols: slice, alpha: np.ndarray, albedo: np.ndarray, top: np.ndarray) -> None:
        """Lay an item over what is there: its ``alpha``, ``albedo`` and ``top`` height on a window."""
        alpha = alpha.astype(np.float32)
        albedo = np.clip(albedo, 0.01, 1.0).astype(np.float32)
        below = 1.0 - alpha
        self.paint[rows, cols] *= below
        self.paint[rows, cols] += alpha * albedo
        self.alpha[rows, cols] *= below
        self.alpha[rows, cols] += alpha
        height = self.height[rows, cols]
        np.copyto(height, np.maximum(height, top), where=alpha > 0.02)

    def layer(self) -> CoverLayer:
        return CoverLayer(self.grid, self.col0, self.alpha, self.paint, self.height)


def _stretch(grid: TextureGrid, spec: Overgrowth) -> tuple[float, float] | None:
    lo = max(spec.z_m[0], grid.z0)
    hi = min(spec.z_m[1], grid.z0 + grid.cell * (grid.nz - 1))
    return (lo, hi) if hi > lo else None


def _positions(spec: Overgrowth, per_m: float, stretch: tuple[float, float], rng: np.random.Generator) -> np.ndarray:
    """Poisson positions along ``Z`` with ``per_m`` items per metre times the density profile."""
    lo, hi = stretch
    peak = profile_peak(spec.density, lo, hi)
    if per_m <= 0 or peak <= 0:
        return np.empty(0)
    z = rng.uniform(lo, hi, int(rng.poisson(per_m * peak * (hi - lo))))
    keep = rng.uniform(0.0, peak, z.size) < profile_factor(z, spec.density)
    return z[keep]


def _add_mats(canvas: _Canvas, spec: Overgrowth, rng: np.random.Generator) -> None:
    """Algae mats: a thresholded noise field whose cover follows the density profile."""
    if spec.mat_cover <= 0 or profile_peak(spec.density, -math.inf, math.inf) <= 0:
        return
    cell = canvas.grid.cell
    shape = canvas.alpha.shape
    scale = spec.mat_scale_m / cell
    field = lowpass_noise(rng, shape, (scale, scale)) + MAT_RAGGEDNESS * lowpass_noise(rng, shape, (1.5, 1.5))
    field /= np.float32(math.sqrt(1.0 + MAT_RAGGEDNESS**2))
    share = spec.mat_cover * profile_factor(canvas.z, spec.density) * zone_weight(canvas.z, spec.z_m, spec.mat_scale_m)
    share = np.clip(share, 0.0, 0.999)
    normal = statistics.NormalDist()
    # A share too small to move 1.0 - share is no cover at all (inv_cdf(1.0) is infinite and raises).
    levels = {value: (normal.inv_cdf(1.0 - value) if 1.0 - value < 1.0 else math.inf) for value in np.unique(share)}
    threshold = np.array([levels[value] for value in share], dtype=np.float32)[:, None]
    fade = 0.25 * spec.x_m
    lateral = np.clip((spec.x_m - np.abs(canvas.x)) / fade + 0.5, 0.0, 1.0)[None, :]
    alpha = np.clip((field - threshold) / MAT_EDGE + 0.5, 0.0, 1.0) * lateral
    albedo = spec.mat_albedo * (1.0 + 0.3 * lowpass_noise(rng, shape, (0.8, 0.8)))
    top = np.broadcast_to(canvas.surface + np.float32(SURFACE_GAP_M), shape)
    canvas.put(slice(None), slice(None), alpha, albedo, top)


def _add_stones(canvas: _Canvas, spec: Overgrowth, stretch: tuple[float, float], rng: np.random.Generator) -> None:
    """Stones against the pipe's sides (domes on the seabed) and on its top (domes on the pipe)."""
    grid, radius = canvas.grid, canvas.radius
    side = _positions(spec, spec.side_stones_per_m, stretch, rng)
    top = _positions(spec, spec.top_stones_per_m, stretch, rng)
    for cz, on_top in [(z, False) for z in side] + [(z, True) for z in top]:
        size = spec.stone_size_m * float(rng.lognormal(0.0, 0.3))
        semi_a = 0.5 * size * rng.uniform(0.8, 1.25)
        semi_b = semi_a * rng.uniform(0.55, 1.0)
        turn = rng.uniform(0.0, math.pi)
        if on_top:
            cx = rng.uniform(-0.6, 0.6) * radius
        else:
            cx = float(rng.choice((-1.0, 1.0))) * (radius + rng.uniform(-0.3, 0.6) * semi_b)
        shade = spec.stone_albedo * rng.uniform(0.7, 1.3)
        mottle = rng.uniform(0.0, 0.15)
        col = (cx - grid.x0) / grid.cell - canvas.col0
        row = (cz - grid.z0) / grid.cell
        reach = int(math.ceil(semi_a / grid.cell)) + 2
        r0, r1 = max(int(row) - reach, 0), min(int(row) + reach + 1, grid.nz)
        c0, c1 = max(int(col) - reach, 0), min(int(col) + reach + 1, canvas.alpha.shape[1])
        if r0 >= r1 or c0 >= c1:
            continue
        dr = (np.arange(r0, r1, dtype=np.float32)[:, None] - row) * grid.cell
        dc = (np.arange(c0, c1, dtype=np.float32)[None, :] - col) * grid.cell
        along = (dc * math.cos(turn) + dr * math.sin(turn)) / semi_a
        across = (-dc * math.sin(turn) + dr * math.cos(turn)) / semi_b
        rho = np.sqrt(along**2 + across**2)
        dome = np.sqrt(np.clip(1.0 - rho**2, 0.0, 1.0))
        alpha = np.clip((1.0 - rho) * semi_b / grid.cell, 0.0, 1.0)
        texture = 1.0 + mottle * np.sin(7.0 * along + 3.0 * across + turn)
        albedo = shade * (0.5 + 0.5 * dome) * texture
        height = spec.stone_height * size * dome
        if on_top:
            height = height + canvas.surface[None, c0:c1]
        canvas.put(slice(r0, r1), slice(c0, c1), alpha, albedo.astype(np.float32), height.astype(np.float32))


def _add_fronds(canvas: _Canvas, spec: Overgrowth, stretch: tuple[float, float], rng: np.random.Generator) -> None:
    """Tufts of long, nearly straight fronds rooted near the pipe; some lie along it."""
    roots = _positions(spec, spec.fronds_per_m, stretch, rng)
    if roots.size == 0:
        return
    grid = canvas.grid
    mask = np.zeros(canvas.alpha.shape, dtype=np.uint8)
    scale = 4  # sub-texel precision of cv2.polylines (shift = 2)
    for cz in roots:
        cx = rng.uniform(-spec.x_m, spec.x_m)
        along_pipe = rng.uniform() < spec.parallel_share
        if along_pipe:
            heading0, fan = float(rng.choice((0.5, -0.5))) * math.pi + rng.normal(0.0, 0.1), 0.12
        else:
            heading0, fan = rng.uniform(0.0, 2.0 * math.pi), 0.45
        for _ in range(int(rng.integers(3, 8))):
            col = (cx - grid.x0) / grid.cell - canvas.col0 + rng.normal(0.0, 1.5)
            row = (cz - grid.z0) / grid.cell + rng.normal(0.0, 1.5)
            heading = heading0 + rng.normal(0.0, fan)
            length = spec.frond_length_m * float(rng.lognormal(0.0, 0.3)) / grid.cell
            segments = 4
            step = length / segments
            points = [(col, row)]
            for _ in range(segments):
                heading += rng.normal(0.0, 0.07)
                col, row = col + step * math.cos(heading), row + step * math.sin(heading)
                points.append((col, row))
            width = max(1, round(spec.frond_width_m * rng.uniform(0.6, 1.4) / grid.cell))
            poly = np.round(np.array(points) * scale).astype(np.int32)
            cv2.polylines(mask, [poly], False, int(rng.integers(170, 256)), width, cv2.LINE_AA, shift=2)
    alpha = mask.astype(np.float32) / 255.0
    albedo = spec.frond_albedo * (1.0 + 0.25 * lowpass_noise(rng, mask.shape, (1.5, 1.5)))
    top = np.broadcast_to(canvas.surface + np.float32(SURFACE_GAP_M), mask.shape)
    canvas.put(slice(None), slice(None), alpha, albedo, top)


def overgrowth_layer(
    specs: SequenceOf[Overgrowth], grid: TextureGrid, radius: float, rng: np.random.Generator
) -> CoverLayer | None:
    """The overgrowth of a scene on a band of its seabed grid.

    Parameters
    ----------
    specs : sequence of Overgrowth
        The stretches of overgrowth; later ones lie over earlier ones.
    grid : TextureGrid
        The seabed grid; the pipe axis is at ``X = 0``.
    radius : float
        Pipe radius ``r`` in m.
    rng : numpy.random.Generator
        Source of every random choice; one child generator is spawned per
        stretch.

    Returns
    -------
    CoverLayer or None
        None when nothing was drawn (no stretches, or all densities zero),
        so that such a scene renders exactly as one without overgrowth.

    References
    ----------
    seeds/000, section 5.2.3 and Fig. 5.2 (stones and algae around the cable
    in S1); seeds/000, section 2.1 and seeds/004, section IV (seaweed and
    fouling break the borders a line detector looks for).
    """
    if not specs:
        return None
    reach = max(
        radius + (PIPE_MARGIN_CELLS + 1) * grid.cell,
        *(spec.x_m + 2.5 * spec.frond_length_m + spec.stone_size_m for spec in specs),
    )
    half = min(reach, -grid.x0 - grid.cell)
    col0 = max(int(math.floor((-half - grid.x0) / grid.cell)), 0)
    canvas = _Canvas(grid, col0, grid.nx - 2 * col0, radius)
    for spec, stream in zip(specs, rng.spawn(len(specs))):
        stretch = _stretch(grid, spec)
        if stretch is None:
            continue
        mats, stones, fronds = stream.spawn(3)
        _add_mats(canvas, spec, mats)
        _add_stones(canvas, spec, stretch, stones)
        _add_fronds(canvas, spec, stretch, fronds)
    if not canvas.alpha.any():
        return None
    return canvas.layer()
