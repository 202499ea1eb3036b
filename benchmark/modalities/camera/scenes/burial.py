"""Sand over the pipe: the burial profile and the visible share of the cable.

Seeds/004 (Fig. 14, Table IV) shows a pipeline "partially or totally
covered by sand" for several consecutive frames, where a tracker has to
coast on its motion model.  Here sand is a level along the pipe: at each
``Z`` the sand surface over the pipe is at height ``Y = L(Z)``, between the
seabed (``Y = -r``, nothing hidden) and above the top of the pipe
(``Y > r``, all hidden).  A pipe point below ``L(Z)`` shows sand instead.

The ground truth reports how much of the cable a tracker could see: the
*visible fraction* of a frame is the share of the in-image cable length not
hidden by sand.  Each cross-section counts with the share of the pipe's
width, seen from straight above, that the sand leaves uncovered (1 while
the sand is below the axis, ``sqrt(1 - (L/r)^2)`` while it rises from the
axis to the top, 0 above), and cross-sections are weighted by their length
in the image, sampled uniformly along the image of the pipe's top line.
"""

from __future__ import annotations

import math
from collections.abc import Sequence as SequenceOf

import numpy as np

from benchmark.modalities.camera.geometry import Line
from benchmark.modalities.camera.model import CameraPose
from benchmark.modalities.camera.scenes.projection import ImageSize, homogeneous_line, pose_axes, projection_matrix
from benchmark.modalities.camera.scenes.silhouette import pixel_line_to_model
from benchmark.modalities.camera.scenes.spec import Burial
from benchmark.scenes.noise import smoothed_noise


def _ramp(z: np.ndarray, lo: float, hi: float, width: float) -> np.ndarray:
    if width <= 0:
        return ((z >= lo) & (z <= hi)).astype(float)
    rise = np.clip((z - lo) / width + 1.0, 0.0, 1.0)
    fall = np.clip((hi - z) / width + 1.0, 0.0, 1.0)
    return 0.5 - 0.5 * np.cos(math.pi * np.minimum(rise, fall))


def sand_level(
    burials: SequenceOf[Burial], radius: float, z: np.ndarray, rng: np.random.Generator
) -> np.ndarray:
    """Height ``L(Z)`` of the sand surface over the pipe.

    Parameters
    ----------
    burials : sequence of Burial
        Stretches of sand; where they overlap the higher level wins.
    radius : float
        Pipe radius ``r`` in m.
    z : numpy.ndarray
        Evenly spaced positions along the pipe, in m.
    rng : numpy.random.Generator
        Source of the sand line's irregularity.

    Returns
    -------
    numpy.ndarray
        ``float32`` heights ``Y``; ``-r`` where there is no sand.

    References
    ----------
    seeds/004, section VI-A and Fig. 14 (pipeline partly or totally covered
    by sand).
    """
    z = np.asarray(z, dtype=float)
    cell = float(z[1] - z[0]) if len(z) > 1 else 1.0
    level = np.zeros_like(z)
    for burial, stream in zip(burials, rng.spawn(len(burials))):
        rough = burial.roughness * smoothed_noise(stream, len(z), 0.05 / cell)
        weight = _ramp(z, burial.z_m[0], burial.z_m[1], burial.ramp_m)
        level = np.maximum(level, weight * (burial.level + rough))
    return (-radius + 2.0 * radius * level).astype(np.float32)


def slice_visibility(level: np.ndarray, radius: float) -> np.ndarray:
    """Share of the pipe's width, seen from above, left uncovered by sand at height ``level``."""
    s = np.asarray(level, dtype=float) / radius
    return np.where(s <= 0.0, 1.0, np.sqrt(np.clip(1.0 - s * s, 0.0, 1.0)))


def image_chord(line: Line, size: ImageSize) -> tuple[tuple[float, float], tuple[float, float]] | None:
    """End points (model coordinates) of a line's chord through the image, or None if it misses.

    The image is the rectangle spanned by the pixel centres (conventions.md
    section 3).
    """
    half_w, half_h = (size[0] - 1) / 2.0, (size[1] - 1) / 2.0
    lo, hi = -math.inf, math.inf
    for p, dp, limit in ((line.x0, line.dx, half_w), (line.y0, line.dy, half_h)):
        if abs(dp) < 1e-15:
            if abs(p) > limit:
                return None
            continue
        a, b = (-limit - p) / dp, (limit - p) / dp
        lo, hi = max(lo, min(a, b)), min(hi, max(a, b))
    if not lo < hi:
        return None
    return (line.x0 + lo * line.dx, line.y0 + lo * line.dy), (line.x0 + hi * line.dx, line.y0 + hi * line.dy)


def visible_fraction(
    pose: CameraPose,
    radius: float,
    focal_px: float,
    size: ImageSize,
    z: np.ndarray,
    level: np.ndarray,
    samples: int = 96,
) -> float:
    """Share of the in-image cable length not hidden by sand.

    Parameters
    ----------
    pose : CameraPose
        Camera pose.
    radius, focal_px : float
        Pipe radius (m) and ``f / dx`` (px).
    size : tuple of int
        Image ``(W, H)``.
    z, level : numpy.ndarray
        The sand profile from :func:`sand_level` and where it is sampled.
    samples : int
        Points sampled along the cable's image.

    Returns
    -------
    float
        In ``[0, 1]``; 0 when the cable is not in the image at all.

    References
    ----------
    seeds/004, Fig. 14 and Table IV (frames without measurements while the
    pipe is under sand).
    """
    matrix = projection_matrix(pose, focal_px, size)
    top = pixel_line_to_model(homogeneous_line(matrix, (0.0, radius, pose.cz), (0.0, 0.0, 1.0)), size)
    chord = image_chord(top, size)
    if chord is None:
        return 0.0
    if float(np.max(level, initial=-radius)) <= 0.0:
        return 1.0
    (x_a, y_a), (x_b, y_b) = chord
    s = (np.arange(samples) + 0.5) / samples
    qx = (x_a + s * (x_b - x_a)) / focal_px
    qy = -(y_a + s * (y_b - y_a)) / focal_px
    inverse = np.linalg.inv(pose_axes(pose))
    rays = inverse @ np.stack((qx, qy, np.ones_like(qx)))
    dx, dy, dz = rays
    # Ray parameter of the point nearest the top line X = 0, Y = r.
    t = -(pose.cx * dx + (pose.cy - radius) * dy) / np.maximum(dx * dx + dy * dy, 1e-12)
    ahead = t > 0
    if not np.any(ahead):
        return 0.0
    along = pose.cz + t[ahead] * dz[ahead]
    seen = slice_visibility(np.interp(along, z, level), radius)
    return float(np.clip(np.mean(seen), 0.0, 1.0))
