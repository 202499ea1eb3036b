"""Each fitted border moved outwards to the foot of its edge, on the frame itself.

A cable or pipe is a cylinder: under lamps or daylight its shading falls
off towards its silhouette, so that its grey levels ramp from the seabed's
to the cable's over several pixels, and the silhouette, where the cable's
border lies, is the outer end of that ramp.  The straight pieces the
borders are fitted to (:mod:`trackbench_texture.borders`) are edges, at
the ramp's steepest point: measured on the camera splits, a bright pipe's
lit border lay 5-7 px inside the true one at 640 x 480.  The thesis leaves
the step from the texture classes to the cable's position open (seeds/000,
section 2.2, Comments); this is part of this implementation's reading.

On every pixel step along a border, the grey-level profile across it is
read on the frame's (lightly smoothed) image.  The ramp's steepest point is
the largest slope within ``reach_px`` of the fitted border; its foot is
where, walking outwards (away from the other border), the slope first falls
below ``foot_share`` of that largest slope, to a fraction of a pixel by
linear interpolation.  The border is the robust (Huber) straight-line fit
to the feet of the stronger half of the steps.
"""

from __future__ import annotations

import math

import cv2
import numpy as np

from benchmark.modalities.camera.geometry import Line, cable_borders, cable_from_borders, model_to_pixel, pixel_to_model
from benchmark.modalities.camera.model import CableState

MIN_POINTS = 8
"""Fewest feet a border is moved on; with fewer it stays where it was fitted."""


def _ramp_feet(profile: np.ndarray, centre: int, reach: int, foot_share: float) -> tuple[np.ndarray, np.ndarray]:
    """Per row of ``profile`` (grey levels at offsets ``-centre..``, outwards positive): the foot and the slope.

    Returns
    -------
    feet : numpy.ndarray
        Offset of each row's foot from the fitted border, px (NaN where the
        slope never falls below the share within the profile).
    slopes : numpy.ndarray
        Each row's largest slope magnitude within ``reach`` of the fitted border.
    """
    slope = np.abs(np.diff(profile, axis=1))
    # Slope k lies between offsets k and k + 1, at offset k + 0.5 - centre.
    window = slope[:, centre - reach : centre + reach]
    peak = np.argmax(window, axis=1) + centre - reach
    rows = np.arange(len(profile))
    strongest = slope[rows, peak]
    below = slope < (foot_share * strongest)[:, None]
    beyond = np.arange(slope.shape[1])[None, :] > peak[:, None]
    candidates = below & beyond
    found = candidates.any(axis=1)
    first = np.argmax(candidates, axis=1)
    before = slope[rows, np.maximum(first - 1, 0)]
    after = slope[rows, first]
    limit = foot_share * strongest
    fraction = np.clip((before - limit) / np.maximum(before - after, 1e-6), 0.0, 1.0)
    feet = (first - 1 + 0.5) + fraction - centre
    return np.where(found, feet, np.nan), strongest


def _moved_border(
    grey: np.ndarray, border: Line, outwards: tuple[float, float], reach: int, foot_share: float
) -> Line:
    """``border`` moved onto the feet of its ramp, ``outwards`` the pixel unit vector away from the cable."""
    height, width = grey.shape
    size = (width, height)
    u0, v0 = model_to_pixel(border.x0, border.y0, size)
    du, dv = border.dx, -border.dy
    nu, nv = outwards
    steps = np.arange(-math.hypot(width, height), math.hypot(width, height) + 1.0, 1.0, dtype=np.float32)
    cu, cv = u0 + steps * du, v0 + steps * dv
    inside = (cu >= 0) & (cu <= width - 1) & (cv >= 0) & (cv <= height - 1)
    cu, cv = cu[inside], cv[inside]
    if len(cu) < MIN_POINTS:
        return border
    centre = 2 * reach
    offsets = np.arange(-centre, 4 * reach + 1, dtype=np.float32)
    map_u = (cu[:, None] + offsets[None, :] * nu).astype(np.float32)
    map_v = (cv[:, None] + offsets[None, :] * nv).astype(np.float32)
    profile = cv2.remap(grey, map_u, map_v, cv2.INTER_LINEAR, borderMode=cv2.BORDER_REPLICATE)
    feet, strength = _ramp_feet(profile, centre, reach, foot_share)
    keep = np.isfinite(feet) & (strength >= np.median(strength))
    if keep.sum() < MIN_POINTS:
        return border
    points = np.column_stack([cu[keep] + feet[keep] * nu, cv[keep] + feet[keep] * nv]).astype(np.float32)
    pu, pv, qu, qv = cv2.fitLine(points, cv2.DIST_HUBER, 0, 0.01, 0.01).ravel()
    return Line.through(pixel_to_model(qu, qv, size), pixel_to_model(qu + pu, qv + pv, size))


def border_feet(image: np.ndarray, state: CableState, reach_px: float, sigma_px: float, foot_share: float) -> CableState:
    """The cable state whose borders are ``state``'s moved outwards to the feet of their edges.

    Parameters
    ----------
    image : numpy.ndarray
        The frame's ``uint8`` grey image, ``(H, W)``.
    state : CableState
        A known cable state in the frame's pixels.
    reach_px : float
        How far on either side of a fitted border its steepest point is
        looked for, px; the foot is looked for up to three times as far outwards.
    sigma_px : float
        Standard deviation of the Gaussian smoothing before the profiles are read, px (0: none).
    foot_share : float
        Share of the steepest slope below which the ramp has ended.

    Returns
    -------
    CableState
        ``state`` itself when the moved borders cross or coincide.

    References
    ----------
    seeds/000, section 2.2 (Comments: the cable position from the texture classes is left open).
    """
    grey = image.astype(np.float32)
    if sigma_px > 0:
        grey = cv2.GaussianBlur(grey, (0, 0), sigma_px, borderType=cv2.BORDER_REFLECT)
    size = (image.shape[1], image.shape[0])
    borders = cable_borders(state)
    middle = [model_to_pixel(line.x0, line.y0, size) for line in borders]
    reach = max(1, math.ceil(reach_px))
    moved = []
    for k, border in enumerate(borders):
        nu, nv = border.dy, border.dx
        other = middle[1 - k]
        if (middle[k][0] - other[0]) * nu + (middle[k][1] - other[1]) * nv < 0:
            nu, nv = -nu, -nv
        moved.append(_moved_border(grey, border, (nu, nv), reach, foot_share))
    try:
        return cable_from_borders(*moved)
    except ValueError:
        return state
