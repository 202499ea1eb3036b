"""Straight segments fitted to contour chains, grouped in strips and filtered.

After the chains of contour pixels (:mod:`trackbench_segmentation.contours`)
Ortiz et al. "fit straight line segments on each set of these connected
pixels.  Short straight line segments are then discarded.  Groups of
co-linear line segments which fall into a strip-shaped region are used to
form longer line segments.  These long straight line segments are filtered
again using different error metrics including the average of the gradient
modulus of the contour pixels" (seeds/000, section 2.3, Fig. 2.5).

A chain climbs one row at a time, so a segment is fitted as ``u = a + b v``
by least squares over its pixels (``u`` the column of the contour point,
``v`` the row).  :class:`Segments` keeps, per segment, the sums that fit
needs; joining segments adds their sums, so a group is refitted over all
its pixels without keeping them.  The readings made here:

* "short" is a row span below ``min_rows`` (:meth:`Segments.longer_than`);
* segment ``j`` falls into the strip of segment ``i`` when both its end
  points lie within ``strip_px`` of ``i``'s line and their directions differ
  by at most ``max_angle``; groups grow greedily from the segment with the
  most pixels, refitted after each round (:func:`group_collinear`);
* the error metrics of the last filter are the mean gradient modulus of the
  segment's contour pixels (the one the thesis names) and the root mean
  square distance of the pixels from the fitted line (:func:`select_long`).
"""

from __future__ import annotations

from dataclasses import dataclass, fields

import numba
import numpy as np

from benchmark.modalities.camera.geometry import ImageSize, Line


@dataclass(frozen=True, slots=True)
class Segments:
    """Straight segments as the sums of their contour pixels, one entry per segment.

    All attributes are ``float64`` arrays of one length.  ``u`` is the
    contour point's column (between the two pixels of a label change), ``v``
    its row, both in pixel coordinates of the whole image; ``g`` is its
    gradient modulus.

    Attributes
    ----------
    n : numpy.ndarray
        Number of pixels.
    sv, su, svv, suv, suu : numpy.ndarray
        Sums of ``v``, ``u``, ``v^2``, ``u v`` and ``u^2``.
    sg : numpy.ndarray
        Sum of ``g``.
    v_low, v_high : numpy.ndarray
        Lowest and highest row index of the segment's pixels (top and bottom).
    """

    n: np.ndarray
    sv: np.ndarray
    su: np.ndarray
    svv: np.ndarray
    suv: np.ndarray
    suu: np.ndarray
    sg: np.ndarray
    v_low: np.ndarray
    v_high: np.ndarray

    @classmethod
    def empty(cls) -> Segments:
        """No segment."""
        return cls(*(np.zeros(0) for _ in _NAMES))

    @classmethod
    def from_pieces(
        cls,
        rows: np.ndarray,
        columns: np.ndarray,
        pieces: np.ndarray,
        gradient: np.ndarray,
        offset: tuple[int, int],
    ) -> Segments:
        """The segments of straight chain pieces.

        Parameters
        ----------
        rows : numpy.ndarray
            ``int`` rows of the contour points of a cell, in the cell's
            coordinates (:func:`trackbench_segmentation.contours.follow_chains`).
        columns : numpy.ndarray
            Their ``float`` columns in the cell
            (:func:`trackbench_segmentation.contours.snap_to_edges`).
        pieces : numpy.ndarray
            ``[first, stop)`` ranges into them, ``(n, 2)``
            (:func:`trackbench_segmentation.contours.split_chains`).
        gradient : numpy.ndarray
            The cell's gradient modulus; a point's ``g`` is read at its
            nearest pixel.
        offset : tuple of int
            ``(row, column)`` of the cell's top-left pixel in the image.
        """
        if len(pieces) == 0:
            return cls.empty()
        nearest = np.clip(np.rint(columns).astype(np.int64), 0, gradient.shape[1] - 1)
        g = gradient[rows, nearest].astype(np.float64)
        v = rows.astype(np.float64) + offset[0]
        u = columns + float(offset[1])
        firsts = pieces[:, 0]

        def sums(values: np.ndarray) -> np.ndarray:
            return np.add.reduceat(values, firsts)

        # Pieces are contiguous, ordered and cover the chains, so reduceat's ranges are the pieces.
        n = (pieces[:, 1] - pieces[:, 0]).astype(np.float64)
        return cls(n, sums(v), sums(u), sums(v * v), sums(u * v), sums(u * u), sums(g),
                   v[pieces[:, 1] - 1], v[firsts])

    @classmethod
    def concatenate(cls, parts: list[Segments]) -> Segments:
        """All segments of ``parts``, in order."""
        if not parts:
            return cls.empty()
        return cls(*(np.concatenate([getattr(part, name) for part in parts]) for name in _NAMES))

    def __len__(self) -> int:
        return len(self.n)

    def take(self, index: np.ndarray) -> Segments:
        """The segments at ``index`` (integer indices or a boolean mask)."""
        return Segments(*(getattr(self, name)[index] for name in _NAMES))

    @property
    def slope(self) -> np.ndarray:
        """``b`` of the least-squares line ``u = a + b v``."""
        denominator = self.n * self.svv - self.sv**2
        with np.errstate(divide="ignore", invalid="ignore"):
            b = (self.n * self.suv - self.su * self.sv) / denominator
        return np.where(denominator > 0, b, 0.0)

    @property
    def intercept(self) -> np.ndarray:
        """``a`` of the least-squares line ``u = a + b v``."""
        return self.fit()[0]

    def fit(self) -> tuple[np.ndarray, np.ndarray]:
        """``(a, b)`` of the least-squares lines ``u = a + b v``, :attr:`intercept` and :attr:`slope` at once."""
        b = self.slope
        return (self.su - b * self.sv) / self.n, b

    @property
    def angle(self) -> np.ndarray:
        """Angle of the segment from the vertical, rad, ``atan(b)``."""
        return np.arctan(self.slope)

    @property
    def span(self) -> np.ndarray:
        """Rows the segment covers, ``v_high - v_low + 1``."""
        return self.v_high - self.v_low + 1.0

    @property
    def rms(self) -> np.ndarray:
        """Root mean square distance in px of the pixels from the fitted line."""
        a, b = self.fit()
        squares = (
            self.suu - 2 * a * self.su - 2 * b * self.suv + self.n * a * a + 2 * a * b * self.sv + b * b * self.svv
        )
        return np.sqrt(np.maximum(squares, 0.0) / self.n / (1.0 + b * b))

    @property
    def mean_gradient(self) -> np.ndarray:
        """Mean gradient modulus of the segment's contour pixels."""
        return self.sg / self.n

    def u_at(self, v: np.ndarray) -> np.ndarray:
        """Columns of the fitted lines at rows ``v`` (broadcast against the segments)."""
        return self.intercept + self.slope * v

    def line(self, k: int, size: ImageSize) -> Line:
        """Segment ``k`` as an infinite line in model coordinates."""
        a, b = float(self.intercept[k]), float(self.slope[k])
        return pixel_line(a, b, float(self.v_low[k]), float(self.v_high[k]), size)

    def longer_than(self, min_rows: float) -> Segments:
        """The segments spanning at least ``min_rows`` rows: short ones are discarded."""
        return self.take(self.span >= min_rows)


_NAMES = tuple(f.name for f in fields(Segments))
"""The attributes of :class:`Segments`, in order."""


def pixel_line(a: float, b: float, top: float, bottom: float, size: ImageSize) -> Line:
    """The line ``u = a + b v`` in model coordinates, through its points at rows ``top`` and ``bottom``."""
    if bottom - top < 1.0:
        top, bottom = top - 0.5, top + 0.5
    return Line.from_pixels((a + b * top, top), (a + b * bottom, bottom), size)


def group_collinear(segments: Segments, strip_px: float, max_angle: float) -> Segments:
    """Join the co-linear segments that fall into one strip.

    Segments are visited from the most pixels down; each not yet joined
    starts a group and absorbs every other free segment whose two end
    points lie within ``strip_px`` of its fitted line and whose angle
    differs by at most ``max_angle``.  The group is refitted and the search
    repeated around the refitted line until nothing more joins.

    Parameters
    ----------
    segments : Segments
        Straight segments.
    strip_px : float
        Half-width of the strip, px, measured perpendicular to the line.
    max_angle : float
        Largest angle between two segments of a group, rad.

    Returns
    -------
    Segments
        One entry per group, most pixels first.

    References
    ----------
    seeds/000, section 2.3: "groups of co-linear line segments which fall
    into a strip-shaped region are used to form longer line segments".
    """
    if len(segments) == 0:
        return segments
    s = segments
    order = np.argsort(-s.n, kind="stable")
    labels = _group(s.n, s.sv, s.su, s.svv, s.suv, s.suu, s.v_low, s.v_high, order, float(strip_px), float(max_angle))
    joined = Segments(*_join(labels, int(labels.max()) + 1, *(getattr(s, name) for name in _NAMES)))
    return joined.take(np.argsort(-joined.n, kind="stable"))


@numba.njit(cache=True, nogil=True)
def _join(
    labels: np.ndarray,
    count: int,
    n: np.ndarray,
    sv: np.ndarray,
    su: np.ndarray,
    svv: np.ndarray,
    suv: np.ndarray,
    suu: np.ndarray,
    sg: np.ndarray,
    v_low: np.ndarray,
    v_high: np.ndarray,
) -> tuple[np.ndarray, ...]:
    """The :class:`Segments` fields of the groups ``labels`` number ``0 .. count-1``, in the order of :data:`_NAMES`.

    The sums are taken segment after segment in index order, as ``np.bincount`` with weights takes them,
    so they are the same to the last bit; the rows are the least and greatest of the group's.
    """
    sums = np.zeros((7, count))
    low = np.full(count, np.inf)
    high = np.full(count, -np.inf)
    for k in range(labels.shape[0]):
        group = labels[k]
        sums[0, group] += n[k]
        sums[1, group] += sv[k]
        sums[2, group] += su[k]
        sums[3, group] += svv[k]
        sums[4, group] += suv[k]
        sums[5, group] += suu[k]
        sums[6, group] += sg[k]
        low[group] = min(low[group], v_low[k])
        high[group] = max(high[group], v_high[k])
    return sums[0], sums[1], sums[2], sums[3], sums[4], sums[5], sums[6], low, high


@numba.njit(cache=True, nogil=True)
def _fit(n: float, sv: float, su: float, svv: float, suv: float) -> tuple[float, float]:
    """``(a, b)`` of the least-squares line ``u = a + b v`` from its sums."""
    denominator = n * svv - sv * sv
    b = (n * suv - su * sv) / denominator if denominator > 0 else 0.0
    return (su - b * sv) / n, b


@numba.njit(cache=True, nogil=True)
def _lines_and_angles(
    n: np.ndarray, sv: np.ndarray, su: np.ndarray, svv: np.ndarray, suv: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``a``, ``b`` (:func:`_fit`) and the angle ``arctan(b)`` of each segment's line from its sums."""
    a = np.empty(n.shape[0])
    b = np.empty(n.shape[0])
    for k in range(n.shape[0]):
        a[k], b[k] = _fit(n[k], sv[k], su[k], svv[k], suv[k])
    return a, b, np.arctan(b)


@numba.njit(cache=True, nogil=True)
def _group(
    n: np.ndarray,
    sv: np.ndarray,
    su: np.ndarray,
    svv: np.ndarray,
    suv: np.ndarray,
    suu: np.ndarray,
    v_low: np.ndarray,
    v_high: np.ndarray,
    order: np.ndarray,
    strip: float,
    max_angle: float,
) -> np.ndarray:
    """Group label of each segment (see :func:`group_collinear`), groups numbered in the order they start.

    Each group's rounds visit only the segments no group took before it:
    the free segments are kept in index order and the taken ones dropped
    after each group.  A round first lists, without branching, the free
    segments whose angle differs from the group's by no more than
    ``max_angle`` (the test written as ``not abs(...) > max_angle``, so a
    NaN angle is let through and then fails the strip), and tests only
    those against the strip; a segment the group takes is given an infinite
    angle, which no later round lets through.  Every segment is so tested
    in the order, and with the sums, of a full scan of all segments each
    round (the test's reference form).
    """
    count = n.shape[0]
    a, b, angle = _lines_and_angles(n, sv, su, svv, suv)
    labels = np.full(count, -1, dtype=np.int64)
    free = np.arange(count)
    free_angle = angle.copy()
    passed = np.empty(count, dtype=np.int64)
    n_free = count
    groups = 0
    for seed in order:
        if labels[seed] >= 0:
            continue
        labels[seed] = groups
        g0, g1, g2, g3, g4 = n[seed], sv[seed], su[seed], svv[seed], suv[seed]
        joined = True
        while joined:
            joined = False
            ga, gb = _fit(g0, g1, g2, g3, g4)
            scale = np.sqrt(1.0 + gb * gb)
            group_angle = np.arctan(gb)
            n_passed = 0
            for f in range(n_free):
                passed[n_passed] = f
                n_passed += not abs(free_angle[f] - group_angle) > max_angle
            for p in range(n_passed):
                j = free[passed[p]]
                if labels[j] >= 0:
                    continue
                top = abs(a[j] + b[j] * v_low[j] - ga - gb * v_low[j]) / scale
                bottom = abs(a[j] + b[j] * v_high[j] - ga - gb * v_high[j]) / scale
                if top <= strip and bottom <= strip:
                    labels[j] = groups
                    free_angle[passed[p]] = np.inf  # taken: no later round's angle test lets it through
                    g0 += n[j]
                    g1 += sv[j]
                    g2 += su[j]
                    g3 += svv[j]
                    g4 += suv[j]
                    joined = True
        kept = 0
        for f in range(n_free):
            if labels[free[f]] < 0:
                free[kept], free_angle[kept] = free[f], free_angle[f]
                kept += 1
        n_free = kept
        groups += 1
    return labels


def select_long(
    segments: Segments, *, min_rows: float, min_gradient: float, max_rms: float, max_count: int
) -> Segments:
    """The long segments that lie on an edge.

    Parameters
    ----------
    segments : Segments
        Grouped segments (:func:`group_collinear`).
    min_rows : float
        Smallest row span of a long segment.
    min_gradient : float
        Smallest mean gradient modulus of its contour pixels, grey levels per
        pixel: lines that do not lie on or near an edge are rejected.
    max_rms : float
        Largest root mean square distance of its pixels from its line, px.
    max_count : int
        At most this many are kept, those with the most pixels.

    Returns
    -------
    Segments
        The kept segments, most pixels first.

    References
    ----------
    seeds/000, section 2.3: long segments "are filtered again using
    different error metrics including the average of the gradient modulus
    of the contour pixels".
    """
    if len(segments) == 0:
        return segments
    s = segments
    keep = np.flatnonzero(
        _is_long(s.n, s.sv, s.su, s.svv, s.suv, s.suu, s.sg, s.v_low, s.v_high, min_rows, min_gradient, max_rms)
    )
    return segments.take(keep[np.argsort(-segments.n[keep], kind="stable")[:max_count]])


@numba.njit(cache=True, nogil=True)
def _is_long(
    n: np.ndarray,
    sv: np.ndarray,
    su: np.ndarray,
    svv: np.ndarray,
    suv: np.ndarray,
    suu: np.ndarray,
    sg: np.ndarray,
    v_low: np.ndarray,
    v_high: np.ndarray,
    min_rows: float,
    min_gradient: float,
    max_rms: float,
) -> np.ndarray:
    """Per segment, :func:`select_long`'s test of :attr:`Segments.span`, :attr:`Segments.mean_gradient` and
    :attr:`Segments.rms`, each computed with the same operations in the same order as the properties."""
    keep = np.empty(n.shape[0], np.bool_)
    for k in range(n.shape[0]):
        denominator = n[k] * svv[k] - sv[k] * sv[k]
        b = (n[k] * suv[k] - su[k] * sv[k]) / denominator if denominator > 0 else 0.0
        a = (su[k] - b * sv[k]) / n[k]
        squares = (
            suu[k] - 2 * a * su[k] - 2 * b * suv[k] + n[k] * a * a + 2 * a * b * sv[k] + b * b * svv[k]
        )
        if squares < 0.0:
            squares = 0.0
        rms = np.sqrt(squares / n[k] / (1.0 + b * b))
        keep[k] = (v_high[k] - v_low[k] + 1.0 >= min_rows) and (sg[k] / n[k] >= min_gradient) and (rms <= max_rms)
    return keep


def compile_kernels() -> None:
    """Compile (or load from numba's cache) the grouping kernel now."""
    one = np.ones(2)
    _group(one, one, one, 2 * one, one, one, one, one, np.arange(2), 1.0, 0.1)
    _join(np.zeros(2, np.int64), 1, one, one, one, one, one, one, one, one, one)
    _is_long(one, one, one, 2 * one, one, one, one, one, one, 1.0, 1.0, 1.0)
