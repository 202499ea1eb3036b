"""Rendering of the chase boat's stereo pair, one pair of BGR images at a time.

Two level pinhole cameras look along CH's heading (seeds/002, Fig. 3): the
left one at CH's reference point, the right one the baseline ``B`` to
starboard, both ``camera_height_m`` above the sea, with the focal length
and principal points of the sequence's
:class:`~benchmark.modalities.stereo.model.StereoCalibration` and the vertical principal
point at the image centre.  Pixel ``(u, v)`` of a camera looks along
``(1, (u - C) / f, (C_v - v) / f)`` (ahead, starboard, up), so a point at
``(x_v, y_v)`` appears at column ``C_y + f y_v / x_v`` in the left image
and ``C_y* + f (y_v - B) / x_v`` in the right one: the model that eq. (15)
inverts (:func:`benchmark.modalities.stereo.geometry.project`).  Rows are
epipolar lines.

Each camera's image is built in layers, the background ray-cast for all
pixels at once with numpy:

1. sky: a gradient from the horizon's haze to the zenith's blue, fixed
   per sequence;
2. sea: every pixel below the horizon meets the sea plane at the forward
   distance ``h f / (v - C_v)`` of its row; the wave field
   (:class:`~benchmark.modalities.stereo.scenes.world.SeaTexture`) is sampled there in
   North-East coordinates, from the pyramid levels whose texels match the
   row's lateral footprint ``distance / f`` (rows and footprints are the
   same in both cameras, so the pattern keeps its disparity), hazed with
   distance, with sun glint on crests towards the sun;
3. shoreline: each column's ray meets the shoreline ring; the skyline
   height there decides which rows see land, coloured from the shore's
   map and hazed, with a soft top edge;
4. target boat: drawn over the background by
   :func:`benchmark.modalities.stereo.scenes.boat.draw_boat`, polygons projected and
   filled with sub-pixel precision;
5. sensor: Gaussian blur, Gaussian noise (the same on the three channels),
   quantisation to ``uint8``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import cv2
import numpy as np

from benchmark.modalities.stereo.geometry import to_north_east
from benchmark.modalities.stereo.model import StereoCalibration
from benchmark.modalities.stereo.scenes.boat import BoatBody, BoatView, boat_body, draw_boat
from benchmark.modalities.stereo.scenes.image_spec import StereoRenderSpec
from benchmark.modalities.stereo.scenes.world import (
    GLINT_THRESHOLD,
    SHORE_BINS,
    SHORE_ROWS,
    SeaTexture,
    Shore,
    sea_texture,
    shoreline,
)
from benchmark.scenes.noise import gaussian_table

SEA_HAZE_M = 350.0
"""Distance over which the sea fades into the horizon's haze (1 / e)."""

SHORE_HAZE_M = 3000.0
"""Distance over which the shoreline fades into the horizon's haze (1 / e)."""

GLINT_POWER = 6
"""Glint falls off as ``cos^6`` of the angle between a ray's azimuth and the sun's."""

GLINT_SCALE = 1.5
"""A slope this far above the glint threshold glitters at full strength."""

SKY_GRADIENT_DEG = 35.0
"""Elevation at which the sky reaches its zenith colour."""


@dataclass(frozen=True)
class StereoView:
    """Where the boats are when a pair is taken.

    Attributes
    ----------
    chase_position_m : tuple of float
        CH's true North-East position (the left camera's optical centre).
    chase_heading : float
        CH's true heading, rad clockwise from north (the cameras' optical axis).
    target_ahead_m, target_starboard_m : float
        TG's reference point in CH's camera frame, ``(x_v, y_v)`` of eq. (11).
    target_aspect : float
        TG's heading minus CH's, rad.
    time_s : float
        Time of the pair (the waves drift with it).
    """

    chase_position_m: tuple[float, float]
    chase_heading: float
    target_ahead_m: float
    target_starboard_m: float
    target_aspect: float
    time_s: float


@dataclass(frozen=True)
class _Camera:
    """Per-camera constants.

    ``offset_m`` is the camera's distance to starboard of CH's reference
    point, ``principal_px`` its ``C_y``, ``slopes`` the ``(u - C_y) / f`` of
    its columns and ``lateral`` the sea's starboard offset ``distance * slope``
    at every pixel below the horizon, in texels of the row's pyramid level.
    """

    offset_m: float
    principal_px: float
    slopes: np.ndarray
    lateral: np.ndarray


class StereoRenderer:
    """Renders the stereo pairs of one sequence.

    Parameters
    ----------
    spec : StereoRenderSpec
        The scene's appearance and the image height.
    calibration : StereoCalibration
        Focal length, baseline, principal points and width (seeds/002, Table 4).
    rng : numpy.random.Generator
        Source of the sequence's wave field and shoreline.

    References
    ----------
    seeds/002, section 2.2 (stereo geometry, Fig. 3, eq. 15) and section 4.1
    (the yellow blob tracked in the field, Fig. 10).
    """

    def __init__(self, spec: StereoRenderSpec, calibration: StereoCalibration, rng: np.random.Generator) -> None:
        self.spec = spec
        self.calibration = calibration
        self.sea: SeaTexture = sea_texture(spec, rng)
        self.shore: Shore = shoreline(spec, rng)
        self.body: BoatBody = boat_body(spec)
        width, height = calibration.width_px, spec.height_px
        self.size = (width, height)
        self.centre_row = (height - 1) / 2.0
        self.rises = (self.centre_row - np.arange(height)) / calibration.focal_px
        self._prepare_sea()
        self.cameras = (
            self._camera(0.0, calibration.principal_left_px),
            self._camera(calibration.baseline_m, calibration.principal_right_px),
        )
        self._sky = self._sky_image()
        # Noise samples scaled to the sensor's and offset by 0.5, so that truncation to uint8 rounds.
        self._noise_table = None
        if spec.noise_grey > 0:
            self._noise_table = gaussian_table() * np.float32(spec.noise_grey) + np.float32(0.5)

    # ------------------------------------------------------------------ setup
    def _camera(self, offset_m: float, principal_px: float) -> _Camera:
        slopes = (np.arange(self.size[0]) - principal_px) / self.calibration.focal_px
        lateral = (self.sea_distance * self.sea_scale)[:, None] * slopes[None, :]
        return _Camera(offset_m, principal_px, slopes, lateral.astype(np.float32))

    def _sky_image(self) -> np.ndarray:
        spec = self.spec
        width, height = self.size
        elevation = np.arctan(np.maximum(self.rises, 0.0))
        weight = np.clip(elevation / math.radians(SKY_GRADIENT_DEG), 0.0, 1.0) ** 0.7
        horizon, zenith = np.array(spec.sky_horizon_bgr), np.array(spec.sky_zenith_bgr)
        rows = horizon * (1.0 - weight[:, None]) + zenith * weight[:, None]
        return np.ascontiguousarray(np.broadcast_to(rows[:, None, :], (height, width, 3)), dtype=np.float32)

    def _prepare_sea(self) -> None:
        """Per-row distance, pyramid levels, colour, wave contrast and glint of the sea below the horizon."""
        spec, f = self.spec, self.calibration.focal_px
        first = int(math.floor(self.centre_row)) + 1
        self.sea_first_row = first
        rows = np.arange(first, self.size[1])
        distance = spec.camera_height_m * f / (rows - self.centre_row)
        self.sea_distance = distance
        top = len(self.sea.levels) - 1
        level = np.clip(np.log2(distance / (f * self.sea.texel_m)), 0.0, top)
        coarse = np.minimum(np.floor(level).astype(int), top - 1)
        # Rows blend level ``coarse`` (weight 1 - frac) with ``coarse + 1`` (weight frac).
        self.sea_blend = (level - coarse).astype(np.float32)[:, None]
        self.sea_scale = 1.0 / (self.sea.texel_m * np.exp2(coarse))
        self.sea_bands = [
            (int(lv), slice(int(idx[0]), int(idx[-1]) + 1))
            for lv in np.unique(coarse)
            for idx in [np.flatnonzero(coarse == lv)]
        ]
        self.sea_forward = (distance * self.sea_scale).astype(np.float32)[:, None]
        haze = 1.0 - np.exp(-distance / SEA_HAZE_M)
        near = np.array(spec.sea_bgr) * (0.85 + 0.15 * np.exp(-distance / 30.0))[:, None]
        horizon = np.array(spec.sky_horizon_bgr)
        self.sea_colour = (near * (1.0 - haze[:, None]) + horizon * haze[:, None]).astype(np.float32)[:, None, :]
        self.sea_contrast = (spec.wave_contrast * (1.0 - haze)).astype(np.float32)[:, None]
        self.sea_glint = (255.0 * spec.glint / GLINT_SCALE**2 * (1.0 - haze)).astype(np.float32)[:, None]

    # ----------------------------------------------------------------- render
    def render_pair(self, view: StereoView, rng: np.random.Generator) -> tuple[np.ndarray, np.ndarray]:
        """The left and right images of one instant.

        Parameters
        ----------
        view : StereoView
            CH's pose and TG's pose relative to it.
        rng : numpy.random.Generator
            Source of the sensor noise of this pair.

        Returns
        -------
        left, right : numpy.ndarray
            ``uint8`` BGR images of shape ``(H, W, 3)``.

        References
        ----------
        seeds/002, eq. (15) (the projection the images follow) and
        section 4.1 (a yellow blob on TG, tracked by colour).
        """
        return self._render(self.cameras[0], view, rng), self._render(self.cameras[1], view, rng)

    def _render(self, camera: _Camera, view: StereoView, rng: np.random.Generator) -> np.ndarray:
        image = self._sky.copy()
        north, east = to_north_east(0.0, camera.offset_m, view.chase_position_m, view.chase_heading)
        self._draw_sea(image, camera, north, east, view)
        self._draw_shore(image, camera, north, east, view.chase_heading)
        self._draw_boat(image, camera, view)
        return self._sensor(image, rng)

    def _draw_sea(self, image: np.ndarray, camera: _Camera, north: float, east: float, view: StereoView) -> None:
        sea = self.sea
        cos_h, sin_h = math.cos(view.chase_heading), math.sin(view.chase_heading)
        sun = math.radians(self.spec.sun_azimuth_deg)
        drift = self.spec.wave_drift_mps * view.time_s
        period = sea.period_m
        # The pattern's origin, wrapped in float64, so the float32 coordinates stay small and precise.
        base_n = ((north - drift * math.cos(sun)) % period) * self.sea_scale
        base_e = ((east - drift * math.sin(sun)) % period) * self.sea_scale
        tex_n = camera.lateral * np.float32(-sin_h)
        tex_n += (base_n[:, None] + cos_h * self.sea_forward).astype(np.float32)
        tex_e = camera.lateral * np.float32(cos_h)
        tex_e += (base_e[:, None] + sin_h * self.sea_forward).astype(np.float32)
        shade = np.empty(tex_n.shape, dtype=np.float32)
        for level, band in self.sea_bands:
            fine = _remap(sea.levels[level], tex_e[band], tex_n[band])
            tex_e[band] *= np.float32(0.5)
            tex_n[band] *= np.float32(0.5)
            coarse = _remap(sea.levels[level + 1], tex_e[band], tex_n[band])
            coarse -= fine
            coarse *= self.sea_blend[band]
            fine += coarse
            shade[band] = fine
        azimuth = view.chase_heading + np.arctan(camera.slopes)
        toward_sun = (np.maximum(np.cos(azimuth - sun), 0.0) ** GLINT_POWER).astype(np.float32)
        # Glint: the squared excess of the slope over the threshold, where the sun is ahead.
        glint = tex_n
        np.subtract(shade, np.float32(GLINT_THRESHOLD), out=glint)
        np.maximum(glint, np.float32(0.0), out=glint)
        glint *= glint
        glint *= self.sea_glint
        glint *= toward_sun
        shade *= self.sea_contrast
        shade += np.float32(1.0)
        channels = []
        for c in range(3):
            channel = shade * self.sea_colour[:, :, c]
            channel += glint
            channels.append(channel)
        image[self.sea_first_row :] = cv2.merge(channels)

    def _draw_shore(self, image: np.ndarray, camera: _Camera, north: float, east: float, heading: float) -> None:
        shore, spec, f = self.shore, self.spec, self.calibration.focal_px
        azimuth = heading + np.arctan(camera.slopes)
        dir_n, dir_e = np.cos(azimuth), np.sin(azimuth)
        along = north * dir_n + east * dir_e
        reach = -along + np.sqrt(along**2 - (north**2 + east**2) + shore.radius_m**2)
        forward = reach / np.sqrt(1.0 + camera.slopes**2)
        hit_n, hit_e = north + reach * dir_n, east + reach * dir_e
        bearing = np.mod(np.arctan2(hit_e, hit_n), 2.0 * math.pi) * (SHORE_BINS / (2.0 * math.pi))
        skyline = np.interp(bearing, np.arange(SHORE_BINS + 1), np.append(shore.heights_m, shore.heights_m[0]))
        h = spec.camera_height_m
        top_row = self.centre_row - f * (skyline - h) / forward
        bottom_row = self.centre_row + f * h / forward
        lo = max(int(math.floor(top_row.min())), 0)
        hi = min(int(math.ceil(bottom_row.max())), self.size[1] - 1)
        if hi < lo:
            return
        rows = np.arange(lo, hi + 1)[:, None]
        height_m = h + forward[None, :] * self.rises[rows]
        cover = np.clip(rows - top_row[None, :] + 0.5, 0.0, 1.0) * np.clip(bottom_row[None, :] - rows + 0.5, 0.0, 1.0)
        cover *= skyline[None, :] > 0.0
        z_index = (np.clip(height_m / shore.top_m, 0.0, 1.0) * (SHORE_ROWS - 1)).astype(np.float32)
        columns = np.ascontiguousarray(np.broadcast_to(bearing.astype(np.float32), z_index.shape))
        land = _remap(shore.colours, columns, z_index)
        haze = (1.0 - np.exp(-forward / SHORE_HAZE_M)).astype(np.float32)[None, :, None]
        land += (np.asarray(spec.sky_horizon_bgr, dtype=np.float32) - land) * haze
        band = image[lo : hi + 1]
        band += (land - band) * cover.astype(np.float32)[..., None]

    # ------------------------------------------------------------------- boat
    def _draw_boat(self, image: np.ndarray, camera: _Camera, view: StereoView) -> None:
        spec = self.spec
        heading = view.chase_heading + view.target_aspect
        sun_az = math.radians(spec.sun_azimuth_deg) - heading
        elevation = math.radians(spec.sun_elevation_deg)
        sun = np.array(
            (math.cos(elevation) * math.cos(sun_az), math.cos(elevation) * math.sin(sun_az), math.sin(elevation))
        )
        boat = BoatView(
            ahead_m=view.target_ahead_m,
            starboard_m=view.target_starboard_m - camera.offset_m,
            aspect=view.target_aspect,
            camera_height_m=spec.camera_height_m,
            sun=sun,
        )
        draw_boat(image, self.body, boat, self.calibration.focal_px, (camera.principal_px, self.centre_row))

    # ----------------------------------------------------------------- sensor
    def _sensor(self, image: np.ndarray, rng: np.random.Generator) -> np.ndarray:
        spec = self.spec
        if spec.blur_px > 0:
            image = cv2.GaussianBlur(image, (0, 0), spec.blur_px)
        if self._noise_table is not None:
            height, width = image.shape[:2]
            draws = rng.integers(0, len(self._noise_table), height * width, dtype=np.uint16)
            noise = np.take(self._noise_table, draws).reshape(height, width)
            cv2.add(image, cv2.merge((noise, noise, noise)), dst=image)
        else:
            image += np.float32(0.5)
        np.clip(image, 0.0, 255.0, out=image)
        return image.astype(np.uint8)


def _remap(source: np.ndarray, col: np.ndarray, row: np.ndarray) -> np.ndarray:
    """Bilinear samples of a map that wraps, at ``float32`` texel coordinates."""
    return cv2.remap(source, col, row, cv2.INTER_LINEAR, borderMode=cv2.BORDER_WRAP)
