"""The image formation model applied to a ray-cast frame: light, water, exposure.

The renderer (:mod:`benchmark.modalities.camera.scenes.render`) casts the
rays and finds, for every pixel, the surface it sees (seabed or pipe), its
albedo, normal and range.  When a spec has ``[optics.water]``,
:class:`WaterFormation` turns those into the light the camera receives, per
colour channel ``c`` (R, G, B), in units where a white Lambertian surface
under irradiance ``E`` returns ``E``:

    I_c = rho t_c (sum_lamps E_lamp_c + E_day_c) exp(-beta_D_c z)      direct signal
          + R_c E_day_c (1 - exp(-beta_B_c z))                        daylight backscatter
          + B_lamp_c(z)                                               lamps' backscatter

where ``rho t_c`` is the albedo times the material's tint, ``z`` the range
from the camera, ``E_lamp_c = I P cos(iota) / d^2 exp(-beta_D_c d)`` each
lamp's light at the surface over the distance ``d`` from it
(:mod:`~benchmark.modalities.camera.scenes.lighting`), ``E_day_c`` the
daylight at depth times the sun flicker, Lambert's cosine of the surface to
the vertical and a share of light from all directions, and ``R_c``,
``beta_D_c``, ``beta_B_c`` the water type's wideband coefficients
(:mod:`~benchmark.modalities.camera.scenes.water`; Akkaynak and Treibitz
2018, eq. (11)).  The lengths through water are thus camera to surface for
the direct signal and lamp to surface to camera for the lamps' light.  The
pipe's middle also shows a white highlight of the lamps' light.

Grey is BT.601 luma of the three channels, applied as soon as the channels
no longer differ (all of the model is linear in the channels, so the sum is
taken per term).  Marine snow (:mod:`~benchmark.modalities.camera.scenes.snow`)
is laid over the result, lens vignetting applied, and the camera's automatic
exposure scales the frame so that its mean is ``mean_grey``; the sensor's
blur, noise, quantisation and compression follow in the renderer.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import cv2
import numpy as np

from benchmark.modalities.camera.model import CameraPose
from benchmark.modalities.camera.scenes.lighting import (
    BACKSCATTER_CELL_PX,
    CausticWaves,
    beam_profile,
    lamp_axis,
    lamp_backscatter_table,
    lookup_backscatter,
)
from benchmark.modalities.camera.scenes.snow import SNOW_ALBEDO, SNOW_RANGE_M, SnowCloud, splat
from benchmark.modalities.camera.scenes.spec import CameraSceneSpec
from benchmark.modalities.camera.scenes.water import GREY_WEIGHTS, daylight_at_depth, water_optics

METERING_STEP = 4
"""The exposure meters every fourth pixel of every fourth row."""

HIGHLIGHT_SHARE = 0.02
"""Share of the frame the exposure keeps from saturating."""

HIGHLIGHT_GREY = 235.0
"""Grey level the brightest :data:`HIGHLIGHT_SHARE` of a frame is held at, at most."""

NEAREST_LAMP_M = 0.05
"""Distances from a lamp below this are taken as this (no surface is inside the lamp's housing)."""


@dataclass
class PipePixels:
    """What the renderer found where rays meet the exposed pipe.

    Attributes
    ----------
    index : numpy.ndarray
        Flat pixel indices.
    normal_x, normal_y : numpy.ndarray
        The pipe's unit normal ``(px, py, 0) / r`` there.
    albedo : numpy.ndarray
        Albedo (bare pipe, growth and overgrowth blended).
    cover : numpy.ndarray
        Share of the pixel that overgrowth covers (it takes the seabed's tint).
    highlight : numpy.ndarray
        Specular highlight factor, already times the cable's ``specular``.
    normal_z : numpy.ndarray or None
        The normal's ``Z`` component where it has one (a cable crossing the
        pipe, :mod:`~benchmark.modalities.camera.scenes.crossing`); None
        where every normal is across ``Z``, as the pipe's.
    """

    index: np.ndarray
    normal_x: np.ndarray
    normal_y: np.ndarray
    albedo: np.ndarray
    cover: np.ndarray
    highlight: np.ndarray
    normal_z: np.ndarray | None = None


class WaterFormation:
    """Per-sequence constants of the image formation model, and the per-frame shading.

    Parameters
    ----------
    spec : CameraSceneSpec
        A spec whose ``optics.water`` is set.
    aim_m : float
        Distance along the optical axis at which the lamps are aimed and the
        lens is focused, and at which the wideband coefficients are taken.
    max_range_m : float
        Farthest range a ray is followed.
    snow : SnowCloud or None
        The sequence's marine snow.
    caustics : CausticWaves or None
        The sun flicker's waves.
    """

    def __init__(
        self,
        spec: CameraSceneSpec,
        aim_m: float,
        max_range_m: float,
        snow: SnowCloud | None,
        caustics: CausticWaves | None,
    ) -> None:
        water = spec.optics.water
        if water is None:
            raise ValueError(f"{spec.name}: the image formation model needs optics.water")
        self.spec, self.water = spec, water
        self.aim_m, self.max_range_m = aim_m, max_range_m
        self.optics = water_optics(water.jerlov, water.depth_m, aim_m)
        self.daylight = water.sun * daylight_at_depth(water.jerlov, water.depth_m)
        self.snow, self.caustics = snow, caustics
        self._seabed_weights = (GREY_WEIGHTS * np.asarray(spec.seabed.tint)).astype(np.float32)
        self._cable_weights = (GREY_WEIGHTS * np.asarray(spec.cable.tint)).astype(np.float32)
        self._veil_grey = float(GREY_WEIGHTS @ (self.optics.reflectance * self.daylight))
        self._lamps = [lamp for lamp in water.lamps if lamp.intensity > 0]
        self._axes = [lamp_axis(lamp, aim_m) for lamp in self._lamps]
        width, height = spec.frame_size
        factor = max(1, math.ceil(width / BACKSCATTER_CELL_PX))
        self._coarse_size = (max(2, width // factor), max(2, height // factor))
        coarse_rays = _coarse_rays(spec.focal_px / factor, self._coarse_size)
        self._backscatter = lamp_backscatter_table(tuple(self._lamps), self.optics, coarse_rays, aim_m, max_range_m)

    def image(
        self,
        pose: CameraPose,
        axes: np.ndarray,
        time_s: float,
        rays: np.ndarray,
        depth: np.ndarray,
        norm: np.ndarray,
        albedo: np.ndarray,
        pipe: PipePixels,
        vignette: np.ndarray,
    ) -> np.ndarray:
        """The frame's grey image after exposure, before the sensor's blur and noise.

        Parameters
        ----------
        pose : CameraPose
        axes : numpy.ndarray
            Rows ``h``, ``v``, ``a`` of the pose.
        time_s : float
            Time of the frame (moves the flicker and the snow).
        rays : numpy.ndarray
            Shape ``(3, N)``: world ray directions ``D`` with ``D . a = 1``.
        depth : numpy.ndarray
            ``t`` of the surface each ray meets (``X = C + t D``).
        norm : numpy.ndarray
            ``|D|``.
        albedo : numpy.ndarray
            Albedo of the seabed (the pipe's pixels are in ``pipe``).
        pipe : PipePixels
        vignette : numpy.ndarray
            Per-pixel lens gain.

        Returns
        -------
        numpy.ndarray
            ``float32`` image of shape ``(H, W)``.

        References
        ----------
        Akkaynak and Treibitz (2018), eq. (11); Jaffe (1990) for the lamps.
        """
        width, height = self.spec.frame_size
        f32 = np.float32
        dx, dy, dz = rays
        range_m = depth * norm
        # Surface point relative to the camera.
        rx, ry, rz = depth * dx, depth * dy, depth * dz
        normal_y = np.ones_like(depth)
        normal_y[pipe.index] = np.maximum(pipe.normal_y, 0.0)
        channels = [np.zeros_like(depth) for _ in range(3)]
        lamp_white = np.zeros_like(depth)
        path = np.empty_like(depth)
        to_world = np.linalg.inv(axes)
        for lamp, axis_cam in zip(self._lamps, self._axes):
            offset = to_world @ np.asarray(lamp.offset_m, dtype=float)
            aim = to_world @ axis_cam
            aim /= np.linalg.norm(aim)
            vx, vy, vz = rx - f32(offset[0]), ry - f32(offset[1]), rz - f32(offset[2])
            distance2 = vx * vx + vy * vy + vz * vz
            np.maximum(distance2, f32(NEAREST_LAMP_M**2), out=distance2)
            distance = np.sqrt(distance2)
            cos_beam = (vx * f32(aim[0]) + vy * f32(aim[1]) + vz * f32(aim[2])) / distance
            incidence = -vy
            incidence[pipe.index] = -(vx[pipe.index] * pipe.normal_x + vy[pipe.index] * pipe.normal_y)
            if pipe.normal_z is not None:
                incidence[pipe.index] -= vz[pipe.index] * pipe.normal_z
            np.maximum(incidence, 0.0, out=incidence)
            light = beam_profile(cos_beam, lamp)
            light *= incidence
            light /= distance * distance2
            light *= f32(lamp.intensity)
            # Lamp to surface to camera: one exponential per channel over the whole path.
            np.add(distance, range_m, out=path)
            for channel, weight, beta in zip(channels, GREY_WEIGHTS, self.optics.beta_d):
                arriving = np.multiply(path, f32(-beta))
                np.exp(arriving, out=arriving)
                arriving *= light
                channel += arriving
                arriving *= f32(weight)
                lamp_white += arriving
        if self.water.sun > 0:
            day = normal_y * f32(1.0 - self.water.sky_ambient) + f32(self.water.sky_ambient)
            if self.caustics is not None and self.caustics.amplitude > 0:
                day *= self.caustics.factor(rx + f32(pose.cx), rz + f32(pose.cz), time_s)
            for channel, sun, beta in zip(channels, self.daylight, self.optics.beta_d):
                passed = np.multiply(range_m, f32(-beta))
                np.exp(passed, out=passed)
                passed *= day
                passed *= f32(sun)
                channel += passed
        grey = self._weighted(channels, self._seabed_weights)
        grey *= albedo
        if pipe.index.size:
            cable = self._weighted([c[pipe.index] for c in channels], self._cable_weights)
            seabed = grey[pipe.index] / np.maximum(albedo[pipe.index], f32(1e-6))
            tinted = cable + pipe.cover * (seabed - cable)
            grey[pipe.index] = pipe.albedo * tinted + pipe.highlight * lamp_white[pipe.index]
        if self._veil_grey > 0:
            veil = sum(
                f32(w * r * e) * -np.expm1(range_m * f32(-b))
                for w, r, e, b in zip(GREY_WEIGHTS, self.optics.reflectance, self.daylight, self.optics.beta_b)
            )
            grey += veil
        if self._lamps:
            grey += self._lamp_backscatter(range_m.reshape(height, width)).reshape(-1)
        image = grey.reshape(height, width)
        if self.snow is not None and len(self.snow):
            self._add_snow(image, pose, axes, time_s, range_m.reshape(height, width))
        image *= vignette.reshape(height, width)
        image *= f32(self._exposure(image))
        return image

    def _exposure(self, image: np.ndarray) -> float:
        """The automatic exposure's gain: the frame's mean to ``mean_grey``, unless that saturates highlights.

        Like a camera's exposure control with highlight protection, the gain
        is also capped so that the brightest :data:`HIGHLIGHT_SHARE` of the
        frame (estimated on every :data:`METERING_STEP`-th pixel) stays at
        :data:`HIGHLIGHT_GREY`.
        """
        metered = image[::METERING_STEP, ::METERING_STEP]
        mean = max(float(metered.mean()), 1e-12)
        bright = max(float(np.quantile(metered, 1.0 - HIGHLIGHT_SHARE)), 1e-12)
        return min(self.water.mean_grey / mean, HIGHLIGHT_GREY / bright)

    @staticmethod
    def _weighted(channels: list[np.ndarray], weights: np.ndarray) -> np.ndarray:
        total = channels[0] * weights[0]
        total += channels[1] * weights[1]
        total += channels[2] * weights[2]
        return total

    def _lamp_backscatter(self, range_m: np.ndarray) -> np.ndarray:
        """The lamps' backscatter in grey at every pixel, from the coarse table at the block-mean range."""
        coarse = cv2.resize(range_m, self._coarse_size, interpolation=cv2.INTER_AREA)
        values = lookup_backscatter(self._backscatter, self.max_range_m, coarse.reshape(-1))
        width, height = self.spec.frame_size
        return cv2.resize(values.reshape(coarse.shape), (width, height), interpolation=cv2.INTER_LINEAR)

    def _add_snow(
        self, image: np.ndarray, pose: CameraPose, axes: np.ndarray, time_s: float, range_m: np.ndarray
    ) -> None:
        """Lay the particles in view over the image (before exposure)."""
        snow, spec = self.snow, self.spec
        assert snow is not None
        world = snow.positions.copy()
        world[1] -= snow.sink * time_s
        relative = world - np.array((pose.cx, pose.cy, pose.cz))[:, None]
        x, y, z = axes @ relative
        distance = np.sqrt(x * x + y * y + z * z)
        width, height = spec.frame_size
        focal = spec.focal_px
        near = (z > 0.05) & (distance < SNOW_RANGE_M)
        u = np.where(near, (width - 1) / 2 + focal * x / np.where(near, z, 1.0), -1e9)
        v = np.where(near, (height - 1) / 2 + focal * y / np.where(near, z, 1.0), -1e9)
        seen = near & (u > -8) & (u < width + 8) & (v > -8) & (v < height + 8)
        index = np.flatnonzero(seen)
        if index.size == 0:
            return
        u, v, z, distance = u[index], v[index], z[index], distance[index]
        cols = np.clip(np.round(u).astype(np.int64), 0, width - 1)
        rows = np.clip(np.round(v).astype(np.int64), 0, height - 1)
        keep = distance < range_m[rows, cols]
        index, u, v, z, distance = index[keep], u[keep], v[keep], z[keep], distance[keep]
        points = np.stack((x[index], y[index], z))
        light = np.zeros((3, index.size))
        for lamp, axis_cam in zip(self._lamps, self._axes):
            towards = points - np.asarray(lamp.offset_m, dtype=float)[:, None]
            rho = np.maximum(np.linalg.norm(towards, axis=0), NEAREST_LAMP_M)
            profile = beam_profile(axis_cam @ towards / rho, lamp).astype(float)
            light += lamp.intensity * profile / rho**2 * np.exp(-np.outer(self.optics.beta_d, rho))
        light += self.daylight[:, None] * self.water.sky_ambient
        radiance = SNOW_ALBEDO * GREY_WEIGHTS @ (light * np.exp(-np.outer(self.optics.beta_d, distance)))
        sizes = snow.diameters[index] * focal / z
        blur = self.water.defocus_px * np.abs(self.aim_m / z - 1.0)
        splat(image, np.stack((u, v)), sizes, blur, radiance)


def _coarse_rays(focal_px: float, size: tuple[int, int]) -> np.ndarray:
    """Camera-frame rays ``(qx, qy, 1)`` of a coarse grid with the same field of view, shape ``(3, n)``."""
    width, height = size
    qx = (np.arange(width) - (width - 1) / 2) / focal_px
    qy = (np.arange(height) - (height - 1) / 2) / focal_px
    grid_x, grid_y = np.meshgrid(qx, qy)
    return np.stack((grid_x.ravel(), grid_y.ravel(), np.ones(grid_x.size)))


__all__ = ["PipePixels", "WaterFormation"]
