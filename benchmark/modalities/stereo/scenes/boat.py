"""The target boat of the rendered stereo pairs: its shape and how it is drawn.

TG is built from flat polygons in its own frame (``f`` forward, ``s`` to
starboard, ``z`` up from the waterline), grouped into three convex solids
stacked on each other:

* the hull, a box with a pointed bow from the waterline up to the deck,
  with a dark stripe along the waterline;
* the cabin on the deck, over the reference point and slightly aft, with a
  band of dark windows round it;
* the marker, the yellow blob of seeds/002, section 4.1: an upright drum
  (a prism of :data:`MARKER_FACETS` sides) on the cabin roof, whose axis
  passes through TG's reference point, i.e. the position the truth gives.

:func:`draw_boat` projects the polygons that face the camera with the
pinhole model of eq. (15) and fills them on a patch round the boat that is
supersampled, finely across (so that edges move by a fraction of a pixel
as the boat does, which is all the disparity there is at 6-24 m) and
coarsely down (rows are epipolar lines; vertical precision does not matter
to stereo).  Within a convex solid the faces that face the camera never
overlap; between solids the painter's order follows from the camera's
height: a solid standing on another hides part of it when the camera looks
down on their joint, and is partly hidden by it when the camera is below
the joint.  The patch is averaged down to pixels and laid over the image
with its coverage, so border pixels mix boat and background.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import cv2
import numpy as np

from benchmark.modalities.stereo.scenes.image_spec import StereoRenderSpec

MARKER_FACETS = 32
"""Sides of the prism that stands for the marker drum (its outline is within 0.5 % of the radius)."""

AMBIENT = 0.55
"""Share of the light on the boat that comes from the sky rather than the sun."""

SUBPIXELS_ACROSS = (16, 8)
"""Patch columns per image column: the first for a boat up to :data:`WIDE_PX` wide, the second beyond."""

WIDE_PX = 48
"""Boats wider than this on the image are supersampled more coarsely across."""

SUBPIXELS_DOWN = 2
"""Patch rows per image row."""

SHIFT_BITS = 4
"""Fractional bits of the polygon vertices handed to :func:`cv2.fillConvexPoly`."""

NEAR_M = 0.05
"""Polygons are clipped to at least this far ahead of the camera."""

HULL, CABIN, MARKER = 0, 1, 2
"""Solid indices."""

HULL_WHITE = (228.0, 230.0, 226.0)
DECK_GREY = (170.0, 176.0, 178.0)
STRIPE_NAVY = (70.0, 35.0, 25.0)
CABIN_WHITE = (215.0, 214.0, 210.0)
WINDOW_DARK = (55.0, 45.0, 40.0)


@dataclass(frozen=True)
class BoatBody:
    """TG as polygons in its own frame.

    Attributes
    ----------
    vertices : numpy.ndarray
        Shape ``(M, 3)``: ``(f, s, z)`` of all polygon corners, m.
    starts : numpy.ndarray
        Shape ``(N + 1,)``: polygon ``i`` has corners ``starts[i]:starts[i+1]``.
    normals : numpy.ndarray
        Shape ``(N, 3)``: outward normal of each polygon (a stripe or a
        window has the normal of the face it is painted on).
    colours : numpy.ndarray
        Shape ``(N, 3)``: BGR albedo in full light.
    solids : numpy.ndarray
        Shape ``(N,)``: :data:`HULL`, :data:`CABIN` or :data:`MARKER`.
    deck_m, roof_m, top_m : float
        Heights of the deck, the cabin roof and the top of the marker.
    """

    vertices: np.ndarray
    starts: np.ndarray
    normals: np.ndarray
    colours: np.ndarray
    solids: np.ndarray
    deck_m: float
    roof_m: float
    top_m: float

    def __len__(self) -> int:
        return len(self.normals)

    def solid_order(self, camera_height_m: float) -> tuple[int, int, int]:
        """The painter's order of the solids for a camera at ``camera_height_m`` above the water.

        A solid standing on another is drawn after it when the camera is
        above their joint and before it when the camera is below.
        """
        if camera_height_m >= self.roof_m:
            return HULL, CABIN, MARKER
        if camera_height_m >= self.deck_m:
            return HULL, MARKER, CABIN
        return MARKER, CABIN, HULL


class _Builder:
    """Collects polygons for :class:`BoatBody`."""

    def __init__(self) -> None:
        self.polygons: list[np.ndarray] = []
        self.normals: list[tuple[float, float, float]] = []
        self.colours: list[tuple[float, float, float]] = []
        self.solids: list[int] = []

    def add(self, corners: list[tuple[float, float, float]], normal, colour, solid: int) -> None:
        self.polygons.append(np.array(corners, dtype=float))
        self.normals.append(tuple(float(c) for c in normal))
        self.colours.append(tuple(float(c) for c in colour))
        self.solids.append(solid)

    def prism(
        self,
        outline: list[tuple[float, float]],
        bottom: float,
        top: float,
        colour,
        solid: int,
        roof_colour,
        bands: tuple[tuple[float, float, float, tuple[float, float, float]], ...] = (),
    ) -> None:
        """Vertical faces and the top of a convex prism over a plan outline, with painted bands.

        Each band ``(from, to, inset, colour)`` is painted on every side
        between heights ``from`` and ``to``, ``inset`` (a share of the side's
        length) in from both ends.
        """
        centre = np.mean(np.array(outline), axis=0)
        for (f0, s0), (f1, s1) in zip(outline, outline[1:] + outline[:1]):
            normal = np.array((s1 - s0, -(f1 - f0)))
            normal /= np.hypot(*normal)
            if normal @ (np.array((f0, s0)) - centre) < 0:
                normal = -normal
            normal3 = (normal[0], normal[1], 0.0)
            self.add([(f0, s0, bottom), (f1, s1, bottom), (f1, s1, top), (f0, s0, top)], normal3, colour, solid)
            for lo, hi, inset, band_colour in bands:
                a = (f0 + inset * (f1 - f0), s0 + inset * (s1 - s0))
                b = (f1 - inset * (f1 - f0), s1 - inset * (s1 - s0))
                self.add([(*a, lo), (*b, lo), (*b, hi), (*a, hi)], normal3, band_colour, solid)
        self.add([(f, s, top) for f, s in outline], (0.0, 0.0, 1.0), roof_colour, solid)

    def build(self, deck: float, roof: float, top: float) -> BoatBody:
        sizes = [len(p) for p in self.polygons]
        return BoatBody(
            vertices=np.concatenate(self.polygons),
            starts=np.concatenate(([0], np.cumsum(sizes))),
            normals=np.array(self.normals),
            colours=np.array(self.colours),
            solids=np.array(self.solids),
            deck_m=deck,
            roof_m=roof,
            top_m=top,
        )


def boat_body(spec: StereoRenderSpec) -> BoatBody:
    """The target boat of a sequence.

    Parameters
    ----------
    spec : StereoRenderSpec
        Hull, cabin and marker sizes and the marker's colour.

    Returns
    -------
    BoatBody
        The hull spans ``f`` in ``[-L/2, L/2]``, its bow tapering over the
        front 30 %; the cabin covers the reference point; the marker drum
        stands on the cabin roof with its axis at ``f = s = 0``.
    """
    half_l, half_b, deck = spec.hull_length_m / 2, spec.hull_beam_m / 2, spec.freeboard_m
    roof = deck + spec.cabin_height_m
    top = roof + spec.marker_height_m
    radius = spec.marker_radius_m
    shoulder = half_l - 0.3 * spec.hull_length_m
    builder = _Builder()
    hull = [(-half_l, -half_b), (-half_l, half_b), (shoulder, half_b), (half_l, 0.0), (shoulder, -half_b)]
    stripe = (0.0, 0.15 * deck, 0.0, STRIPE_NAVY)
    builder.prism(hull, 0.0, deck, HULL_WHITE, HULL, DECK_GREY, bands=(stripe,))
    aft = max(radius + 0.1, 0.22 * spec.hull_length_m)
    fore = max(radius + 0.05, 0.12 * spec.hull_length_m)
    side = max(radius + 0.05, 0.36 * spec.hull_beam_m)
    cabin = [(-aft, -side), (-aft, side), (fore, side), (fore, -side)]
    windows = (deck + 0.3 * spec.cabin_height_m, deck + 0.75 * spec.cabin_height_m, 0.1, WINDOW_DARK)
    builder.prism(cabin, deck, roof, CABIN_WHITE, CABIN, DECK_GREY, bands=(windows,))
    angles = 2.0 * math.pi * (np.arange(MARKER_FACETS) + 0.5) / MARKER_FACETS
    drum = [(radius * math.cos(a), radius * math.sin(a)) for a in angles]
    builder.prism(drum, roof, top, spec.marker_bgr, MARKER, spec.marker_bgr)
    return builder.build(deck, roof, top)


@dataclass(frozen=True)
class BoatView:
    """One camera's view of TG.

    Attributes
    ----------
    ahead_m, starboard_m : float
        TG's reference point relative to this camera, m (camera frame:
        ``x`` ahead, ``y`` to starboard).
    aspect : float
        TG's heading minus the camera's, rad.
    camera_height_m : float
        Height of the camera above the water.
    sun : numpy.ndarray
        Unit vector towards the sun in TG's frame ``(f, s, z)``.
    """

    ahead_m: float
    starboard_m: float
    aspect: float
    camera_height_m: float
    sun: np.ndarray


def draw_boat(
    image: np.ndarray, body: BoatBody, view: BoatView, focal_px: float, principal: tuple[float, float]
) -> tuple[tuple[int, int], tuple[int, int]] | None:
    """Draw TG over a BGR ``float32`` image in place.

    Parameters
    ----------
    image : numpy.ndarray
        Shape ``(H, W, 3)``, the background, overwritten where TG is.
    body : BoatBody
        TG's polygons.
    view : BoatView
        Where TG is relative to the camera, and the sun.
    focal_px : float
        ``f``.
    principal : tuple of float
        ``(column, row)`` of the principal point: ``C_y`` (or ``C_y*``) and
        the vertical centre.

    Returns
    -------
    tuple or None
        ``((u0, u1), (v0, v1))``, the pixel box drawn over (ends
        exclusive), or None when no part of TG is in the image.

    References
    ----------
    seeds/002, eq. (15) and Fig. 3 (the pinhole pair); section 4.1 and
    Fig. 10 (the yellow blob on TG).
    """
    c, s = math.cos(view.aspect), math.sin(view.aspect)
    f_b, s_b, z_b = body.vertices[:, 0], body.vertices[:, 1], body.vertices[:, 2]
    points = np.stack(
        (view.ahead_m + c * f_b - s * s_b, view.starboard_m + s * f_b + c * s_b, z_b - view.camera_height_m), axis=1
    )
    camera = np.array(
        (-c * view.ahead_m - s * view.starboard_m, s * view.ahead_m - c * view.starboard_m, view.camera_height_m)
    )
    anchors = body.vertices[body.starts[:-1]]
    facing = np.einsum("ij,ij->i", body.normals, camera - anchors) > 0.0
    shade = AMBIENT + (1.0 - AMBIENT) * np.maximum(body.normals @ view.sun, 0.0)
    colours = np.clip(body.colours * shade[:, None], 0.0, 255.0)
    with np.errstate(divide="ignore", invalid="ignore"):
        projected = _project(points, focal_px, principal)
    polygons: list[tuple[np.ndarray, tuple[float, ...]]] = []
    for solid in body.solid_order(view.camera_height_m):
        for index in np.flatnonzero(facing & (body.solids == solid)):
            span = slice(body.starts[index], body.starts[index + 1])
            uv = projected[span]
            if points[span, 0].min() < NEAR_M:
                corners = _clip_near(points[span])
                if len(corners) < 3:
                    continue
                uv = _project(corners, focal_px, principal)
            polygons.append((uv, (*colours[index], 255.0)))
    if not polygons:
        return None
    every = np.concatenate([uv for uv, _ in polygons])
    height, width = image.shape[:2]
    u0, u1 = max(int(math.floor(every[:, 0].min())) - 1, 0), min(int(math.ceil(every[:, 0].max())) + 2, width)
    v0, v1 = max(int(math.floor(every[:, 1].min())) - 1, 0), min(int(math.ceil(every[:, 1].max())) + 2, height)
    if u1 <= u0 or v1 <= v0:
        return None
    across = SUBPIXELS_ACROSS[0] if u1 - u0 <= WIDE_PX else SUBPIXELS_ACROSS[1]
    patch = np.zeros(((v1 - v0) * SUBPIXELS_DOWN, (u1 - u0) * across, 4), dtype=np.uint8)
    scale = np.array((across, SUBPIXELS_DOWN), dtype=float)
    # Patch cell j spans image coordinates [u0 - 1/2 + j / n, u0 - 1/2 + (j + 1) / n): its centre is integer j.
    origin = np.array((u0 - 0.5, v0 - 0.5))
    limit = float(1 << 20)
    for uv, colour in polygons:
        sub = np.clip(((uv - origin) * scale - 0.5) * (1 << SHIFT_BITS), -limit, limit)
        cv2.fillConvexPoly(patch, np.round(sub).astype(np.int32), colour, cv2.LINE_8, SHIFT_BITS)
    small = cv2.resize(patch, (u1 - u0, v1 - v0), interpolation=cv2.INTER_AREA).astype(np.float32)
    region = image[v0:v1, u0:u1]
    region *= 1.0 - small[..., 3:] / np.float32(255.0)
    region += small[..., :3]
    return (u0, u1), (v0, v1)


def _project(points: np.ndarray, focal_px: float, principal: tuple[float, float]) -> np.ndarray:
    """Pixel coordinates ``(u, v)`` of camera-frame points ``(ahead, starboard, up)``."""
    u = principal[0] + focal_px * points[:, 1] / points[:, 0]
    v = principal[1] - focal_px * points[:, 2] / points[:, 0]
    return np.stack((u, v), axis=1)


def _clip_near(corners: np.ndarray) -> np.ndarray:
    """The part of a convex polygon (camera frame) at least :data:`NEAR_M` ahead (Sutherland-Hodgman)."""
    out = []
    for a, b in zip(corners, np.roll(corners, -1, axis=0)):
        a_in, b_in = a[0] >= NEAR_M, b[0] >= NEAR_M
        if a_in:
            out.append(a)
        if a_in != b_in:
            t = (NEAR_M - a[0]) / (b[0] - a[0])
            out.append(a + t * (b - a))
    return np.array(out).reshape(-1, 3)
