"""Image geometry of the cable model and the line-pair detection rule.

Two coordinate systems meet here (``conventions.md`` section 1):

* pixel coordinates ``(u, v)``: OpenCV's, column right, row down, origin at
  the centre of the top-left pixel;
* model coordinates ``(x, y)``: origin at the image centre, ``x`` right,
  ``y`` up, as in the thesis (seeds/000, section 4.2) and seeds/004 eq. (4).

A :class:`Line` lives in model coordinates.  A cable state
``(d, alpha, w, beta)`` maps to its two border lines with
:func:`cable_borders` and back with :func:`cable_from_borders`.  The
detection rule of seeds/004, section VI-C compares two line pairs through
their chord mid-points (:func:`chord_midpoint`) and orientations
(:func:`score_line_pair`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from benchmark.modalities.camera.model import CableState
from benchmark.model import Outcome

ImageSize = tuple[int, int]
"""``(W, H)`` in px."""


def pixel_to_model(u: float, v: float, size: ImageSize) -> tuple[float, float]:
    """Pixel ``(u, v)`` to model ``(x, y)``: ``x = u - (W-1)/2``, ``y = (H-1)/2 - v``."""
    width, height = size
    return u - (width - 1) / 2.0, (height - 1) / 2.0 - v


def model_to_pixel(x: float, y: float, size: ImageSize) -> tuple[float, float]:
    """Model ``(x, y)`` to pixel ``(u, v)``; the inverse of :func:`pixel_to_model`."""
    width, height = size
    return x + (width - 1) / 2.0, (height - 1) / 2.0 - y


@dataclass(frozen=True, slots=True)
class Line:
    """An infinite line ``{(x0, y0) + s (dx, dy)}`` in model coordinates.

    The direction is stored as a unit vector; its sign carries no meaning.
    """

    x0: float
    y0: float
    dx: float
    dy: float

    def __post_init__(self) -> None:
        norm = math.hypot(self.dx, self.dy)
        if not (math.isfinite(norm) and norm > 0 and math.isfinite(self.x0) and math.isfinite(self.y0)):
            raise ValueError(f"not a line: point ({self.x0}, {self.y0}), direction ({self.dx}, {self.dy})")
        object.__setattr__(self, "dx", self.dx / norm)
        object.__setattr__(self, "dy", self.dy / norm)

    @classmethod
    def through(cls, p: tuple[float, float], q: tuple[float, float]) -> Line:
        """The line through two distinct model points."""
        return cls(p[0], p[1], q[0] - p[0], q[1] - p[1])

    @classmethod
    def from_pixels(cls, p: tuple[float, float], q: tuple[float, float], size: ImageSize) -> Line:
        """The line through two distinct pixel points ``(u, v)``."""
        return cls.through(pixel_to_model(*p, size), pixel_to_model(*q, size))

    @classmethod
    def from_normal(cls, rho: float, phi: float) -> Line:
        """The line ``x cos(phi) + y sin(phi) = rho`` in model coordinates."""
        c, s = math.cos(phi), math.sin(phi)
        return cls(rho * c, rho * s, -s, c)

    @property
    def orientation(self) -> float:
        """Angle of the direction in ``[0, pi)``, counter-clockwise from ``+x``."""
        return math.atan2(self.dy, self.dx) % math.pi

    def nearest_point_to_origin(self) -> tuple[float, float]:
        """The foot of the perpendicular from the image centre."""
        s = -(self.x0 * self.dx + self.y0 * self.dy)
        return self.x0 + s * self.dx, self.y0 + s * self.dy


def _rotate(x: float, y: float, angle: float) -> tuple[float, float]:
    c, s = math.cos(angle), math.sin(angle)
    return c * x - s * y, s * x + c * y


def cable_borders(state: CableState) -> tuple[Line, Line]:
    """The left and right border lines of a cable state.

    The centreline is ``{p : p . n = d}`` with ``n = (cos alpha, sin alpha)``
    and direction ``t = (-sin alpha, cos alpha)``.  The left border passes
    through ``c0 - (w/2) n`` with direction ``R(-beta) t``, the right one
    through ``c0 + (w/2) n`` with direction ``R(+beta) t``, where
    ``c0 = d n``.

    Parameters
    ----------
    state : CableState
        A known cable state.

    Returns
    -------
    left, right : Line
        The two borders in model coordinates.

    References
    ----------
    seeds/000, section 4.2, Fig. 4.3 and Table 4.1; conventions.md section 1.
    """
    if not state.is_known:
        raise ValueError(f"cable state is not fully known: {state}")
    nx, ny = math.cos(state.alpha), math.sin(state.alpha)
    tx, ty = -ny, nx
    cx, cy = state.d * nx, state.d * ny
    half = state.w / 2.0
    left = Line(cx - half * nx, cy - half * ny, *_rotate(tx, ty, -state.beta))
    right = Line(cx + half * nx, cy + half * ny, *_rotate(tx, ty, state.beta))
    return left, right


def _normalise_angle(angle: float) -> float:
    """Wrap an angle to ``(-pi, pi]``."""
    wrapped = math.remainder(angle, 2.0 * math.pi)
    return math.pi if wrapped == -math.pi else wrapped


def cable_from_borders(first: Line, second: Line) -> CableState:
    """The cable state whose borders are the two given lines, in either order.

    The centreline is the bisector of the acute angle between the borders
    (of their common direction when they are parallel), so ``|beta| <=
    45 deg``.  Of the two equivalent parameterisations the one with
    ``alpha`` in ``(-pi/2, pi/2]`` is returned; ``beta`` is then positive
    when the borders converge towards the top of the image and negative when
    they diverge.

    Parameters
    ----------
    first, second : Line
        The border lines in model coordinates.

    Returns
    -------
    CableState
        The state with :func:`cable_borders` giving back the same two lines.

    References
    ----------
    conventions.md section 1 (the inverse of its border construction).
    """
    ux, uy = first.dx, first.dy
    vx, vy = second.dx, second.dy
    if ux * vx + uy * vy < 0:
        vx, vy = -vx, -vy
    tx, ty = ux + vx, uy + vy
    norm = math.hypot(tx, ty)
    tx, ty = tx / norm, ty / norm
    # Orient the centreline upwards so that alpha lands in (-pi/2, pi/2].
    if ty < 0 or (ty == 0 and tx > 0):
        tx, ty = -tx, -ty
    alpha = math.atan2(-tx, ty)
    nx, ny = ty, -tx
    half_angle = 0.5 * math.atan2(abs(ux * vy - uy * vx), ux * vx + uy * vy)

    # Each border as m . p = c with its unit normal m turned towards +n; the
    # centreline is where the two signed distances cancel, (m1 + m2) . p = c1 + c2.
    # This avoids the borders' intersection, which is far away for small beta.
    normals = []
    for line in (first, second):
        mx, my = line.dy, -line.dx
        if mx * nx + my * ny < 0:
            mx, my = -mx, -my
        normals.append((mx, my, mx * line.x0 + my * line.y0))
    (m1x, m1y, c1), (m2x, m2y, c2) = normals
    d = (c1 + c2) / math.hypot(m1x + m2x, m1y + m2y)
    c0x, c0y = d * nx, d * ny
    # Offsets along n at which each border crosses the normal through c0, and
    # how they change one unit further along +t.
    crossings = [(c - (mx * c0x + my * c0y)) / (mx * nx + my * ny) for mx, my, c in normals]
    slopes = [-(mx * tx + my * ty) / (mx * nx + my * ny) for mx, my, _ in normals]
    left, right = (0, 1) if crossings[0] <= crossings[1] else (1, 0)
    width = crossings[right] - crossings[left]
    converging_up = slopes[right] - slopes[left] < 0
    beta = half_angle if converging_up else -half_angle
    return CableState(d, alpha, width, beta)


def chord_midpoint(line: Line, size: ImageSize) -> tuple[float, float]:
    """Mid-point of a line's chord through the image, in model coordinates.

    The chord is the part of the line inside the rectangle spanned by the
    pixel centres, ``0 <= u <= W-1`` and ``0 <= v <= H-1``.  A line that
    misses the rectangle gives its point nearest the image centre.

    References
    ----------
    conventions.md section 3; seeds/004, section VI-C.
    """
    half_w, half_h = (size[0] - 1) / 2.0, (size[1] - 1) / 2.0
    s_low, s_high = -math.inf, math.inf
    for p, dp, limit in ((line.x0, line.dx, half_w), (line.y0, line.dy, half_h)):
        if abs(dp) < 1e-15:
            if abs(p) > limit:
                return line.nearest_point_to_origin()
            continue
        a, b = (-limit - p) / dp, (limit - p) / dp
        s_low, s_high = max(s_low, min(a, b)), min(s_high, max(a, b))
    if s_low > s_high:
        return line.nearest_point_to_origin()
    s = 0.5 * (s_low + s_high)
    return line.x0 + s * line.dx, line.y0 + s * line.dy


def orientation_difference(a: Line, b: Line) -> float:
    """Angle between two lines modulo ``pi``, in ``[0, pi/2]`` rad."""
    diff = abs(a.orientation - b.orientation) % math.pi
    return min(diff, math.pi - diff)


@dataclass(frozen=True, slots=True)
class DetectionRule:
    """The line-pair detection rule of seeds/004, section VI-C (Table V).

    Attributes
    ----------
    max_midpoint_px : float
        Largest Euclidean distance between matched chord mid-points.
    max_angle_deg : float
        Largest orientation difference between matched lines.
    """

    max_midpoint_px: float = 5.0
    max_angle_deg: float = 3.0


def match_line_pairs(
    reported: tuple[Line, Line], truth: tuple[Line, Line], size: ImageSize
) -> list[tuple[tuple[Line, Line], tuple[float, float]]]:
    """Match reported lines to ground-truth lines by mid-point distance.

    Returns
    -------
    list of (matched, distances)
        The assignments with the smallest summed mid-point distance: usually
        one, both when they tie.  ``matched`` holds the reported lines
        reordered to pair with ``truth[0]`` and ``truth[1]``; ``distances``
        the mid-point distance of each pair in px.

    References
    ----------
    conventions.md section 3.
    """
    mid_r = [np.array(chord_midpoint(line, size)) for line in reported]
    mid_t = [np.array(chord_midpoint(line, size)) for line in truth]
    candidates = []
    for first, second in ((0, 1), (1, 0)):
        distances = (
            float(np.linalg.norm(mid_r[first] - mid_t[0])),
            float(np.linalg.norm(mid_r[second] - mid_t[1])),
        )
        candidates.append(((reported[first], reported[second]), distances))
    best = min(sum(distances) for _, distances in candidates)
    return [c for c in candidates if sum(c[1]) <= best + 1e-9]


def score_line_pair(
    reported: tuple[Line, Line] | None,
    truth: tuple[Line, Line],
    size: ImageSize,
    rule: DetectionRule = DetectionRule(),
) -> Outcome:
    """Score one frame's reported line pair against the ground-truth pair.

    Parameters
    ----------
    reported : tuple of Line or None
        The tracker's two border lines; None when it reported nothing.
    truth : tuple of Line
        The ground-truth border lines.
    size : tuple of int
        Image ``(W, H)`` in px.
    rule : DetectionRule
        Thresholds; the defaults are those of the paper (5 px, 3 deg).

    Returns
    -------
    Outcome
        ``MISSED`` without a report; ``CORRECT`` when, for each truth line,
        the matched reported line has its chord mid-point closer than
        ``max_midpoint_px`` and its orientation closer than
        ``max_angle_deg``; ``FALSE`` otherwise.  When two assignments tie,
        either may make the pair correct, so the outcome does not depend on
        the order of the lines.

    References
    ----------
    seeds/004, section VI-C and Table V; conventions.md section 3.
    """
    if reported is None:
        return Outcome.MISSED
    max_angle = math.radians(rule.max_angle_deg)
    for matched, distances in match_line_pairs(reported, truth, size):
        if all(
            distance < rule.max_midpoint_px and orientation_difference(line, true_line) < max_angle
            for line, true_line, distance in zip(matched, truth, distances)
        ):
            return Outcome.CORRECT
    return Outcome.FALSE


def state_errors(estimate: CableState, truth: CableState) -> tuple[float, float, float, float]:
    """Errors ``estimate - truth`` of ``(d, alpha, w, beta)``.

    ``alpha`` is compared modulo ``pi`` (a centreline has no direction): when
    the wrapped difference exceeds ``pi/2`` the estimate is read in its
    equivalent form ``(-d, alpha -+ pi)``.
    """
    d_est, alpha_diff = estimate.d, _normalise_angle(estimate.alpha - truth.alpha)
    if abs(alpha_diff) > math.pi / 2:
        alpha_diff -= math.copysign(math.pi, alpha_diff)
        d_est = -d_est
    return d_est - truth.d, alpha_diff, estimate.w - truth.w, estimate.beta - truth.beta
