"""From the edges the filter tracks to the cable's silhouette.

Eq. (4.11) weighs a pair of borders by the grey-level change a derivative of
Gaussian finds across them, and the filter settles where that change is
steepest.  On a flat band of paint, or a dark cable on bright sand, the
steepest change is the cable's outline.  On a lit cylinder brighter than
the seabed it is not: a lamp near the camera lights the pipe's middle and
grazes its flanks, so from the outline inwards the grey level climbs a ramp
of shading (seeds/000, section 6.1: "the cable's center is mostly
brighter"), and the flank facing away from a side lamp lies in the pipe's
own shadow, a thin rim darker than the seabed beside it.  The steepest
change of the cable's sign is then up the ramp, inside the outline, and the
filter reports the cable too narrow: by a median 8-12 px on the 640 x 480
bright and painted cables of camera-dev (d01, d02, d09) and by 15-45 px on
the concrete pipes of camera-train (w01, w08, w11), where the detection
rule allows each border 5 px.

:class:`Silhouette` moves each border of the reported state from the edge
to the outline.  It reads the border count of eq. (4.11) with the border
moved by ``o`` px along its normal (``o > 0`` towards the centreline), signed
so that the cable's own polarity is positive, ``g(o)``:

1. the *edge* is the peak of ``g`` within the filter's half size ``r`` of
   the reported border;
2. outwards from it, the *foot* is where ``g`` has fallen to ``fraction`` of
   the peak, and the outline lies the filter's ``sigma`` inwards of it: on
   an ideal blurred step the half-height point lies ``1.18 sigma_total``
   out, so a sharp border stays where it was to within a pixel, while on a
   ramp the foot is where the ramp leaves the seabed;
3. a *rim*: when within ``rim_reach_px`` beyond the foot the count of the
   opposite sign (the step from the seabed down into the shadowed rim)
   reaches ``rim_ratio`` of the peak, the outline is that step.

A border whose count does not fall to the level within half the cable's
width keeps its position.  A cable darker than the seabed is left alone:
its flanks are darker still, so its steepest edge already is its outline
(the dark-on-sand draws of camera-train and camera-dev: 0 px), while
moving it out, on the dark cables of the clutter family (S1), ran onto
algae and cost 2.3 points there (:mod:`trackbench_condensation.params`).
Only the reported state moves: the particles keep tracking the steepest
edges, which eq. (4.11) finds reliably, and the width prior
(:mod:`trackbench_condensation.width`) follows the tracked width.

Each border is a straight line, so its counts at all the offsets are the
line scores of :func:`~trackbench_condensation.measure.line_scores` at the
border's own normal ``n(alpha -+ beta)``: one compiled call per border.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from benchmark.lazy import lazy_module
from trackbench_condensation.kernel import dog_sigma
from trackbench_condensation.observation import as_grey_image

# The numba kernels load on the first frame, so that listing the trackers does not import numba.
measure = lazy_module("trackbench_condensation.measure")


@dataclass(frozen=True)
class Silhouette:
    """Moves the borders of a state from the steepest edges out to the cable's outline.

    Parameters
    ----------
    taps : numpy.ndarray
        Filter taps of the observation model (odd, ``2 r + 1``).
    spacing : float
        Sample point distance along a border, px.
    fraction : float
        Share of the edge's peak count at which the outline is placed, in ``(0, 1)``.
    rim_ratio : float
        Share of the peak an opposite step must reach to be taken for a
        shadowed rim's outline; 0 ignores rims.
    rim_reach_px : float
        How far beyond the foot of the ramp a rim's outline may lie, px.

    References
    ----------
    seeds/000, section 4.5, eqs. (4.10)-(4.11); section 6.1 (appearance of
    a cylindrical cable).
    """

    taps: np.ndarray
    spacing: float
    fraction: float = 0.5
    rim_ratio: float = 0.35
    rim_reach_px: float = 4.0

    def __post_init__(self) -> None:
        if not 0.0 < self.fraction < 1.0:
            raise ValueError(f"silhouette fraction must be in (0, 1), got {self.fraction}")
        if not self.rim_ratio >= 0.0:
            raise ValueError(f"rim ratio must be >= 0, got {self.rim_ratio}")
        if not self.rim_reach_px >= 0.0:
            raise ValueError(f"rim reach must be >= 0 px, got {self.rim_reach_px}")

    @property
    def radius(self) -> int:
        """Half size ``r`` of the filter window, px."""
        return (len(self.taps) - 1) // 2

    def outline(self, state: np.ndarray, image: np.ndarray) -> np.ndarray:
        """The state ``(d, alpha, w, beta)`` with both borders moved to the outline.

        Parameters
        ----------
        state : numpy.ndarray
            ``(4,)`` reported state, px and rad.
        image : numpy.ndarray
            The frame's grey image.

        Returns
        -------
        numpy.ndarray
            ``(4,)``: ``alpha`` and ``beta`` unchanged; ``d`` and ``w`` with
            each border at its outline (or where it was) and then ``w >= 1``;
            the state itself for a cable darker than the seabed or ``w <= 0``.

        References
        ----------
        seeds/000, eq. (4.11).
        """
        d, alpha, w, beta = np.asarray(state, dtype=float)[:4].tolist()
        if not w > 0:
            return np.asarray(state[:4], dtype=float).copy()
        image = as_grey_image(image)
        # Each border is a straight line with its own normal n(alpha -+ beta), at the
        # distance (d -+ w/2) cos(beta) from the centre; its count is that line's score.
        cos_beta = np.cos(beta)
        # Eq. (4.11)'s polarity: a bright cable has c_l < 0 < c_r.
        left, right = measure.border_line_scores(
            image, self.taps, self.spacing, alpha - beta, alpha + beta, (d - 0.5 * w) * cos_beta, (d + 0.5 * w) * cos_beta
        )
        if not right - left > 0:
            return np.array([d, alpha, w, beta])
        radius = self.radius
        normals = (np.array([alpha - beta]), np.array([alpha + beta]))

        def counts(side: int, offsets: np.ndarray) -> np.ndarray:
            # side -1: the left border, moved inwards (+n) by the offsets; +1: the right one (-n).
            lines = (d + side * (0.5 * w - offsets)) * cos_beta
            return measure.line_scores(image, self.taps, self.spacing, normals[(side + 1) // 2], lines)[0]

        offsets = np.arange(-(int(np.ceil(0.5 * w)) + radius), radius + 1, dtype=float)
        shift_left = self._shift(offsets, -counts(-1, offsets))
        shift_right = self._shift(offsets, counts(1, offsets))
        width = max(w - shift_left - shift_right, 1.0)
        return np.array([d + 0.5 * (shift_left - shift_right), alpha, width, beta])

    def _shift(self, offsets: np.ndarray, curve: np.ndarray) -> float:
        """Inward shift (negative: outward) of one border from its count curve ``g(o)``."""
        radius = self.radius
        near = np.flatnonzero(np.abs(offsets) <= radius)
        peak_at = int(near[np.argmax(curve[near])])
        peak = float(curve[peak_at])
        if not peak > 0:
            return 0.0
        level = self.fraction * peak
        below = np.flatnonzero(curve[:peak_at] <= level)
        if len(below) == 0:
            return 0.0
        foot_at = int(below[-1])
        # Interpolate the crossing between foot_at (below) and foot_at + 1 (above).
        rise = curve[foot_at + 1] - curve[foot_at]
        crossing = offsets[foot_at] + ((level - curve[foot_at]) / rise if rise > 0 else 0.0)
        shift = crossing + dog_sigma(len(self.taps))
        if self.rim_ratio > 0:
            window = np.flatnonzero((offsets >= crossing - self.rim_reach_px) & (offsets <= crossing))
            if len(window):
                rim_at = int(window[np.argmax(-curve[window])])
                if -curve[rim_at] >= self.rim_ratio * peak:
                    shift = float(offsets[rim_at])
        return float(shift)
