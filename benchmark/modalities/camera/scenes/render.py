"""Ray casting of the pipe-on-seabed scene, one grey frame at a time.

Every pixel casts the ray ``C + t D`` of the pinhole model (seeds/004,
section II; :func:`benchmark.modalities.camera.scenes.projection.pixel_rays`), with ``D``
scaled so that ``t`` is the depth along the optical axis.  All pixels are
processed at once with numpy:

1. the seabed plane ``Y = -r``: ``t = (-r - Cy) / D_y`` where the ray goes
   down; rays that never meet it (looking above the horizon) end at the
   distance where the water is opaque;
2. the pipe ``X^2 + Y^2 = r^2``: the nearer root of the quadratic, computed
   only for the pixels whose ray meets the cylinder in front of the camera;
3. albedo: the seabed map sampled at the hit ``(X, Z)`` with
   :func:`cv2.remap` (a coarser, pre-filtered copy takes over where a pixel
   covers several texels), the pipe map at ``(psi, Z)``; where the pipe lies
   below the sand level the pixel keeps the seabed behind it, so a buried
   pipe disappears but for a faint trace; where algae or stones lie on
   the pipe (:mod:`benchmark.modalities.camera.scenes.overgrowth`) and their top is above the
   pipe point, the pixel shows them, lit like the seabed around them; a
   cable crossing the pipe (:mod:`benchmark.modalities.camera.scenes.crossing`)
   is another cylinder, shaded like the pipe, that takes the pixels where
   it is nearer than the surface found so far;
4. light from a lamp at the camera: Lambertian shading (so the middle of
   the pipe, facing the lamp, is brightest) with an ambient share, a
   highlight along the pipe, fall-off with the distance squared (softened
   by a share of daylight) and vignetting, and the camera's automatic gain,
   which undoes most of the change of light at the image centre;
5. water: haze blends towards the water's grey with
   ``exp(-c * distance)``;
6. sensor: Gaussian blur, a few bright suspended particles, Gaussian noise,
   quantisation to ``uint8``.

Everything that does not change from frame to frame (ray directions in the
camera frame, vignetting, albedo maps, sand profile) is held by
:class:`SceneAssets`, built once per sequence.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import cv2
import numpy as np

from benchmark.modalities.camera.model import CameraPose
from benchmark.modalities.camera.scenes.formation import PipePixels, WaterFormation
from benchmark.modalities.camera.scenes.lighting import CausticWaves
from benchmark.modalities.camera.scenes.projection import pixel_rays, pose_axes
from benchmark.modalities.camera.scenes.spec import CameraSceneSpec
from benchmark.modalities.camera.scenes.snow import SnowCloud
from benchmark.modalities.camera.scenes.texture import PSI_CELLS, TextureGrid
from benchmark.scenes.noise import gaussian_table

if TYPE_CHECKING:
    from benchmark.modalities.camera.scenes.crossing import CrossingCable, CrossingHits

OPAQUE_TRANSMISSION = 1.0 / 1024.0
"""Haze transmission below which the water colour is all that is left."""

MAX_RANGE_M = 60.0
"""Farthest distance a ray is followed, whatever the water."""

HIGHLIGHT_SQUARINGS = 4
"""The highlight along the middle of the pipe is ``cos^(2^4)`` of the angle to the lamp."""

MOUND_RELIEF = 0.2
"""How much of the pipe's rounded shading shows through the sand that covers it."""

REMAP_ROW = 1024
"""Row length of the coordinate maps :func:`remap_flat` hands to :func:`cv2.remap`."""

LAMP_CLAMP = 4.0
"""Largest fall-off factor of the lamp (for surfaces much nearer than the reference distance)."""

COVER_EDGE_M = 0.01
"""Height over which overgrowth fades in where its top meets the pipe's surface."""


@dataclass(frozen=True)
class SceneAssets:
    """Per-sequence arrays the renderer reuses for every frame.

    Attributes
    ----------
    grid : TextureGrid
        Where the seabed map lies; the pipe map and the sand profile share
        its rows along ``Z``.
    seabed, seabed_coarse : numpy.ndarray
        Seabed albedo at full resolution and ``coarse_factor`` times coarser.
    coarse_factor : int
    cable : numpy.ndarray
        Shape ``(nz, PSI_CELLS, 2)``: the pipe's albedo and a small offset
        (m) that makes the sand line on the pipe irregular.
    sand : numpy.ndarray
        Sand level ``L(Z)`` per row of the grid (m).
    rays : numpy.ndarray
        Shape ``(3, H * W)``: camera-frame ray coordinates ``(qx, qy, 1)``.
    vignette : numpy.ndarray
        Per-pixel gain, shape ``(H * W,)``.
    reference_distance_m : float
        Distance at which the lamp's fall-off factor is 1.
    cover : numpy.ndarray or None
        Shape ``(nz, ncols, 3)``: the overgrowth over the pipe, as alpha,
        albedo times alpha and top height above the seabed (m), on columns
        of the seabed grid from ``X = cover_x0`` (see
        :meth:`benchmark.modalities.camera.scenes.overgrowth.CoverLayer.pipe_band`); None
        when there is none.
    cover_x0 : float
        ``X`` of the first column of ``cover``, m.
    snow : SnowCloud or None
        Marine snow of the water model.
    caustics : CausticWaves or None
        Sun flicker of the water model.
    crossings : tuple of CrossingCable
        Cables lying across the pipe (:mod:`~benchmark.modalities.camera.scenes.crossing`).
    """

    grid: TextureGrid
    seabed: np.ndarray
    seabed_coarse: np.ndarray
    coarse_factor: int
    cable: np.ndarray
    sand: np.ndarray
    rays: np.ndarray
    vignette: np.ndarray
    reference_distance_m: float
    cover: np.ndarray | None = None
    cover_x0: float = 0.0
    snow: SnowCloud | None = None
    caustics: CausticWaves | None = None
    crossings: tuple[CrossingCable, ...] = ()


@dataclass(frozen=True)
class _PipeSurface:
    """Where rays meet the pipe: depth ``t``, point ``(px, py)``, ray ``hy`` and ``|D|``, facing, map row, albedo, buried."""

    t: np.ndarray
    px: np.ndarray
    py: np.ndarray
    hy: np.ndarray
    hn: np.ndarray
    facing: np.ndarray
    row: np.ndarray
    albedo: np.ndarray
    under: np.ndarray


def remap_flat(source: np.ndarray, col: np.ndarray, row: np.ndarray) -> np.ndarray:
    """Bilinear samples of a wrapping map at flat arrays of texel coordinates.

    :func:`cv2.remap` needs 2-D coordinate maps narrower than 32767, so the
    coordinates are laid out in rows of 1024 (padded) and the result is
    flattened back; multi-channel maps give shape ``(n, channels)``.
    """
    n = col.size
    rows = -(-n // REMAP_ROW)
    padded = rows * REMAP_ROW
    if padded != n:
        col = np.concatenate((col.ravel(), np.zeros(padded - n, dtype=np.float32)))
        row = np.concatenate((row.ravel(), np.zeros(padded - n, dtype=np.float32)))
    sampled = cv2.remap(
        source,
        col.reshape(rows, REMAP_ROW),
        row.reshape(rows, REMAP_ROW),
        cv2.INTER_LINEAR,
        borderMode=cv2.BORDER_WRAP,
    )
    flat = sampled.reshape(padded, -1)[:n]
    return flat[:, 0] if sampled.ndim == 2 else flat


def camera_rays(focal_px: float, size: tuple[int, int]) -> np.ndarray:
    """Ray coordinates ``(qx, qy, 1)`` of all pixels, shape ``(3, H * W)``, ``float32``."""
    qx, qy = pixel_rays(focal_px, size)
    return np.stack((qx.ravel(), qy.ravel(), np.ones(qx.size, dtype=np.float32)))


def vignette_gain(size: tuple[int, int], strength: float) -> np.ndarray:
    """Gain ``1 - strength * rho^2`` with ``rho`` the distance from the centre over the half diagonal."""
    width, height = size
    x = (np.arange(width, dtype=np.float32) - (width - 1) / 2) / (0.5 * math.hypot(width, height))
    y = (np.arange(height, dtype=np.float32) - (height - 1) / 2) / (0.5 * math.hypot(width, height))
    rho2 = x[None, :] ** 2 + y[:, None] ** 2
    return (1.0 - strength * rho2).astype(np.float32).ravel()


class _Workspace:
    """Buffers reused from frame to frame.

    Allocating a few dozen full-frame temporaries per frame costs as much as
    the arithmetic (fresh pages from the system), so the full-frame steps
    write into these buffers instead.
    """

    def __init__(self, size: tuple[int, int]) -> None:
        width, height = size
        n = width * height
        self.rays = np.empty((3, n), dtype=np.float32)
        self.norm2, self.norm, self.t_ground, self.col, self.row = (np.empty(n, dtype=np.float32) for _ in range(5))
        self.facing, self.lit, self.qa, self.qb, self.disc, self.tmp = (np.empty(n, dtype=np.float32) for _ in range(6))
        self.albedo = np.empty((height, width), dtype=np.float32)
        self.coarse = np.empty((height, width), dtype=np.float32)
        self.blurred = np.empty((height, width), dtype=np.float32)
        self.noise = np.empty((height, width), dtype=np.float32)
        self.hit, self.ahead = np.empty(n, dtype=bool), np.empty(n, dtype=bool)


class Renderer:
    """Renders frames of one scene.

    Parameters
    ----------
    spec : CameraSceneSpec
        The scene definition (optics, pipe size, image size).
    assets : SceneAssets
        Its precomputed arrays.
    """

    def __init__(self, spec: CameraSceneSpec, assets: SceneAssets) -> None:
        self.spec = spec
        self.assets = assets
        optics = spec.optics
        self._formation: WaterFormation | None = None
        if optics.water is not None:
            formation = WaterFormation(spec, assets.reference_distance_m, MAX_RANGE_M, assets.snow, assets.caustics)
            clearest = float(np.min(formation.optics.beta_d))
            self._max_range = min(MAX_RANGE_M, -math.log(OPAQUE_TRANSMISSION) / clearest)
            formation.max_range_m = self._max_range
            self._formation = formation
        elif optics.attenuation_per_m > 0:
            self._max_range = min(MAX_RANGE_M, -math.log(OPAQUE_TRANSMISSION) / optics.attenuation_per_m)
        else:
            self._max_range = MAX_RANGE_M
        self._gain = (assets.vignette * np.float32(optics.exposure)).astype(np.float32)
        self._work = _Workspace(spec.frame_size)
        self._normal_table = gaussian_table() if optics.noise_grey > 0 or optics.shot_noise > 0 else None

    def render(
        self, pose: CameraPose, rng: np.random.Generator, time_s: float = 0.0, clean: bool = False
    ) -> np.ndarray:
        """One grey frame seen from ``pose``.

        Parameters
        ----------
        pose : CameraPose
            Camera pose in the pipeline frame.
        rng : numpy.random.Generator
            Source of the sensor noise and suspended particles of this frame.
        time_s : float
            Time of the frame, for what moves by itself (the water model's
            sun flicker and marine snow).
        clean : bool
            Stop before the sensor's noise, quantisation and compression:
            return the blurred ``float32`` image (``rng`` is not used).

        Returns
        -------
        numpy.ndarray
            ``uint8`` image of shape ``(H, W)``.

        References
        ----------
        seeds/004, section II (pinhole camera, pipe as a cylinder of known
        diameter on the seabed).
        """
        spec, assets, optics, work = self.spec, self.assets, self.spec.optics, self._work
        width, height = spec.frame_size
        grid = assets.grid
        radius = spec.radius
        inv_cell = np.float32(1.0 / grid.cell)
        f32 = np.float32
        tmp = work.tmp

        axes = pose_axes(pose)
        np.matmul(np.linalg.inv(axes).astype(np.float32), assets.rays, out=work.rays)
        dx, dy, dz = work.rays
        norm2, norm = work.norm2, work.norm
        np.multiply(dx, dx, out=norm2)
        np.multiply(dy, dy, out=tmp)
        norm2 += tmp
        qa = work.qa
        np.copyto(qa, norm2)
        np.multiply(dz, dz, out=tmp)
        norm2 += tmp
        np.sqrt(norm2, out=norm)

        # Seabed plane Y = -r.  Rays that go down too gently (or up) stop at
        # the depth where the water is opaque.
        height_above = pose.cy + radius
        down = work.facing
        np.minimum(dy, f32(-height_above / self._max_range), out=down)
        t_ground = work.t_ground
        np.divide(f32(-height_above), down, out=t_ground)
        col, row = work.col, work.row
        np.multiply(dx, inv_cell, out=col)
        col *= t_ground
        col += f32((pose.cx - grid.x0) / grid.cell)
        np.multiply(dz, inv_cell, out=row)
        row *= t_ground
        row += f32((pose.cz - grid.z0) / grid.cell)
        albedo = self._sample_seabed(t_ground, down)
        facing = down
        np.divide(down, norm, out=facing)
        np.negative(facing, out=facing)

        # Pipe X^2 + Y^2 = r^2: the nearer root where the ray meets it ahead.
        qb, disc = work.qb, work.disc
        np.multiply(dx, f32(pose.cx), out=qb)
        np.multiply(dy, f32(pose.cy), out=tmp)
        qb += tmp
        np.multiply(qb, qb, out=disc)
        np.multiply(qa, f32(pose.cx**2 + pose.cy**2 - radius**2), out=tmp)
        disc -= tmp
        np.greater(disc, 0.0, out=work.hit)
        np.less(qb, f32(-1e-9), out=work.ahead)
        work.hit &= work.ahead
        hits = np.flatnonzero(work.hit)
        if self._formation is not None:
            return self._sensor(self._water_image(pose, axes, hits, time_s).reshape(height, width), rng, clean)

        lit = work.lit
        np.multiply(facing, f32(1.0 - optics.ambient), out=lit)
        lit += f32(optics.ambient)
        lit *= albedo
        depth = t_ground
        if hits.size:
            exposed, lit_pipe, t_pipe, buried, relief = self._shade_pipe(hits, pose)
            lit[exposed] = lit_pipe
            depth[exposed] = t_pipe
            lit[buried] *= relief
        for crossing in assets.crossings:
            self._draw_crossing(crossing, pose, lit, depth)

        gain = self._automatic_gain(pose, axes[2])
        if optics.light_falloff:
            # Daylight reaches everything alike; the lamp's share falls off with distance squared.
            lamp = gain * (1.0 - optics.daylight)
            np.multiply(depth, depth, out=tmp)
            tmp *= norm2
            np.divide(f32(lamp * assets.reference_distance_m**2), tmp, out=tmp)
            np.minimum(tmp, f32(lamp * LAMP_CLAMP), out=tmp)
            tmp += f32(gain * optics.daylight)
            lit *= tmp
        else:
            lit *= f32(gain)
        lit *= self._gain
        if optics.attenuation_per_m > 0:
            water = f32(optics.water_grey)
            np.multiply(depth, norm, out=tmp)
            tmp *= f32(-optics.attenuation_per_m)
            np.exp(tmp, out=tmp)
            lit -= water
            lit *= tmp
            lit += water
        return self._sensor(lit.reshape(height, width), rng, clean)

    def _lamp_factor(self, distance: float) -> float:
        """Light at ``distance`` relative to the reference distance: daylight plus the lamp's fall-off."""
        optics = self.spec.optics
        if not optics.light_falloff:
            return 1.0
        lamp = min(self.assets.reference_distance_m**2 / max(distance, 1e-6) ** 2, LAMP_CLAMP)
        return optics.daylight + (1.0 - optics.daylight) * lamp

    def _automatic_gain(self, pose: CameraPose, axis: np.ndarray) -> float:
        """The camera's gain control: it undoes ``auto_gain`` of the light change at the image centre.

        ``axis`` is the optical axis ``a`` of the pose.
        """
        optics = self.spec.optics
        if optics.auto_gain <= 0:
            return 1.0
        down = -float(axis[1]) / math.hypot(*(float(c) for c in axis))
        if down > 0.05:
            distance = (pose.cy + self.spec.radius) / down
        else:
            distance = self._max_range
        return self._lamp_factor(distance) ** -optics.auto_gain

    def _sample_seabed(self, t_ground: np.ndarray, down: np.ndarray) -> np.ndarray:
        """Seabed albedo at the texel coordinates in the workspace.

        Where a pixel covers more than 1.5 texels the coarse map fades in
        (fully from 4.5 texels), so distant sand does not shimmer; only the
        rows that need it are blended.
        """
        assets, work = self.assets, self._work
        width, height = self.spec.frame_size
        col, row = work.col.reshape(height, width), work.row.reshape(height, width)
        fine = cv2.remap(
            assets.seabed, col, row, cv2.INTER_LINEAR, dst=work.albedo, borderMode=cv2.BORDER_WRAP
        ).reshape(-1)
        # Texels per pixel: distance / (focal * cos(incidence)) / cell = t |D|^2 / (-D_y) / (f cell).
        footprint = work.qb
        np.multiply(t_ground, work.norm2, out=footprint)
        footprint /= down
        footprint *= np.float32(-1.0 / (self.spec.focal_px * assets.grid.cell))
        rows = np.flatnonzero(footprint.reshape(height, width).max(axis=1) > 1.5)
        if rows.size == 0:
            return fine
        span = slice(int(rows[0]) * width, (int(rows[-1]) + 1) * width)
        weight = footprint[span]
        weight -= np.float32(1.5)
        weight /= np.float32(3.0)
        np.clip(weight, 0.0, 1.0, out=weight)
        factor = np.float32(1.0 / assets.coarse_factor)
        band = slice(int(rows[0]), int(rows[-1]) + 1)
        coarse = work.coarse[band]
        coarse = cv2.remap(
            assets.seabed_coarse,
            col[band] * factor,
            row[band] * factor,
            cv2.INTER_LINEAR,
            dst=coarse,
            borderMode=cv2.BORDER_WRAP,
        )
        blend = coarse.reshape(-1)
        blend -= fine[span]
        blend *= weight
        fine[span] += blend
        return fine

    def _pipe_surface(self, hits: np.ndarray, pose: CameraPose) -> _PipeSurface:
        """Where the rays ``hits`` meet the pipe, and its surface there."""
        spec, assets, work = self.spec, self.assets, self._work
        grid = assets.grid
        radius = np.float32(spec.radius)
        dx, dy, dz = work.rays
        hx, hy, hz, hn = dx[hits], dy[hits], dz[hits], work.norm[hits]
        t = (-work.qb[hits] - np.sqrt(work.disc[hits])) / work.qa[hits]
        px = np.float32(pose.cx) + t * hx
        py = np.float32(pose.cy) + t * hy
        pz = np.float32(pose.cz) + t * hz
        # Lamp at the camera: cos of the angle between the normal (px, py, 0)/r and -D.
        facing = np.maximum(-(px * hx + py * hy) / (radius * hn), np.float32(0.0))
        psi = np.arctan2(px, py)
        row = (pz - np.float32(grid.z0)) / np.float32(grid.cell)
        col = psi * np.float32(PSI_CELLS / (2 * math.pi)) + np.float32(PSI_CELLS / 2)
        surface = remap_flat(assets.cable, col, row)
        sand_rows = np.clip(row.astype(np.int32), 0, grid.nz - 1)
        under = py < assets.sand[sand_rows] + surface[:, 1]
        return _PipeSurface(t, px, py, hy, hn, facing, row, surface[:, 0], under)

    @staticmethod
    def _highlight(facing: np.ndarray, specular: float) -> np.ndarray:
        """The highlight along the middle of a cable, ``specular cos^(2^4)`` of the angle to the lamp."""
        highlight = facing * facing
        for _ in range(HIGHLIGHT_SQUARINGS - 1):
            highlight *= highlight
        return np.float32(specular) * highlight

    def _shade_cable(self, albedo: np.ndarray, facing: np.ndarray, specular: float) -> np.ndarray:
        """A cable's surface lit by the lamp at the camera: Lambert with the ambient share, plus the highlight."""
        ambient = np.float32(self.spec.optics.ambient)
        lit = albedo * (ambient + (1 - ambient) * facing)
        if specular > 0:
            lit += self._highlight(facing, specular)
        return lit

    def _crossing_in_front(self, crossing: CrossingCable, pose: CameraPose, depth: np.ndarray) -> CrossingHits:
        """Where ``crossing`` is nearer than the surface each pixel saw so far; ``depth`` takes its depth there."""
        seen = crossing.hits(pose, self._work.rays, self._work.norm2)
        front = seen.where(seen.t < depth[seen.index])
        depth[front.index] = front.t
        return front

    def _draw_crossing(self, crossing: CrossingCable, pose: CameraPose, lit: np.ndarray, depth: np.ndarray) -> None:
        """Shade, in place, the pixels that see ``crossing`` nearer than what they saw (``depth``, updated too)."""
        front = self._crossing_in_front(crossing, pose, depth)
        lit[front.index] = self._shade_cable(front.albedo, front.facing, crossing.look.specular)

    def _water_crossing(
        self, crossing: CrossingCable, pose: CameraPose, pipe: PipePixels, depth: np.ndarray
    ) -> PipePixels:
        """``pipe``'s pixels for the water model, those where ``crossing`` is nearer taken by it (``depth`` updated)."""
        front = self._crossing_in_front(crossing, pose, depth)
        keep = ~np.isin(pipe.index, front.index)
        specular = crossing.look.specular
        highlight = self._highlight(front.facing, specular) if specular > 0 else np.zeros_like(front.facing)
        normal_z = np.zeros_like(pipe.normal_x) if pipe.normal_z is None else pipe.normal_z
        return PipePixels(
            np.concatenate((pipe.index[keep], front.index)),
            np.concatenate((pipe.normal_x[keep], front.normal[0])),
            np.concatenate((pipe.normal_y[keep], front.normal[1])),
            np.concatenate((pipe.albedo[keep], front.albedo)),
            np.concatenate((pipe.cover[keep], np.zeros_like(front.albedo))),
            np.concatenate((pipe.highlight[keep], highlight)),
            np.concatenate((normal_z[keep], front.normal[2])),
        )

    def _shade_pipe(
        self, hits: np.ndarray, pose: CameraPose
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """Shade the pixels whose ray meets the pipe.

        Returns
        -------
        exposed, lit, depth : numpy.ndarray
            Pixels that see the pipe above the sand, their lit albedo and depth.
        buried, relief : numpy.ndarray
            Pixels where sand covers the pipe: they keep the seabed's values,
            times ``relief``, a faint trace of the mound over the pipe.
        """
        pipe = self._pipe_surface(hits, pose)
        facing, t = pipe.facing, pipe.t
        lit = self._shade_cable(pipe.albedo, facing, self.spec.cable.specular)
        if self.assets.cover is not None:
            self._overgrow(lit, hits, pipe.px, pipe.py, pipe.row)
        under = pipe.under
        if not under.any():
            return hits, lit, t, hits[:0], lit[:0]
        above = ~under
        return hits[above], lit[above], t[above], hits[under], self._relief(pipe)

    @staticmethod
    def _relief(pipe: _PipeSurface) -> np.ndarray:
        """The faint trace of the mound over a buried pipe, a factor on the seabed's light."""
        under = pipe.under
        relief = 1.0 + MOUND_RELIEF * (pipe.facing[under] + pipe.hy[under] / pipe.hn[under])
        return relief.astype(np.float32)

    def _water_image(self, pose: CameraPose, axes: np.ndarray, hits: np.ndarray, time_s: float) -> np.ndarray:
        """The frame through the image formation model (:class:`WaterFormation`), before the sensor."""
        assert self._formation is not None
        work, spec = self._work, self.spec
        albedo, depth = work.albedo.reshape(-1), work.t_ground
        empty = np.zeros(0, dtype=np.float32)
        pipe = PipePixels(hits[:0], empty, empty, empty, empty, empty)
        if hits.size:
            surface = self._pipe_surface(hits, pose)
            lit = surface.albedo.copy()
            cover = np.zeros_like(lit)
            if self.assets.cover is not None:
                cover = self._overgrow(lit, hits, surface.px, surface.py, surface.row, shaded=False)
            above = ~surface.under
            specular = spec.cable.specular
            highlight = self._highlight(surface.facing, specular) if specular > 0 else np.zeros_like(lit)
            inverse_radius = np.float32(1.0 / spec.radius)
            pipe = PipePixels(
                hits[above],
                surface.px[above] * inverse_radius,
                surface.py[above] * inverse_radius,
                lit[above],
                cover[above],
                highlight[above],
            )
            depth[pipe.index] = surface.t[above]
            if surface.under.any():
                albedo[hits[surface.under]] *= self._relief(surface)
        for crossing in self.assets.crossings:
            pipe = self._water_crossing(crossing, pose, pipe, depth)
        return self._formation.image(
            pose, axes, time_s, work.rays, depth, work.norm, albedo, pipe, self.assets.vignette
        )

    def _overgrow(
        self, lit: np.ndarray, hits: np.ndarray, px: np.ndarray, py: np.ndarray, row: np.ndarray, shaded: bool = True
    ) -> np.ndarray:
        """Lay the overgrowth over the lit pipe pixels ``hits`` (in place on ``lit``); returns the share it covers.

        The layer is sampled at the pipe point's ``(X, Z)``; it hides the
        pipe where its top is above the point (with a soft step of
        :data:`COVER_EDGE_M`) and is lit with the seabed's Lambertian
        factor of the same ray, so an alga or a stone looks the same on both
        sides of a border it crosses.  Unshaded (``shaded=False``), ``lit``
        is an albedo and the overgrowth's albedo is laid over it as it is.
        """
        spec, assets = self.spec, self.assets
        cell = np.float32(assets.grid.cell)
        col = (px - np.float32(assets.cover_x0)) / cell
        cover = remap_flat(assets.cover, col, row)
        step = cover[:, 2] - py
        step -= np.float32(spec.radius)
        step *= np.float32(1.0 / COVER_EDGE_M)
        step += np.float32(0.5)
        np.clip(step, 0.0, 1.0, out=step)
        lit *= 1.0 - cover[:, 0] * step
        if shaded:
            ambient = np.float32(spec.optics.ambient)
            shade = self._work.facing[hits] * (1 - ambient) + ambient
            lit += cover[:, 1] * step * shade
        else:
            lit += cover[:, 1] * step
        return cover[:, 0] * step

    def _sensor(self, image: np.ndarray, rng: np.random.Generator, clean: bool = False) -> np.ndarray:
        """Blur, suspended particles, noise, quantisation and compression (only blur and particles when ``clean``).

        The noise has the variance ``noise_grey^2 + shot_noise * I`` at grey
        level ``I``: read noise and the shot noise of the photons counted
        (Poisson, so its variance grows with the signal).
        """
        optics, work = self.spec.optics, self._work
        height, width = image.shape
        if optics.snow_per_frame > 0 and optics.water is None and not clean:
            count = int(rng.poisson(optics.snow_per_frame))
            rows = rng.integers(0, height, count)
            cols = rng.integers(0, width, count)
            np.add.at(image, (rows, cols), rng.uniform(60.0, 160.0, count).astype(np.float32))
        if optics.blur_px > 0:
            image = cv2.GaussianBlur(image, (0, 0), optics.blur_px, dst=work.blurred)
        if clean:
            return image.copy()
        if self._normal_table is not None:
            draws = rng.integers(0, len(self._normal_table), image.size, dtype=np.uint16)
            np.take(self._normal_table, draws.reshape(image.shape), out=work.noise)
            if optics.shot_noise > 0:
                work.noise *= noise_sigma(image, optics.noise_grey, optics.shot_noise)
            else:
                work.noise *= np.float32(optics.noise_grey)
            image += work.noise
        image += np.float32(0.5)
        np.clip(image, 0.0, 255.0, out=image)
        frame = image.astype(np.uint8)
        if optics.jpeg_quality > 0:
            frame = jpeg_roundtrip(frame, optics.jpeg_quality)
        return frame


def noise_sigma(grey: np.ndarray | float, read_grey: float, shot_noise: float) -> np.ndarray:
    """Standard deviation of the sensor noise at grey level ``grey``: ``sqrt(read^2 + shot * max(grey, 0))``."""
    variance = np.maximum(np.asarray(grey, dtype=np.float32), np.float32(0.0)) * np.float32(shot_noise)
    variance += np.float32(read_grey**2)
    return np.sqrt(variance)


def jpeg_roundtrip(frame: np.ndarray, quality: int) -> np.ndarray:
    """A grey ``uint8`` frame encoded as JPEG at ``quality`` (1-100) and decoded, as a video link would deliver it."""
    ok, encoded = cv2.imencode(".jpg", frame, [cv2.IMWRITE_JPEG_QUALITY, int(quality)])
    if not ok:
        raise ValueError(f"JPEG encoding failed at quality {quality}")
    return cv2.imdecode(encoded, cv2.IMREAD_GRAYSCALE)
