"""A second cable lying across the followed one: where the rays meet it.

The followed pipe is the cylinder ``X^2 + Y^2 = r^2`` around the ``Z`` axis,
resting on the seabed ``Y = -r`` (seeds/004, section II).  A crossing
(:class:`~benchmark.modalities.camera.scenes.spec.Crossing`) is another
straight cylinder of radius ``r_c`` resting on the same seabed, its axis
the horizontal line through

    A = (0, r_c - r, at_m)     along     u = (sin a, 0, cos a)

with ``a`` the crossing angle from ``+Z`` towards ``+X``; so it passes
over the followed cable's axis at ``Z = at_m``.  In a closed-loop run the
pipe frame is the route's tangent frame and ``Z`` the arc length
(:mod:`benchmark.closedloop.loop`), so the crossing lies at that arc length
and at that angle to the route's tangent there.

Projection: it is ray cast like the pipe.  The ray ``C + t D`` of a pixel
(:func:`~benchmark.modalities.camera.scenes.projection.pixel_rays`, ``t``
the depth along the optical axis) meets the cylinder where the parts of
``C - A + t D`` perpendicular to ``u`` have length ``r_c``:

    |w_p + t D_p|^2 = r_c^2,   w_p = w - (w.u) u,  D_p = D - (D.u) u,  w = C - A,

a quadratic whose nearer root, where it is ahead of the camera, is the
point seen.  Its outward normal ``n`` (the part of ``P - A`` perpendicular
to ``u``, over ``r_c``), the arc length ``(P - A).u`` along it and the angle
``psi`` around it from its top (towards ``e = (cos a, 0, -sin a)``, which
is ``+X`` for a cable along ``Z``) address its surface map, a
:func:`~benchmark.modalities.camera.scenes.texture.cable_map` of its own
look.  The renderer shades it as it shades the pipe and keeps, in every
pixel, the surface nearer the camera: the two cylinders interpenetrate
where they cross, and whichever the ray meets first is seen.  The crossing
is neither buried by the followed cable's sand nor covered by its
overgrowth.  The image formation model of the water
(:mod:`~benchmark.modalities.camera.scenes.formation`) lights it by its
normal, which unlike the pipe's has a ``Z`` component, and tints it as the
followed cable.

The image of its axis, :func:`crossing_axis_line`, serves to find it in a
frame (tests, views); the ground truth stays the followed cable.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from benchmark.modalities.camera.model import CameraPose
from benchmark.modalities.camera.scenes.projection import ImageSize, homogeneous_line, projection_matrix
from benchmark.modalities.camera.scenes.render import remap_flat
from benchmark.modalities.camera.scenes.spec import CableLook, CameraSceneSpec, Crossing
from benchmark.modalities.camera.scenes.texture import PSI_CELLS, TextureGrid, cable_map


@dataclass(frozen=True)
class CrossingHits:
    """Where rays meet a crossing cable, and its surface there.

    Attributes
    ----------
    index : numpy.ndarray
        Flat indices of the rays (pixels) that meet it ahead of the camera.
    t : numpy.ndarray
        Their depth along the optical axis.
    facing : numpy.ndarray
        Cosine of the angle between its normal and the way back to the
        camera (where the lamp is), at least 0.
    albedo : numpy.ndarray
        Its surface map there.
    normal : numpy.ndarray
        Its outward unit normal there, shape ``(3, n)``.
    """

    index: np.ndarray
    t: np.ndarray
    facing: np.ndarray
    albedo: np.ndarray
    normal: np.ndarray

    def where(self, mask: np.ndarray) -> CrossingHits:
        """The hits of the rays ``mask`` selects."""
        return CrossingHits(self.index[mask], self.t[mask], self.facing[mask], self.albedo[mask], self.normal[:, mask])


@dataclass(frozen=True)
class CrossingCable:
    """A crossing cable as the renderer needs it: its axis, radius, look and surface map.

    Attributes
    ----------
    origin : numpy.ndarray
        ``A``, the point of its axis over the followed cable's axis.
    direction : numpy.ndarray
        ``u``, the unit vector along it.
    radius : float
        ``r_c``, in m.
    look : CableLook
        Its surface, for the highlight.
    surface : numpy.ndarray
        Its albedo, shape ``(nz, PSI_CELLS)``, rows ``cell`` apart along it
        (the map wraps).
    cell : float
        Row spacing of ``surface``, m.
    """

    origin: np.ndarray
    direction: np.ndarray
    radius: float
    look: CableLook
    surface: np.ndarray
    cell: float

    @classmethod
    def build(
        cls, crossing: Crossing, spec: CameraSceneSpec, grid: TextureGrid, rng: np.random.Generator
    ) -> CrossingCable:
        """The crossing ``crossing`` of the scene ``spec``, its surface map drawn from ``rng`` on the rows of ``grid``.

        Parameters
        ----------
        crossing : Crossing
            Where it lies and how it looks.
        spec : CameraSceneSpec
            The scene: the followed pipe's radius and look.
        grid : TextureGrid
            The seabed's grid; the map takes its number of rows and spacing.
        rng : numpy.random.Generator
            Source of its surface texture.
        """
        radius = spec.radius if crossing.diameter_m is None else crossing.diameter_m / 2.0
        look = spec.cable if crossing.look is None else crossing.look
        angle = math.radians(crossing.angle_deg)
        return cls(
            origin=np.array((0.0, radius - spec.radius, crossing.at_m)),
            direction=np.array((math.sin(angle), 0.0, math.cos(angle))),
            radius=radius,
            look=look,
            surface=cable_map(look, grid.nz, grid.cell, radius, rng),
            cell=grid.cell,
        )

    @property
    def side(self) -> np.ndarray:
        """``e``: the horizontal unit vector across it, ``+X`` for a cable along ``Z``."""
        ux, _, uz = self.direction
        return np.array((uz, 0.0, -ux))

    def hits(self, pose: CameraPose, rays: np.ndarray, norm2: np.ndarray) -> CrossingHits:
        """Where the rays ``C + t D`` from the pose's centre meet it (module docstring).

        Parameters
        ----------
        pose : CameraPose
            The camera, in the pipe frame.
        rays : numpy.ndarray
            World directions ``D``, shape ``(3, n)``, scaled so that ``t``
            is the depth along the optical axis.
        norm2 : numpy.ndarray
            ``|D|^2`` of each, shape ``(n,)``.

        Returns
        -------
        CrossingHits
            The rays that meet it ahead of the camera and its surface there.

        References
        ----------
        seeds/004, section II: the pinhole camera and the pipe as a cylinder,
        here about an axis across the pipe's.
        """
        f32 = np.float32
        ux, _, uz = (float(c) for c in self.direction)
        w = np.array((pose.cx, pose.cy, pose.cz)) - self.origin
        along_camera = float(w @ self.direction)
        wx, wy, wz = w - along_camera * self.direction
        dx, dy, dz = rays
        along = dx * f32(ux) + dz * f32(uz)
        qa = norm2 - along * along
        qb = dx * f32(wx) + dy * f32(wy) + dz * f32(wz)
        disc = qb * qb - qa * f32(wx * wx + wy * wy + wz * wz - self.radius**2)
        index = np.flatnonzero((disc > 0) & (qb < f32(-1e-9)))
        if index.size == 0:
            empty = np.zeros(0, dtype=np.float32)
            return CrossingHits(index, empty, empty, empty, np.zeros((3, 0), dtype=np.float32))
        hx, hy, hz, h_along, h_norm2 = dx[index], dy[index], dz[index], along[index], norm2[index]
        t = (-qb[index] - np.sqrt(disc[index])) / qa[index]
        s = f32(along_camera) + t * h_along
        inverse_radius = f32(1.0 / self.radius)
        # Normal: the part of P - A = w + t D perpendicular to u, over r_c.
        px = (f32(w[0]) + t * hx - s * f32(ux)) * inverse_radius
        py = (f32(w[1]) + t * hy) * inverse_radius
        pz = (f32(w[2]) + t * hz - s * f32(uz)) * inverse_radius
        facing = np.maximum(-(px * hx + py * hy + pz * hz) / np.sqrt(h_norm2), f32(0.0))
        ex, _, ez = (float(c) for c in self.side)
        psi = np.arctan2(px * f32(ex) + pz * f32(ez), py)
        col = psi * f32(PSI_CELLS / (2 * math.pi)) + f32(PSI_CELLS / 2)
        row = np.mod(s / f32(self.cell), f32(self.surface.shape[0])).astype(np.float32)
        albedo = remap_flat(self.surface, col.astype(np.float32), row)
        return CrossingHits(index, t, facing.astype(np.float32), albedo, np.stack((px, py, pz)))


def crossing_axis_line(cable: CrossingCable, pose: CameraPose, focal_px: float, size: ImageSize) -> np.ndarray:
    """The image of the crossing's axis as a homogeneous pixel line ``(a, b, c)``, ``a u + b v + c = 0``.

    References
    ----------
    seeds/004, eq. (1) applied to homogeneous points
    (:func:`~benchmark.modalities.camera.scenes.projection.homogeneous_line`).
    """
    return homogeneous_line(projection_matrix(pose, focal_px, size), cable.origin, cable.direction)
