"""The second border read off the grey levels beside the first, where the cable class does not reach it.

The cable class marks a band about ``window_px`` wide around the edges the
texture descriptors see (:mod:`trackbench_texture.borders`).  On a wide
pipe whose one side is a sharp step and the other a soft ramp or a shadow
(concrete pipes, bright pipes on mud, large frames), only the sharp side
gets the cable class and straight pieces; the other border lies outside
the region, and the straight pieces of the region cannot pair.  The
thesis leaves the step from the classified image to the cable's position
open (seeds/000, section 2.2, Comments); this is part of this
implementation's reading.

Once the first border is found, the second is the straight line beside it
along which the grey level changes most consistently in the opposite
sense: crossing a cable, the grey level steps one way at one border and
back at the other.  For every candidate line at a plausible width from the
first and within twice the largest skew of it, the grey-level difference
across it is averaged over every scan line it crosses (a projection of
the gradient, so that a long weak edge adds up and the seabed's texture
averages out); the candidate with the largest average of the opposite
sign wins if that average is at least ``min_strength`` of the first
border's own.  A cylinder's shading and the growth on it make steps inside
the cable as well; a border is its silhouette, the outermost step, so of
the candidates whose step comes within ``widest_share`` of the strongest
the one farthest from the first border is taken.  No threshold in grey levels is involved: only the ratio of
the two borders' contrasts.
"""

from __future__ import annotations

import math

import cv2
import numpy as np

MIN_STRENGTH = 0.3
"""Smallest ratio of the second border's averaged grey-level step to the first's.

Out of fold on camera-train's world sequences / on camera-dev (the
measurements of :mod:`trackbench_texture.params`), strength 0.1 / 0.2 /
0.3 / 0.5 / 0.7 (the strongest candidate): 63.1 (11.2) / 63.1 (11.2) /
63.0 (8.3) / 61.4 (5.9) / 60.7 (5.4) and 79.4 (9.4) / 79.4 (8.2) / 78.6
(7.8) / 75.8 (6.0) / 74.8 (4.9) % correct (false): 0.3 keeps most of the
gain at fewer false reports.  A module constant rather than a tracker
parameter, so that the parameters of ``texture-paper``, which never reads
a border off the grey levels, stay what they were (its model's training
key hashes them)."""

WIDEST_SHARE = 0.8
"""Of the candidates whose step comes within this share of the strongest's, the farthest from the first
border is the partner (1: the strongest).

A cylinder's shading and the growth on it step inside the cable too
(dev/d13, d06: both borders found on one side, 8-10 px apart).  1 / 0.9 /
0.8 / 0.6 / 0.4, train world / dev: 63.0 / 63.9 / 64.3 / 63.1 / 62.4 and
78.6 / 79.3 / 79.5 / 79.4 / 78.9 % correct; a constant for the reason
:data:`MIN_STRENGTH` is."""

SLOPE_STEPS = 9
"""Relative slopes tried between the first border and its partner, spread over twice the largest skew."""

OWN_REACH_PX = 2
"""How far either side of the first border its own grey-level step is looked for, px."""


def _mean_steps(scan_grey: np.ndarray, slope: float, intercept: float, offsets: np.ndarray, min_rows: float) -> np.ndarray:
    """Per offset, the grey-level difference across the line ``across = slope * along + intercept + offset``,
    averaged over the scan lines where the line lies inside the image (NaN where it lies on fewer than ``min_rows``).

    The difference at offset ``d`` is the grey level at ``d + 0.5`` minus the one at ``d - 0.5``.
    """
    height, width = scan_grey.shape
    along = np.arange(height, dtype=np.float32)
    base = slope * along + intercept
    positions = base[:, None] + np.concatenate([offsets - 0.5, offsets[-1:] + 0.5])[None, :]
    profile = cv2.remap(
        scan_grey,
        positions.astype(np.float32),
        np.broadcast_to(along[:, None], positions.shape).astype(np.float32),
        cv2.INTER_LINEAR,
        borderMode=cv2.BORDER_REPLICATE,
    )
    inside = (positions >= 0) & (positions <= width - 1)
    usable = inside[:, :-1] & inside[:, 1:]
    steps = np.where(usable, np.diff(profile, axis=1), 0.0)
    count = usable.sum(axis=0)
    means = steps.sum(axis=0) / np.maximum(count, 1)
    return np.where(count >= max(min_rows, 2), means, np.nan)


def partner_line(
    scan_grey: np.ndarray,
    slope: float,
    intercept: float,
    *,
    min_width_px: float,
    max_width_px: float,
    max_skew: float,
    min_rows: float,
    min_strength: float = MIN_STRENGTH,
    widest_share: float = WIDEST_SHARE,
) -> tuple[float, float] | None:
    """The second border of the cable whose first border is ``across = slope * along + intercept``, or None.

    Parameters
    ----------
    scan_grey : numpy.ndarray
        ``float32`` grey levels (lightly smoothed) indexed ``[along, across]``.
    slope, intercept : float
        The first border in scan coordinates.
    min_width_px, max_width_px : float
        The plausible widths, measured perpendicular to the first border at the middle scan line, px.
    max_skew : float
        Largest skew of a border, rad: the partner's direction may differ by twice as much.
    min_rows : float
        Fewest scan lines the partner must cross inside the image.
    min_strength : float
        Smallest ratio of the partner's averaged grey-level step to the first border's.
    widest_share : float
        Of the candidates whose step is at least this share of the strongest's, the one farthest from
        the first border wins (1: the strongest).

    Returns
    -------
    (float, float) or None
        The partner's ``(slope, intercept)`` in scan coordinates; None when
        the first border shows no step, or no candidate of the opposite
        sign reaches ``min_strength`` of it.

    References
    ----------
    seeds/000, section 2.2 (Comments: the cable position from the texture classes is left open).
    """
    height, _ = scan_grey.shape
    middle = 0.5 * (height - 1)
    own_offsets = np.arange(-OWN_REACH_PX, OWN_REACH_PX + 1, dtype=np.float32)
    own = _mean_steps(scan_grey, slope, intercept, own_offsets, min_rows)
    if not np.isfinite(own).any():
        return None
    own_step = own[np.nanargmax(np.abs(own))]
    if own_step == 0:
        return None
    stretch = math.hypot(1.0, slope)
    reach = math.ceil(max_width_px * stretch) + 1
    offsets = np.arange(-reach, reach + 1, dtype=np.float32)
    gap = np.abs(offsets) / stretch
    plausible = (gap >= min_width_px) & (gap <= max_width_px)
    least = min_strength * abs(own_step)
    angle = math.atan(slope)
    candidates = []
    for turn in np.linspace(-2.0 * max_skew, 2.0 * max_skew, SLOPE_STEPS):
        turned = math.tan(angle + turn)
        turned_intercept = slope * middle + intercept - turned * middle
        means = _mean_steps(scan_grey, turned, turned_intercept, offsets, min_rows)
        opposite = -np.sign(own_step) * means
        opposite[~plausible | ~np.isfinite(opposite)] = -np.inf
        candidates.append((opposite, turned, turned_intercept))
    peak = max(float(np.max(opposite)) for opposite, _, _ in candidates)
    if peak < least:
        return None
    floor = max(least, widest_share * peak)
    chosen, widest = None, -1.0
    for opposite, turned, turned_intercept in candidates:
        strong = np.flatnonzero(opposite >= floor)
        if len(strong) and np.abs(offsets[strong]).max() > widest:
            k = strong[np.argmax(np.abs(offsets[strong]))]
            widest, chosen = float(abs(offsets[k])), (turned, turned_intercept + float(offsets[k]))
    return chosen
