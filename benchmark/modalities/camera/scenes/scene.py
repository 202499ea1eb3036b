"""A synthetic camera sequence: a :class:`benchmark.model.Sequence` rendered on the fly.

:class:`CameraScene` turns a :class:`~benchmark.modalities.camera.scenes.spec.CameraSceneSpec`
into frames.  All randomness comes from one seed: a
:class:`numpy.random.SeedSequence` of ``spec.seed`` spawns independent
streams for the textures, the trajectory noise, the inertial sensor's noise
and the per-frame sensor noise (frame ``k`` has its own stream, so any
frame can be rendered on its own and is identical to the one the full
iteration yields).  The same spec therefore gives bit-identical frames.

Nothing holds the rendered sequence: the object keeps only its spec, and
lazily the small per-sequence arrays (trajectory, albedo maps, sand
profile) in a cache that is dropped when the object is pickled, so worker
processes rebuild it (:class:`~benchmark.scenes.scene.SimulatedScene`).
Frames are rendered one at a time as they are iterated.

Each frame carries

* ``observation``: the ``uint8`` grey image;
* ``truth``: :class:`benchmark.modalities.camera.model.CameraTruth` with the projected cable
  state (:func:`benchmark.modalities.camera.scenes.silhouette.cable_truth`), the camera pose
  and the visible fraction (:func:`benchmark.modalities.camera.scenes.burial.visible_fraction`);
* ``navigation``: the :class:`benchmark.modalities.camera.model.VehicleSpeeds` an inertial
  sensor reports, i.e. the solution of seeds/004 eq. (7) plus noise.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from benchmark.errors import DataError
from benchmark.modalities.camera.model import CameraCalibration, CameraPose, CameraTruth, VehicleSpeeds
from benchmark.modalities.camera.scenes.burial import sand_level, visible_fraction
from benchmark.modalities.camera.scenes.crossing import CrossingCable
from benchmark.modalities.camera.scenes.motion import Trajectory, build_trajectory, vehicle_speeds
from benchmark.modalities.camera.scenes.overgrowth import overgrowth_layer
from benchmark.modalities.camera.scenes.projection import pixel_rays, pose_axes
from benchmark.modalities.camera.contrast import measure_contrast
from benchmark.modalities.camera.scenes.lighting import CausticWaves
from benchmark.modalities.camera.scenes.render import Renderer, SceneAssets, camera_rays, noise_sigma, vignette_gain
from benchmark.modalities.camera.scenes.snow import SNOW_RANGE_M, SnowCloud
from benchmark.modalities.camera.scenes.silhouette import cable_truth
from benchmark.modalities.camera.scenes.spec import CameraSceneSpec
from benchmark.modalities.camera.scenes.texture import TextureGrid, cable_map, coarse_level, lowpass_noise, seabed_map
from benchmark.model import SequenceInfo
from benchmark.scenes.scene import SimulatedScene

TEXEL_M = 0.01
"""Seabed and pipe texels are 1 cm."""

COARSE_FACTOR = 4

FAR_VIEW_M = 12.0
"""Seabed farther ahead than this reuses the map (it wraps); haze hides it."""

CONTRAST_FRAMES = 3
"""Frames, spread over the sequence, on which the cable's contrast is measured."""

# Indices of the independent random streams spawned from the seed.
_TEXTURE, _TRAJECTORY, _NAVIGATION, _FRAMES = range(4)


@dataclass
class _Cache:
    """What a scene computes once and keeps while it lives (never pickled)."""

    trajectory: Trajectory
    speeds: np.ndarray
    grid: TextureGrid
    sand_z: np.ndarray
    sand_y: np.ndarray
    renderer: Renderer | None = None


class CameraScene(SimulatedScene[CameraSceneSpec, _Cache]):
    """A rendered pipe-on-seabed camera sequence (seeds/004, section II).

    Parameters
    ----------
    spec : CameraSceneSpec
        The definition, seed included.

    Notes
    -----
    Rendering reuses per-scene buffers, so one scene object must not render
    in two threads at once; processes (each with its own unpickled copy)
    are fine.  The cached maps take 3-9 MB per sequence.

    Examples
    --------
    >>> scene = CameraScene.from_dict({"name": "camera/demo", "n_frames": 3})
    >>> [frame.observation.shape for frame in scene]
    [(240, 320), (240, 320), (240, 320)]
    """

    spec_type = CameraSceneSpec

    def __init__(self, spec: CameraSceneSpec, conditions: Mapping[str, Any] | None = None) -> None:
        super().__init__(spec, conditions)
        self._measured: dict[str, float] | None = None

    def __setstate__(self, state: dict[str, Any]) -> None:
        super().__setstate__(state)
        self._measured = None

    @property
    def info(self) -> SequenceInfo:
        """Name, size, frame interval and :class:`CameraCalibration` of the sequence."""
        spec = self._spec
        return SequenceInfo(
            name=spec.name,
            modality="camera",
            n_frames=spec.n_frames,
            frame_size=spec.frame_size,
            frame_interval_s=spec.frame_interval_s,
            calibration=CameraCalibration(spec.focal_px, spec.pipe_diameter_m, spec.nominal_tilt),
            extra={
                "description": spec.description,
                "seed": spec.seed,
                "source": "rendered",
                "conditions": self.drawn_conditions,
            },
        )

    def _build_cache(self) -> _Cache:
        spec = self._spec
        trajectory = build_trajectory(spec.motion, spec.n_frames, spec.frame_interval_s, self._stream(_TRAJECTORY))
        _check_clearance(spec, trajectory)
        true_speeds = vehicle_speeds(trajectory, spec.frame_interval_s, spec.nominal_tilt)
        noise = self._stream(_NAVIGATION).standard_normal(true_speeds.shape)
        speeds = true_speeds + spec.motion.speed_noise_mps * noise
        grid = _seabed_grid(spec, trajectory)
        sand_z = grid.z_coords()
        sand_y = sand_level(spec.burial, spec.radius, sand_z, self._stream(_TEXTURE, 0))
        return _Cache(trajectory, speeds, grid, sand_z, sand_y)

    def _renderer(self) -> Renderer:
        state = self._state()
        if state.renderer is None:
            state.renderer = Renderer(self._spec, self._build_assets(state))
        return state.renderer

    def _build_assets(self, state: _Cache) -> SceneAssets:
        spec, grid = self._spec, state.grid
        seabed = seabed_map(spec.seabed, grid, self._stream(_TEXTURE, 1))
        surface = cable_map(spec.cable, grid.nz, grid.cell, spec.radius, self._stream(_TEXTURE, 2))
        jitter = 0.08 * spec.radius * lowpass_noise(self._stream(_TEXTURE, 3), surface.shape, (3.0, 3.0))
        cover, cover_x0 = None, 0.0
        layer = overgrowth_layer(spec.overgrowth, grid, spec.radius, self._stream(_TEXTURE, 4))
        if layer is not None:
            seabed = layer.composite(seabed)
            cover, cover_x0 = layer.pipe_band(spec.radius)
        snow, caustics = self._water_assets(state)
        crossings = tuple(
            CrossingCable.build(crossing, spec, grid, self._stream(_TEXTURE, 7, number))
            for number, crossing in enumerate(spec.crossing)
        )
        return SceneAssets(
            grid=grid,
            seabed=seabed,
            seabed_coarse=coarse_level(seabed, COARSE_FACTOR),
            coarse_factor=COARSE_FACTOR,
            cable=np.ascontiguousarray(np.stack((surface, jitter), axis=-1), dtype=np.float32),
            sand=state.sand_y,
            rays=camera_rays(spec.focal_px, spec.frame_size),
            vignette=vignette_gain(spec.frame_size, spec.optics.vignetting),
            reference_distance_m=_reference_distance(spec, state.trajectory),
            cover=cover,
            cover_x0=cover_x0,
            snow=snow,
            caustics=caustics,
            crossings=crossings,
        )

    def _water_assets(self, state: _Cache) -> tuple[SnowCloud | None, CausticWaves | None]:
        """Marine snow in the water the camera passes through, and the sun flicker's waves (water model only)."""
        spec = self._spec
        water = spec.optics.water
        if water is None:
            return None, None
        snow = None
        if water.snow_per_m3 > 0:
            trajectory = state.trajectory
            box = (
                (float(np.min(trajectory.cx)) - SNOW_RANGE_M, float(np.max(trajectory.cx)) + SNOW_RANGE_M),
                (-spec.radius, float(np.max(trajectory.cy)) + 1.0),
                (float(np.min(trajectory.cz)) - 1.0, float(np.max(trajectory.cz)) + SNOW_RANGE_M),
            )
            snow = SnowCloud.draw(self._stream(_TEXTURE, 5), box, water.snow_per_m3, water.snow_size_mm)
        caustics = None
        if water.sun > 0 and water.caustics > 0:
            caustics = CausticWaves.draw(
                self._stream(_TEXTURE, 6), water.caustic_scale_m, water.caustic_speed_mps, water.caustics, water.depth_m
            )
        return snow, caustics

    def trajectory(self) -> Trajectory:
        """The camera poses, ``n_frames + 1`` samples."""
        return self._state().trajectory

    def navigation(self, index: int) -> VehicleSpeeds:
        """Speeds reported at frame ``index`` (seeds/004 eq. (7), with sensor noise)."""
        s_x, s_y, s_z = (float(v) for v in self._state().speeds[self._check(index)])
        return VehicleSpeeds(lateral=s_x, vertical=s_y, frontal=s_z)

    def truth(self, index: int) -> CameraTruth:
        """Ground truth of frame ``index``, without rendering it."""
        return self.truth_from(self._state().trajectory.pose(self._check(index)))

    def truth_from(self, pose: CameraPose) -> CameraTruth:
        """The ground truth of the scene seen from any ``pose``: the cable's projection and the visible share."""
        spec, state = self._spec, self._state()
        cable = cable_truth(pose, spec.radius, spec.focal_px, spec.frame_size)
        visible = visible_fraction(pose, spec.radius, spec.focal_px, spec.frame_size, state.sand_z, state.sand_y)
        return CameraTruth(cable=cable, pose=pose, visible_fraction=visible)

    def render(self, index: int) -> np.ndarray:
        """The image of frame ``index`` alone (identical to the one :meth:`frames` yields)."""
        return self.render_from(self._state().trajectory.pose(self._check(index)), index)

    def render_clean(self, index: int) -> np.ndarray:
        """Frame ``index`` before the sensor's noise, quantisation and compression: ``float32`` grey levels."""
        return self.render_from(self._state().trajectory.pose(self._check(index)), index, clean=True)

    def render_from(self, pose: CameraPose, index: int, clean: bool = False) -> np.ndarray:
        """The scene seen from any ``pose`` at frame ``index``'s time, with that frame's sensor noise.

        A closed-loop run (:mod:`benchmark.closedloop`) renders its frames
        this way, from the poses its vehicle reaches; the seabed is textured
        over what the spec's own trajectory sees.
        """
        return self._renderer().render(pose, self._stream(_FRAMES, index), self._time(index), clean=clean)

    def _time(self, index: int) -> float:
        return index * self._spec.frame_interval_s

    def conditions(self) -> dict[str, Any]:
        """The drawn conditions, plus ``contrast_grey`` and ``noise_grey`` measured on the sequence.

        ``contrast_grey`` is :func:`~benchmark.modalities.camera.contrast.cable_contrast`
        averaged over :data:`CONTRAST_FRAMES` frames spread over the
        sequence, rendered without noise or compression (clipped to the
        grey levels an image can hold); ``noise_grey`` is
        the standard deviation of the sensor noise at the mean grey level of
        the cable in those frames.  Both are measured once and kept.
        """
        if self._measured is None:
            self._measured = self._measure()
        return {**self.drawn_conditions, **self._measured}

    def _measure(self) -> dict[str, float]:
        spec = self._spec
        frames = np.unique(np.linspace(0, spec.n_frames - 1, CONTRAST_FRAMES).round().astype(int))
        contrasts, cable_greys = [], []
        for index in frames:
            truth = self.truth(int(index))
            if not truth.cable.is_known:
                continue
            measured = measure_contrast(np.clip(self.render_clean(int(index)), 0.0, 255.0), truth.cable)
            if measured is not None:
                contrasts.append(measured.contrast)
                cable_greys.append(measured.cable_grey)
        if not contrasts:
            return {"contrast_grey": math.nan, "noise_grey": math.nan}
        sigma = noise_sigma(float(np.mean(cable_greys)), spec.optics.noise_grey, spec.optics.shot_noise)
        return {"contrast_grey": round(float(np.mean(contrasts)), 2), "noise_grey": round(float(sigma), 2)}

    def observation(self, index: int) -> np.ndarray:
        """The grey image of frame ``index``: :meth:`render`."""
        return self.render(index)


def _check_clearance(spec: CameraSceneSpec, trajectory: Trajectory) -> None:
    """The camera must stay above the seabed and outside the pipe, looking ahead rather than back."""
    problems = (
        (trajectory.cy + spec.radius <= 0.05, "is less than 5 cm above the seabed"),
        (np.hypot(trajectory.cx, trajectory.cy) <= 1.05 * spec.radius, "touches the pipe"),
        (np.abs(trajectory.phi) >= math.pi / 2 + 0.35, "looks backwards (tilt beyond 110 deg)"),
    )
    for bad, what in problems:
        frames = np.flatnonzero(bad[: spec.n_frames])
        if frames.size:
            raise DataError(f"{spec.name}: at frame {int(frames[0])} the camera {what}; check its motion")


def _ground_hits(spec: CameraSceneSpec, trajectory: Trajectory) -> tuple[np.ndarray, np.ndarray]:
    """``X`` and ``Z`` where the rays of the image's border pixels meet the seabed, every frame."""
    qx, qy = pixel_rays(spec.focal_px, spec.frame_size)
    border = np.concatenate((qx[0], qx[-1], qx[:, 0], qx[:, -1])), np.concatenate((qy[0], qy[-1], qy[:, 0], qy[:, -1]))
    rays = np.stack((border[0], border[1], np.ones_like(border[0]))).astype(float)
    xs, zs = [], []
    for k in range(len(trajectory)):
        pose = trajectory.pose(k)
        dx, dy, dz = np.linalg.inv(pose_axes(pose)) @ rays
        down = np.minimum(dy, -1e-9)
        t = (-spec.radius - pose.cy) / down
        reach = FAR_VIEW_M / np.sqrt(dx * dx + dy * dy + dz * dz)
        t = np.minimum(t, reach)
        xs.append(pose.cx + t * dx)
        zs.append(pose.cz + t * dz)
    return np.concatenate(xs), np.concatenate(zs)


def _seabed_grid(spec: CameraSceneSpec, trajectory: Trajectory) -> TextureGrid:
    """A texture grid over the seabed the camera sees during the sequence."""
    xs, zs = _ground_hits(spec, trajectory)
    half_width = float(np.clip(np.max(np.abs(xs)) + 0.5, 2.0, 6.0))
    nx = int(math.ceil(2 * half_width / TEXEL_M / 64.0)) * 64
    z_lo, z_hi = float(np.min(zs)) - 0.5, float(np.max(zs)) + 0.5
    nz = int(math.ceil((z_hi - z_lo) / TEXEL_M / 64.0)) * 64
    return TextureGrid(x0=-0.5 * nx * TEXEL_M, z0=z_lo, cell=TEXEL_M, nx=nx, nz=nz)


def _reference_distance(spec: CameraSceneSpec, trajectory: Trajectory) -> float:
    """The lamp's reference distance: given, or camera to seabed along the optical axis at the mean pose."""
    if spec.optics.reference_distance_m is not None:
        return spec.optics.reference_distance_m
    height = float(np.mean(trajectory.cy)) + spec.radius
    tilt = float(np.mean(trajectory.phi))
    return height / max(math.sin(tilt), 0.2)
