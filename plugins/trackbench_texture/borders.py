"""The cable's borders from the classified image.

"The determination of the cable position out of the segmentation results is
not addressed here but necessary if the system is to be used for the
guidance of an underwater vehicle" (seeds/000, section 2.2, Comments).
Texture is measured over a neighbourhood about as wide as the cable, so the
cable class marks a strip around the cable, not its borders; the borders
are the straight line pieces (the pixels the straightness descriptor
counts) along the two sides of that strip.  The reading implemented here:

1. the **strip** is the connected part of the cable-class pixels
   (8-connectivity, at least ``min_region_px`` pixels) that spans the
   largest share of the image's height or width, since a cable crosses the
   whole view.  Its second moments tell whether it lies along the image's
   height (then it is scanned row by row) or across it (column by column);
2. its **centreline** is a robust straight-line fit (OpenCV's Huber
   ``fitLine``) to the middle of the strip in each row (column); it splits
   the straight-piece pixels inside the strip into the two sides;
3. each **border** is a RANSAC line fit to one side's straight-piece
   pixels: the line through two of them that has the most pixels within
   ``inlier_px``, refined by least squares on those.  A border is the
   longest straight line on its side, so clutter inside the strip rarely
   outvotes it.  The pairs of pixels are drawn from the run's random
   generator.  That is the ``"sides"`` pairing (:data:`PAIRINGS`); the
   ``"parallel"`` pairing needs no centreline: the first border is the
   best-supported line along the strip, the second the best-supported line
   off it that runs within twice the largest skew of it at a plausible
   width, and the straight pieces may be looked for in the whole cable
   region rather than the strip, so that a cable wider than the texture
   neighbourhood, whose cable class is a band along each border, is found.

The strip is **not cable-shaped**, and no detection is reported, when no
part is large enough, when the chosen part spans less than
``min_length_share`` of the rows (columns), when either border's inliers
lie on less than ``min_inlier_share`` of the rows (columns) the strip
spans, or when the borders cross inside the image, are narrower than
``min_width_px`` or wider than ``max_width_px``, or converge or diverge by
more than ``max_skew_deg``.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable
from dataclasses import dataclass

import cv2
import numba
import numpy as np

from benchmark.modalities.camera.geometry import Line, cable_from_borders
from benchmark.modalities.camera.model import CableState
from trackbench_texture.params import Pairing
from trackbench_texture.partner import MIN_STRENGTH, WIDEST_SHARE, partner_line
from trackbench_texture.working import WorkingImage


@dataclass(frozen=True, eq=False)
class Strip:
    """The cable region of a classified image, in scan coordinates.

    Attributes
    ----------
    by_rows : bool
        True when the strip lies along the image's height and is scanned row
        by row; False when it is scanned column by column.
    mask : numpy.ndarray
        ``bool`` array of the strip's pixels, indexed ``[along, across]``
        (the image itself when scanned by rows, its transpose otherwise).
    """

    by_rows: bool
    mask: np.ndarray

    def scan(self, image: np.ndarray) -> np.ndarray:
        """An ``(H, W)`` image indexed ``[along, across]`` like :attr:`mask`."""
        return image if self.by_rows else image.T

    @functools.cached_property
    def crossed(self) -> np.ndarray:
        """``bool`` per scan line: True where the strip crosses it."""
        return self.mask.any(axis=1)

    @property
    def coverage(self) -> float:
        """Share of the scan lines the strip crosses."""
        return float(self.crossed.mean())


@dataclass(frozen=True)
class ScanLine:
    """The line ``across = slope * along + intercept`` in scan coordinates."""

    slope: float
    intercept: float

    def at(self, along: np.ndarray | float) -> np.ndarray | float:
        """The across-coordinate of the line at ``along``."""
        return self.slope * along + self.intercept

    def distance(self, along: np.ndarray, across: np.ndarray) -> np.ndarray:
        """Perpendicular distances of points from the line, px."""
        return np.abs(across - self.at(along)) / math.hypot(1.0, self.slope)


def cable_strip(
    cable: np.ndarray, min_region_px: int, rows: np.ndarray | None = None, cols: np.ndarray | None = None
) -> Strip | None:
    """The connected part of the cable-class pixels that spans the image best, or None.

    Parameters
    ----------
    cable : numpy.ndarray
        ``bool`` array of shape ``(H, W)``: the cable-class pixels; or, with
        ``rows`` and ``cols``, of shape ``(h, w)``: the cable-class points of
        a grid, each filling a block of pixels.
    min_region_px : int
        Smallest connected part considered, px.
    rows, cols : numpy.ndarray, optional
        ``(H,)`` and ``(W,)``: the grid row (column) whose class each pixel
        row (column) takes.  Both non-decreasing, and every grid row
        (column) fills at least one pixel row (column), so that the parts
        of the grid fill exactly the parts of the image.

    Returns
    -------
    Strip or None
        None when no connected part has ``min_region_px`` pixels.
    """
    on_grid = rows is not None and cols is not None
    if not on_grid:
        rows, cols = np.arange(cable.shape[0]), np.arange(cable.shape[1])
    count, labels, stats, _ = cv2.connectedComponentsWithStats(cable.astype(np.uint8), connectivity=8)
    parts = stats[1:]
    row_px, col_px = np.bincount(rows, minlength=cable.shape[0]), np.bincount(cols, minlength=cable.shape[1])
    area = np.bincount(labels.ravel(), weights=np.outer(row_px, col_px).ravel(), minlength=count)[1:]
    span = np.maximum(
        _extent_px(row_px, parts[:, cv2.CC_STAT_TOP], parts[:, cv2.CC_STAT_HEIGHT]) / len(rows),
        _extent_px(col_px, parts[:, cv2.CC_STAT_LEFT], parts[:, cv2.CC_STAT_WIDTH]) / len(cols),
    )
    candidates = np.flatnonzero(area >= min_region_px)
    if len(candidates) == 0:
        return None
    best = candidates[span[candidates] == span[candidates].max()]
    if len(best) > 1 and on_grid:
        # Of tied parts the first in OpenCV's labelling of the pixels wins; the grid's labels may come in another order.
        return cable_strip(cable[rows][:, cols], min_region_px)
    region = (labels == best[0] + 1)[rows][:, cols]
    moments = cv2.moments(region.astype(np.uint8), binaryImage=True)
    by_rows = bool(moments["mu02"] >= moments["mu20"])
    return Strip(by_rows, region if by_rows else region.T)


def _extent_px(block_px: np.ndarray, first: np.ndarray, blocks: np.ndarray) -> np.ndarray:
    """Pixels covered by ``blocks`` consecutive blocks from block ``first`` on; block ``k`` has ``block_px[k]``."""
    starts = np.concatenate([[0], np.cumsum(block_px)])
    return starts[first + blocks] - starts[first]


def centreline(strip: Strip) -> ScanLine:
    """A robust straight line through the middle of the strip on each scan line it crosses."""
    crossed = strip.crossed
    rows = strip.mask[crossed]
    first = np.argmax(rows, axis=1)
    last = rows.shape[1] - 1 - np.argmax(rows[:, ::-1], axis=1)
    along = np.flatnonzero(crossed).astype(np.float32)
    middle = 0.5 * (first + last).astype(np.float32)
    if len(along) < 2:
        return ScanLine(0.0, float(middle.mean()))
    va, vc, a0, c0 = cv2.fitLine(np.column_stack([along, middle]), cv2.DIST_HUBER, 0, 0.01, 0.01).ravel()
    if abs(va) < 1e-6:
        return ScanLine(0.0, float(np.median(middle)))
    return ScanLine(float(vc / va), float(c0 - vc / va * a0))


@numba.njit(cache=True, nogil=True)
def _support(
    along: np.ndarray, across: np.ndarray, slopes: np.ndarray, intercepts: np.ndarray, limits: np.ndarray
) -> np.ndarray:
    """Per line ``k``, the number of points whose across-residual from it is at most ``limits[k]``.

    Line ``k`` is ``across = slopes[k] * along + intercepts[k]``.
    """
    support = np.empty(len(slopes), np.intp)
    for k in range(len(slopes)):
        count = 0
        for j in range(len(along)):
            if abs(across[j] - (slopes[k] * along[j] + intercepts[k])) <= limits[k]:
                count += 1
        support[k] = count
    return support


GreyLevels = Callable[[], "np.ndarray | None"]
"""The grey levels of the image in scan coordinates, or None when there are none, worked out on the first call."""

Admissible = Callable[[np.ndarray, np.ndarray], np.ndarray]
"""``(slopes, intercepts) -> bool`` per candidate line: whether RANSAC may choose it."""


def ransac_line(
    along: np.ndarray,
    across: np.ndarray,
    inlier_px: float,
    trials: int,
    rng: np.random.Generator,
    admissible: Admissible | None = None,
) -> tuple[ScanLine, np.ndarray] | None:
    """The line through two of the points with the most points within ``inlier_px``, refined by least squares.

    Parameters
    ----------
    along, across : numpy.ndarray
        ``(N,)`` scan coordinates of the points.
    inlier_px : float
        Distance within which a point supports a line, px.
    trials : int
        Number of pairs of points tried.
    rng : numpy.random.Generator
        Draws the pairs.
    admissible : callable, optional
        Which candidate lines may be chosen (all when None); the refined
        line is kept only while it stays admissible.

    Returns
    -------
    (ScanLine, numpy.ndarray) or None
        The refined line and its inliers (``(N,)`` bool); None for fewer
        than two points or when no pair spans two scan lines (or none is admissible).
    """
    n = len(along)
    if n < 2:
        return None
    pairs = rng.integers(n, size=(trials, 2))
    d_along = along[pairs[:, 1]] - along[pairs[:, 0]]
    usable = d_along != 0
    if not usable.any():
        return None
    pairs, d_along = pairs[usable], d_along[usable]
    slopes = (across[pairs[:, 1]] - across[pairs[:, 0]]) / d_along
    intercepts = across[pairs[:, 0]] - slopes * along[pairs[:, 0]]
    if admissible is not None:
        allowed = admissible(slopes, intercepts)
        if not allowed.any():
            return None
        slopes, intercepts = slopes[allowed], intercepts[allowed]
    support = _support(along, across, slopes, intercepts, inlier_px * np.hypot(1.0, slopes))
    best = int(np.argmax(support))
    line = ScanLine(float(slopes[best]), float(intercepts[best]))
    for _ in range(2):
        inliers = line.distance(along, across) <= inlier_px
        if inliers.sum() < 2 or np.ptp(along[inliers]) == 0:
            break
        slope, intercept = np.polyfit(along[inliers], across[inliers], 1)
        if admissible is not None and not admissible(np.array([slope]), np.array([intercept]))[0]:
            break
        line = ScanLine(float(slope), float(intercept))
    return line, line.distance(along, across) <= inlier_px


def _pixel_ends(line: ScanLine, by_rows: bool, size: tuple[int, int]) -> tuple[tuple[float, float], ...]:
    """Two pixel points ``(u, v)`` of a scan line of an image of ``size = (W, H)``."""
    extent = max((size[1] if by_rows else size[0]) - 1.0, 1.0)
    ends = [(float(line.at(t)), t) for t in (0.0, extent)]
    if not by_rows:
        ends = [(t, a) for a, t in ends]
    return tuple(ends)


@dataclass(frozen=True)
class _PairLimits:
    """What a pair of borders must satisfy: RANSAC's settings and the cable-shape tests (scan-line units)."""

    inlier_px: float
    trials: int
    min_rows: float
    min_width_px: float
    max_width_px: float
    max_skew: float
    partner_strength: float = MIN_STRENGTH
    partner_widest_share: float = WIDEST_SHARE

    def supported(self, along: np.ndarray, inliers: np.ndarray) -> bool:
        """Whether a border's inliers lie on at least ``min_rows`` scan lines."""
        return len(np.unique(along[inliers])) >= self.min_rows


def _by_sides(
    strip: Strip,
    along: np.ndarray,
    across: np.ndarray,
    limits: _PairLimits,
    rng: np.random.Generator,
    scan_grey: GreyLevels | None = None,
) -> list[ScanLine] | None:
    """One border on each side of the strip's centreline: each side's RANSAC line."""
    left_side = across < centreline(strip).at(along)
    borders = []
    for side in (left_side, ~left_side):
        fit = ransac_line(along[side], across[side], limits.inlier_px, limits.trials, rng)
        if fit is None or not limits.supported(along[side], fit[1]):
            return None
        borders.append(fit[0])
    return borders


def _first_border(
    along: np.ndarray, across: np.ndarray, limits: _PairLimits, rng: np.random.Generator
) -> tuple[ScanLine, np.ndarray] | None:
    """The best-supported line along the strip (at most 45 degrees off it) and its inliers, or None."""
    first = ransac_line(
        along, across, limits.inlier_px, limits.trials, rng, lambda slopes, _: np.abs(slopes) <= 1.0
    )
    if first is None or not limits.supported(along, first[1]):
        return None
    return first


def _parallel_partner(
    line: ScanLine,
    taken: np.ndarray,
    middle: float,
    along: np.ndarray,
    across: np.ndarray,
    limits: _PairLimits,
    rng: np.random.Generator,
) -> ScanLine | None:
    """The best-supported line off ``line`` that makes at most twice the largest skew with it at a plausible width."""
    angle = math.atan(line.slope)

    def partner(slopes: np.ndarray, intercepts: np.ndarray) -> np.ndarray:
        gap = np.abs(slopes * middle + intercepts - line.at(middle)) / math.hypot(1.0, line.slope)
        parallel = np.abs(np.arctan(slopes) - angle) <= 2.0 * limits.max_skew
        return parallel & (gap >= limits.min_width_px) & (gap <= limits.max_width_px)

    rest_along, rest_across = along[~taken], across[~taken]
    second = ransac_line(rest_along, rest_across, limits.inlier_px, limits.trials, rng, partner)
    if second is None or not limits.supported(rest_along, second[1]):
        return None
    return second[0]


def _profile_partner(line: ScanLine, scan_grey: GreyLevels, limits: _PairLimits) -> ScanLine | None:
    """The partner of ``line`` read off the grey levels beside it (:func:`~trackbench_texture.partner.partner_line`)."""
    levels = scan_grey()
    if levels is None:
        raise ValueError("texture: the profile pairings need the working image's grey levels")
    found = partner_line(
        levels,
        line.slope,
        line.intercept,
        min_width_px=limits.min_width_px,
        max_width_px=limits.max_width_px,
        max_skew=limits.max_skew,
        min_rows=limits.min_rows,
        min_strength=limits.partner_strength,
        widest_share=limits.partner_widest_share,
    )
    return None if found is None else ScanLine(*found)


def _paired(
    strip: Strip,
    along: np.ndarray,
    across: np.ndarray,
    limits: _PairLimits,
    rng: np.random.Generator,
    scan_grey: GreyLevels,
    partners: tuple[str, ...],
) -> list[ScanLine] | None:
    """The first border, then the first of ``partners`` (``"straight"``, ``"profile"``) that finds its partner."""
    middle = 0.5 * (strip.mask.shape[0] - 1)
    first = _first_border(along, across, limits, rng)
    if first is None:
        return None
    line, taken = first
    for kind in partners:
        second = (
            _parallel_partner(line, taken, middle, along, across, limits, rng)
            if kind == "straight"
            else _profile_partner(line, scan_grey, limits)
        )
        if second is not None:
            return sorted([line, second], key=lambda border: border.at(middle))
    return None


PAIRINGS: dict[str, Callable[..., list[ScanLine] | None]] = {
    "sides": _by_sides,
    "parallel": functools.partial(_paired, partners=("straight",)),
    "profile": functools.partial(_paired, partners=("profile",)),
    "parallel-profile": functools.partial(_paired, partners=("straight", "profile")),
}
"""How the two borders are found, by name: ``(strip, along, across, limits, rng, scan_grey)`` to the two scan
lines in order of their across-coordinate, or None (``scan_grey``: the grey levels in scan coordinates, which
the profile pairings need, worked out when first asked for: :data:`GreyLevels`).  ``"parallel"``: the best-supported line along the strip, then the best-supported
line a cable's width from it, drawn from the points off the first among lines that make at most twice the
largest skew with it; ``"profile"``: its partner read off the grey levels beside it
(:mod:`trackbench_texture.partner`); ``"parallel-profile"``: as ``"parallel"``, and where no straight pieces
pair, as ``"profile"``."""


def fit_borders(
    strip: Strip,
    straight: np.ndarray,
    rng: np.random.Generator,
    work: WorkingImage | None = None,
    region: np.ndarray | None = None,
    pairing: Pairing = "sides",
    *,
    inlier_px: float,
    trials: int,
    min_length_share: float,
    min_inlier_share: float,
    min_width_px: float,
    max_width_px: float,
    max_skew: float,
    grey: np.ndarray | Callable[[], np.ndarray] | None = None,
    partner_strength: float = MIN_STRENGTH,
    partner_widest_share: float = WIDEST_SHARE,
) -> CableState | None:
    """The cable state of the straight borders along the two sides of the strip, or None.

    Parameters
    ----------
    strip : Strip
        The cable region (:func:`cable_strip`).
    straight : numpy.ndarray
        ``(H, W)`` map, non-zero on straight line pieces
        (:attr:`trackbench_texture.descriptors.PixelKinds.straight`).
    rng : numpy.random.Generator
        Draws RANSAC's pairs of points.
    work : WorkingImage, optional
        The working image ``straight`` belongs to: the state is returned in
        its frame's pixels.  None: in ``straight``'s own.
    region : numpy.ndarray, optional
        ``(H, W)`` bool: where the straight pieces are looked for (all the
        cable-class pixels); None: in the strip.
    pairing : str
        A key of :data:`PAIRINGS`.
    inlier_px, trials : float, int
        RANSAC's inlier distance (px) and number of pairs.
    min_length_share, min_inlier_share, min_width_px, max_width_px : float
        The cable-shape tests of the module docstring.
    max_skew : float
        Largest ``|beta|``, rad.
    grey : numpy.ndarray or callable, optional
        ``(H, W)`` ``float32`` grey levels of the image ``straight`` belongs
        to (lightly smoothed): needed by the profile pairings; or a function
        without arguments that returns them, called only if a pairing reads them.
    partner_strength : float
        The profile pairings' smallest ratio of the second border's grey-level step to the first's.
    partner_widest_share : float
        The profile pairings take the widest candidate whose step is at least this share of the strongest's.

    Returns
    -------
    CableState or None
        None when the strip is not cable-shaped (the width and skew tests
        are taken on the working image).
    """
    crossed = strip.crossed
    if crossed.mean() < min_length_share:
        return None
    searched = strip.mask if region is None else strip.scan(region)
    along, across = np.divmod(np.flatnonzero(strip.scan(straight > 0) & searched), strip.mask.shape[1])
    limits = _PairLimits(
        inlier_px, trials, min_inlier_share * crossed.sum(), min_width_px, max_width_px, max_skew, partner_strength, partner_widest_share
    )

    @functools.cache
    def scan_grey() -> np.ndarray | None:
        levels = grey() if callable(grey) else grey
        return None if levels is None else np.ascontiguousarray(strip.scan(levels), dtype=np.float32)

    borders = PAIRINGS[pairing](strip, along.astype(np.float64), across.astype(np.float64), limits, rng, scan_grey)
    if borders is None:
        return None
    low, high = borders
    extent = float(strip.mask.shape[0] - 1)
    if any(high.at(t) <= low.at(t) for t in (0.0, extent)):
        return None
    size = (straight.shape[1], straight.shape[0])
    ends = [_pixel_ends(border, strip.by_rows, size) for border in (low, high)]
    state = cable_from_borders(*(Line.from_pixels(*pair, size) for pair in ends))
    if not (min_width_px <= state.w <= max_width_px and abs(state.beta) <= max_skew):
        return None
    if work is None or not work.resampled:
        return state
    return cable_from_borders(*(work.frame_line(*pair) for pair in ends))

PROFILE_PAIRINGS = frozenset({"profile", "parallel-profile"})
"""The pairings that read the second border off the grey levels (and need them)."""
