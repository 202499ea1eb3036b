"""Contours of the segments and the chains of contour pixels followed up from the bottom.

"Once the image is segmented, the contours of the segments are used ... the
search for line segments starts from the bottom of the image: once a
contour pixel of a segmented region is found, adjacent pixels are selected
according to a prediction of the cable orientation produced by a Kalman
filter applied over the past cable parameters" (seeds/000, section 2.3,
Fig. 2.5).  The readings made here:

* a contour pixel is a pixel whose right neighbour carries another label
  (:func:`contour_mask`); its contour point lies between the two, at
  ``u + 1/2``.  The cable runs from the bottom of the image upwards, so
  every row crosses each of its borders once, and horizontal label changes
  are exactly the border crossings; a label change between rows would only
  add the horizontal runs the walk below cannot follow;
* a chain (:func:`follow_chains`) starts at the lowest unused contour pixel
  (rows scanned bottom-up, columns left to right) and climbs one row at a
  time; in the next row it expects the contour where the predicted cable
  orientation takes it (``du = -tan(alpha)`` per row up, conventions.md
  section 1) and takes the unused contour pixel nearest to that within
  ``reach`` columns.  Up to ``max_gap`` rows without such a pixel are
  bridged along the predicted direction; the chain ends at the next one;
* a chain that bends is cut into straight pieces by recursive splitting at
  the point farthest from the chord, while that point is more than
  ``split_px`` away (:func:`split_chains`), so that a border followed into
  a stone's outline still gives its straight part.

One addition: a segment's border is where its grey level crosses a cut
between two mountains, which on a soft edge (a cylinder's shading falling
off towards its silhouette) lies inside the edge.  Each contour point is
therefore moved to the strongest gradient modulus within ``snap_px`` columns
of it, refined to a fraction of a pixel by a parabola through the maximum
and its two neighbours (:func:`snap_to_edges`).

The walk and the splitting are compiled with numba (cached on disk); a
tracker calls :func:`compile_kernels` once before its first timed frame.
"""

from __future__ import annotations

import numba
import numpy as np


def contour_mask(labels: np.ndarray) -> np.ndarray:
    """The contour pixels of a segmentation: those whose right neighbour has another label.

    Parameters
    ----------
    labels : numpy.ndarray
        Segment labels of shape ``(h, w)`` (:func:`trackbench_segmentation.histogram.back_project`).

    Returns
    -------
    numpy.ndarray
        Boolean ``(h, w)``; the last column is never a contour pixel.

    References
    ----------
    seeds/000, section 2.3: "the contours of the segments are used for the
    following steps".
    """
    mask = np.zeros(labels.shape, dtype=bool)
    np.not_equal(labels[:, :-1], labels[:, 1:], out=mask[:, :-1])
    return mask


@numba.njit(cache=True, nogil=True)
def _follow(
    mask: np.ndarray, slope: float, reach: int, max_gap: int, min_rows: int
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    height, width = mask.shape
    free = mask.copy()
    capacity = max(16, int(mask.sum()))
    rows = np.empty(capacity, dtype=np.int64)
    cols = np.empty(capacity, dtype=np.int64)
    starts = np.empty(capacity + 1, dtype=np.int64)
    n_points = 0
    n_chains = 0
    for v0 in range(height - 1, -1, -1):
        for u0 in range(width):
            if not free[v0, u0]:
                continue
            first = n_points
            free[v0, u0] = False
            rows[n_points] = v0
            cols[n_points] = u0
            n_points += 1
            position = float(u0)
            gap = 0
            v = v0 - 1
            while v >= 0:
                expected = position + slope
                centre = int(np.floor(expected + 0.5))
                best = -1
                best_distance = 1e9
                for u in range(centre - reach, centre + reach + 1):
                    if 0 <= u < width and free[v, u]:
                        distance = abs(u - expected)
                        if distance < best_distance:
                            best, best_distance = u, distance
                if best < 0:
                    gap += 1
                    if gap > max_gap:
                        break
                    position = expected
                else:
                    gap = 0
                    free[v, best] = False
                    rows[n_points] = v
                    cols[n_points] = best
                    n_points += 1
                    position = float(best)
                v -= 1
            if n_points - first >= min_rows:
                starts[n_chains] = first
                n_chains += 1
            else:
                n_points = first
    starts[n_chains] = n_points
    return rows[:n_points].copy(), cols[:n_points].copy(), starts[: n_chains + 1].copy()


def follow_chains(
    mask: np.ndarray, alpha: float, *, reach: int, max_gap: int, min_rows: int
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Chains of contour pixels climbing from the bottom in a predicted direction.

    Parameters
    ----------
    mask : numpy.ndarray
        Boolean contour pixels of shape ``(h, w)`` (:func:`contour_mask`).
    alpha : float
        Predicted cable orientation in rad (conventions.md section 1; 0 is
        vertical); must lie in ``(-pi/2, pi/2)``.
    reach : int
        Columns either side of the expected one searched in the next row.
    max_gap : int
        Rows without a contour pixel a chain may bridge.
    min_rows : int
        Chains with fewer pixels are dropped (they stay used).

    Returns
    -------
    rows, cols : numpy.ndarray
        ``int64`` pixel coordinates of every kept chain's pixels, chain after
        chain, each chain from the bottom up (one pixel per row).
    starts : numpy.ndarray
        ``int64`` offsets of the chains into ``rows``/``cols``, with the total
        appended: chain ``k`` is ``starts[k]:starts[k+1]``.

    References
    ----------
    seeds/000, section 2.3 and Fig. 2.5.
    """
    if not -np.pi / 2 < alpha < np.pi / 2:
        raise ValueError(f"the walk climbs rows and needs |alpha| < 90 deg, got {np.degrees(alpha):.1f} deg")
    return _follow(np.ascontiguousarray(mask, dtype=np.bool_), -float(np.tan(alpha)), reach, max_gap, min_rows)


@numba.njit(cache=True, nogil=True)
def _split(rows: np.ndarray, cols: np.ndarray, starts: np.ndarray, tolerance: float) -> np.ndarray:
    n_chains = starts.shape[0] - 1
    pieces = np.empty((rows.shape[0] + 1, 2), dtype=np.int64)
    n_pieces = 0
    stack = np.empty((rows.shape[0] + 2, 2), dtype=np.int64)
    for chain in range(n_chains):
        stack[0, 0] = starts[chain]
        stack[0, 1] = starts[chain + 1]
        depth = 1
        while depth > 0:
            depth -= 1
            first, stop = stack[depth, 0], stack[depth, 1]
            last = stop - 1
            dv = float(rows[last] - rows[first])
            du = float(cols[last] - cols[first])
            norm = np.sqrt(dv * dv + du * du)
            farthest = -1
            largest = tolerance
            if norm > 0 and stop - first > 2:
                for k in range(first + 1, last):
                    distance = abs((rows[k] - rows[first]) * du - (cols[k] - cols[first]) * dv) / norm
                    if distance > largest:
                        farthest, largest = k, distance
            if farthest < 0:
                pieces[n_pieces, 0] = first
                pieces[n_pieces, 1] = stop
                n_pieces += 1
            else:
                # The later half is pushed first so that pieces come out bottom-up.
                stack[depth, 0] = farthest
                stack[depth, 1] = stop
                stack[depth + 1, 0] = first
                stack[depth + 1, 1] = farthest
                depth += 2
    return pieces[:n_pieces].copy()


def split_chains(rows: np.ndarray, cols: np.ndarray, starts: np.ndarray, tolerance: float) -> np.ndarray:
    """Cut chains into straight pieces by recursive splitting at the farthest point.

    Parameters
    ----------
    rows, cols, starts : numpy.ndarray
        Chains as :func:`follow_chains` returns them.
    tolerance : float
        Largest distance in px of a pixel from its piece's chord.

    Returns
    -------
    numpy.ndarray
        ``int64`` array of shape ``(n, 2)``: ``[first, stop)`` index ranges
        into ``rows``/``cols``, one per piece, covering every chain.

    References
    ----------
    seeds/000, section 2.3: "straight line segments are fitted on each set
    of these connected pixels".
    """
    if tolerance <= 0:
        raise ValueError(f"the split tolerance must be positive, got {tolerance}")
    return _split(rows, cols, starts, float(tolerance))


def snap_to_edges(rows: np.ndarray, cols: np.ndarray, modulus: np.ndarray, radius: int) -> np.ndarray:
    """Columns of the contour points moved to the strongest gradient nearby.

    Parameters
    ----------
    rows, cols : numpy.ndarray
        Contour pixels (the point lies between ``cols`` and ``cols + 1``).
    modulus : numpy.ndarray
        Gradient modulus of the cell, ``(h, w)``.
    radius : int
        The maximum is sought in columns ``cols - radius + 1 .. cols + radius``
        (clipped to the cell); 0 keeps the points at ``cols + 1/2``, and so
        does a window without a single maximum (a flat modulus).

    Returns
    -------
    numpy.ndarray
        ``float64`` columns of the points, sub-pixel: the first column of the
        window's maximum, moved by at most half a pixel towards the vertex of
        the parabola through it and its two neighbours when that parabola
        opens downwards.
    """
    if radius <= 0 or len(cols) == 0:
        return cols.astype(np.float64) + 0.5
    return _snap(rows, cols, modulus, radius)


@numba.njit(cache=True, nogil=True)
def _snap(rows: np.ndarray, cols: np.ndarray, modulus: np.ndarray, radius: int) -> np.ndarray:
    """:func:`snap_to_edges` for ``radius > 0``; a point whose window and neighbours lie inside its row reads no clamped column."""
    width = modulus.shape[1]
    snapped = np.empty(cols.shape[0], dtype=np.float64)
    for k in range(cols.shape[0]):
        row, col = rows[k], cols[k]
        line = modulus[row]
        if col - radius >= 0 and col + radius + 1 < width:
            # The window and the parabola's neighbours lie inside the row: no column is clamped.
            peak = col - radius + 1
            largest = smallest = line[peak]
            for u in range(col - radius + 2, col + radius + 1):
                value = line[u]
                if value > largest:
                    peak, largest = u, value
                smallest = min(smallest, value)
            if largest == smallest:
                snapped[k] = col + 0.5
                continue
            left = np.float64(line[peak - 1])
            centre = np.float64(line[peak])
            right = np.float64(line[peak + 1])
        else:
            peak = min(max(col - radius + 1, 0), width - 1)
            largest = smallest = line[peak]
            for u in range(col - radius + 2, col + radius + 1):
                value = line[min(max(u, 0), width - 1)]
                if value > largest:
                    peak, largest = min(max(u, 0), width - 1), value
                smallest = min(smallest, value)
            if largest == smallest:
                snapped[k] = col + 0.5
                continue
            left = np.float64(line[max(peak - 1, 0)])
            centre = np.float64(line[peak])
            right = np.float64(line[min(peak + 1, width - 1)])
        curvature = left - 2.0 * centre + right
        shift = 0.5 * (left - right) / curvature if curvature < 0 else 0.0
        snapped[k] = peak + min(max(shift, -0.5), 0.5)
    return snapped


@numba.njit(cache=True, nogil=True)
def label_changes(grey: np.ndarray, starts: np.ndarray, mask: np.ndarray) -> np.ndarray:
    """The contour pixels under ``mask`` of the back projection of ``grey`` on mountains starting at ``starts``.

    Parameters
    ----------
    grey : numpy.ndarray
        ``uint8`` cell of shape ``(h, w)``.
    starts : numpy.ndarray
        ``int64`` grey levels where mountains start, increasing
        (:func:`trackbench_segmentation.histogram.mountains`).
    mask : numpy.ndarray
        Boolean ``(h, w)``: the pixels that may be contour pixels.

    Returns
    -------
    numpy.ndarray
        Boolean ``(h, w)``, ``contour_mask(back_project(grey, starts)) & mask``
        (:func:`contour_mask`, :func:`trackbench_segmentation.histogram.back_project`).
    """
    table = np.searchsorted(starts, np.arange(256), side="right")
    height, width = grey.shape
    changes = np.zeros((height, width), dtype=np.bool_)
    for r in range(height):
        for c in range(width - 1):
            changes[r, c] = mask[r, c] and table[grey[r, c]] != table[grey[r, c + 1]]
    return changes


def compile_kernels() -> None:
    """Compile (or load from numba's cache) the walk and the splitting now, on a tiny image."""
    mask = np.zeros((4, 4), dtype=bool)
    mask[:, 1] = True
    rows, cols, starts = follow_chains(mask, 0.0, reach=1, max_gap=1, min_rows=2)
    split_chains(rows, cols, starts, 1.0)
    modulus = np.ones((4, 4), np.float32)
    snap_to_edges(rows, cols, modulus, 2)
    grey = np.zeros((4, 4), np.uint8)
    for cell in (np.s_[:, :], np.s_[:2, :2]):
        for counted in (mask[cell], np.ones(grey[cell].shape, np.bool_)):
            label_changes(grey[cell], np.zeros(1, np.int64), counted)
