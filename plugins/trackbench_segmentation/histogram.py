"""Segmentation of one image cell by its grey level x gradient histogram (Panda and Rosenfeld).

Ortiz et al. segment each cell of the image with a method of Panda and
Rosenfeld (seeds/000, section 2.3, Fig. 2.4).  Every pixel of the cell is
counted in a bidimensional histogram whose axes are its grey level and the
modulus of its Sobel gradient.  Pixels inside smooth regions sit in the low
rows of the histogram, one "hill" per region; contour pixels, with a high
modulus, sit in the upper part.  The histogram is cut above the smooth
pixels, the contour rows are discarded and the rest is projected onto the
grey-level axis; the "mountains" of that projection, separated by its
valleys, are the regions, and mapping each pixel's grey level back to its
mountain (the back projection) is the segmentation of the cell.

The thesis leaves four things open; the readings made here are

* the gradient modulus is the Euclidean norm of OpenCV's 3 x 3 Sobel
  derivatives, divided by 4 so that a step of ``h`` grey levels between two
  flat regions has a modulus of ``h`` (:func:`gradient_modulus`);
* the cut between smooth and contour pixels is a quantile of the cell's own
  moduli, so that it follows the contrast of each cell (:func:`contour_cut`);
* a valley is a local minimum of the projection smoothed by a Gaussian that
  is deep against both neighbouring peaks: it stays a valley while its
  height is at most ``valley_ratio`` times the lower of the two highest
  points of the mountains on either side (:func:`mountains`).  The tracker's
  default ratio is 1, every local minimum: a cable covers too small a share
  of a cell for its hill to stand apart from the ground's
  (:class:`trackbench_segmentation.params.SegmentationParams`);
* back projection labels every pixel of the cell, contour pixels included,
  by the mountain its grey level falls in: the mountains' grey intervals
  partition ``0..255`` (:func:`back_project`).
"""

from __future__ import annotations

import functools
import math
from collections.abc import Sequence

import cv2
import numba
import numpy as np

GREY_LEVELS = 256
"""Number of grey levels of a ``uint8`` image, the histogram's grey axis."""


def gradient_modulus(image: np.ndarray) -> np.ndarray:
    """Modulus of the Sobel gradient, in grey levels per pixel.

    Parameters
    ----------
    image : numpy.ndarray
        ``uint8`` grey image of shape ``(H, W)``.

    Returns
    -------
    numpy.ndarray
        ``float32`` array of shape ``(H, W)``: ``sqrt(Gx^2 + Gy^2) / 4`` with
        ``Gx``, ``Gy`` the 3 x 3 Sobel responses (borders replicated).  The
        division by the Sobel kernel's weight 4 makes an ideal step of ``h``
        grey levels read ``h``.  The responses are integers of at most
        ``4 * 255`` and ``Gx^2 + Gy^2`` at most ``2 * 1020^2 < 2^24``, so in
        ``float32`` every sum is exact whatever order OpenCV adds in; only
        the square root rounds, correctly, as ``numpy.sqrt`` does.  The
        result does not depend on how the image happens to lie in memory.

    References
    ----------
    seeds/000, section 2.3: "a digital approximation of the gradient
    modulus ... computed using the Sobel operator".
    """
    gx = cv2.Sobel(image, cv2.CV_32F, 1, 0, ksize=3, borderType=cv2.BORDER_REPLICATE)
    gy = cv2.Sobel(image, cv2.CV_32F, 0, 1, ksize=3, borderType=cv2.BORDER_REPLICATE)
    # In place, to spare the allocations: every step but the square root is exact (see above).
    np.multiply(gx, gx, out=gx)
    np.multiply(gy, gy, out=gy)
    np.add(gx, gy, out=gx)
    np.sqrt(gx, out=gx)
    np.multiply(gx, np.float32(0.25), out=gx)
    return gx


def ranked_bins(counts: np.ndarray, shares: Sequence[float]) -> np.ndarray:
    """For each share ``q``, the bin holding the value of rank ``floor(q (n - 1))`` (from 0) among the ``n`` counted.

    Parameters
    ----------
    counts : numpy.ndarray
        A histogram: how many values fall in each bin, in increasing order of value.
    shares : sequence of float
        Shares in ``[0, 1]``.

    Returns
    -------
    numpy.ndarray
        ``int`` bin indices, one per share.
    """
    cumulative = np.cumsum(np.asarray(counts).astype(np.int64))
    return np.searchsorted(cumulative, np.asarray(shares, dtype=np.float64) * (cumulative[-1] - 1), side="right")


LEVEL_STEP = 0.25
"""Resolution of :func:`gradient_level`, grey levels per px."""


def gradient_level(modulus: np.ndarray) -> float:
    """The frame's gradient level: the median of its gradient moduli, to :data:`LEVEL_STEP`.

    The level at which half the pixels count as smooth (``smooth_share``
    0.5, :func:`contour_cut`) measures how rough the frame's ground and
    noise are; a line lies on an edge when its contour pixels are several
    times steeper.  Read from a histogram of :data:`LEVEL_STEP` bins, which
    costs a fraction of a full median on a 640 x 480 frame.

    Parameters
    ----------
    modulus : numpy.ndarray
        ``float32`` gradient moduli (:func:`gradient_modulus`).

    Returns
    -------
    float
        The lower edge of the bin holding the median modulus.
    """
    top = float(modulus.max()) + LEVEL_STEP
    n_bins = int(np.ceil(top / LEVEL_STEP))
    counts = cv2.calcHist([modulus], [0], None, [n_bins], [0.0, n_bins * LEVEL_STEP]).ravel()
    return float(ranked_bins(counts, (0.5,))[0]) * LEVEL_STEP


@numba.njit(cache=True, nogil=True, inline="always")
def _sobel_square(grey: np.ndarray, up: int, r: int, down: int, left: int, c: int, right: int) -> np.int32:
    """``Gx^2 + Gy^2`` of OpenCV's 3 x 3 Sobel responses at ``(r, c)``, the neighbours' rows and columns given."""
    gx = (np.int32(grey[up, right]) + 2 * np.int32(grey[r, right]) + np.int32(grey[down, right])) - (
        np.int32(grey[up, left]) + 2 * np.int32(grey[r, left]) + np.int32(grey[down, left])
    )
    gy = (np.int32(grey[down, left]) + 2 * np.int32(grey[down, c]) + np.int32(grey[down, right])) - (
        np.int32(grey[up, left]) + 2 * np.int32(grey[up, c]) + np.int32(grey[up, right])
    )
    return np.int32(gx * gx + gy * gy)


@numba.njit(cache=True, nogil=True)
def _gradients(
    grey: np.ndarray, bin_width: float, n_bins: int, exact_inverse: bool
) -> tuple[np.ndarray, np.ndarray, float]:
    """:func:`gradient_modulus`, :func:`gradient_bins` and :func:`gradient_level` of ``grey`` in one pass.

    The Sobel responses are the integers OpenCV's 3 x 3 kernels give with the
    borders replicated; their squares' sum is exact in ``float32`` and its
    square root is rounded once, so every modulus is :func:`gradient_modulus`'s
    bit for bit.  The rows divide in ``float32`` as numpy divides a
    ``float32`` array by a Python float (by a power of two, multiplying by its
    inverse is the same division), and the level counts ``floor(4 m)``, the
    bin OpenCV's histogram of :data:`LEVEL_STEP` puts ``m`` in.
    """
    height, width = grey.shape
    modulus = np.empty((height, width), dtype=np.float32)
    rows = np.empty((height, width), dtype=np.int64)
    divisor = np.float32(bin_width)
    inverse = np.float32(1.0) / divisor
    top_row = np.float32(n_bins - 1)
    # The largest modulus is sqrt(2 * 1020^2) / 4 < 361 grey levels per px.
    quarter = np.float32(0.25)
    squares = np.empty(width, dtype=np.int32)
    # Four histograms, filled in turn, so that neighbouring pixels of one bin do not wait on each other.
    counts = np.zeros((4, 4 * 361 + 2), dtype=np.int64)
    for r in range(height):
        up, down = max(r - 1, 0), min(r + 1, height - 1)
        for c in range(1, width - 1):
            squares[c] = _sobel_square(grey, up, r, down, c - 1, c, c + 1)
        squares[0] = _sobel_square(grey, up, r, down, 0, 0, min(1, width - 1))
        squares[width - 1] = _sobel_square(grey, up, r, down, max(width - 2, 0), width - 1, width - 1)
        line = modulus[r]
        for c in range(width):
            line[c] = np.sqrt(np.float32(squares[c])) * quarter
        row_of = rows[r]
        if exact_inverse:
            for c in range(width):
                row_of[c] = np.int64(min(line[c] * inverse, top_row))
        else:
            for c in range(width):
                row_of[c] = np.int64(min(line[c] / divisor, top_row))
        for c in range(width):
            counts[c & 3, np.int64(line[c] * np.float32(4.0))] += 1
    rank = 0.5 * (height * width - 1)
    below_median = 0
    level = 0
    while below_median + counts[0, level] + counts[1, level] + counts[2, level] + counts[3, level] <= rank:
        below_median += counts[0, level] + counts[1, level] + counts[2, level] + counts[3, level]
        level += 1
    return modulus, rows, level * LEVEL_STEP


def frame_gradients(grey: np.ndarray, bin_width: float, n_bins: int) -> tuple[np.ndarray, np.ndarray, float]:
    """A frame's gradient moduli, their rows of the joint histogram and its gradient level, in one compiled pass.

    Parameters
    ----------
    grey : numpy.ndarray
        ``uint8`` grey image of shape ``(H, W)``, at least 1 x 1.
    bin_width, n_bins : float, int
        The joint histogram's gradient bins (:func:`gradient_bins`).

    Returns
    -------
    modulus : numpy.ndarray
        ``gradient_modulus(grey)``.
    rows : numpy.ndarray
        ``gradient_bins(modulus, bin_width, n_bins)``.
    level : float
        ``gradient_level(modulus)``.

    References
    ----------
    seeds/000, section 2.3 (the Sobel gradient modulus of the histogram's second axis).
    """
    if bin_width <= 0 or n_bins < 1:
        raise ValueError(f"need a positive bin width and at least one bin, got {bin_width} and {n_bins}")
    grey = np.ascontiguousarray(grey, dtype=np.uint8)
    return _gradients(grey, float(bin_width), int(n_bins), _is_power_of_two(bin_width))


def joint_histogram(grey: np.ndarray, modulus: np.ndarray, bin_width: float, n_bins: int) -> np.ndarray:
    """The bidimensional histogram of grey level x gradient modulus of Fig. 2.4.

    Parameters
    ----------
    grey : numpy.ndarray
        ``uint8`` grey levels of the cell's pixels, any shape.
    modulus : numpy.ndarray
        Gradient moduli of the same pixels (:func:`gradient_modulus`).
    bin_width : float
        Width of a gradient bin, grey levels per pixel.
    n_bins : int
        Number of gradient bins; moduli beyond the last bin count in it.

    Returns
    -------
    numpy.ndarray
        ``int64`` array of shape ``(n_bins, 256)``: row ``k`` counts the pixels
        of each grey level whose modulus lies in ``[k, k + 1) * bin_width``.
        It sums to the number of pixels.

    References
    ----------
    seeds/000, section 2.3 and Fig. 2.4 (after Panda and Rosenfeld).
    """
    if bin_width <= 0 or n_bins < 1:
        raise ValueError(f"need a positive bin width and at least one bin, got {bin_width} and {n_bins}")
    rows = gradient_bins(modulus, bin_width, n_bins)
    index = rows.ravel() * GREY_LEVELS + grey.ravel().astype(np.int64)
    return np.bincount(index, minlength=n_bins * GREY_LEVELS).reshape(n_bins, GREY_LEVELS)


def gradient_bins(modulus: np.ndarray, bin_width: float, n_bins: int) -> np.ndarray:
    """The gradient row of :func:`joint_histogram` each pixel is counted in (``int64``, same shape)."""
    return np.minimum(modulus / bin_width, n_bins - 1).astype(np.int64)


def contour_cut(modulus: np.ndarray, smooth_share: float, bin_width: float, n_bins: int) -> int:
    """The first gradient row of the histogram that holds contour pixels.

    The cut is the bin above the ``smooth_share`` quantile of the cell's
    moduli: at least that share of the pixels lie below it and count as
    smooth.  A quantile, not a fixed modulus, so that the cut follows the
    contrast of each cell (a vignetted corner against the lit centre).

    Parameters
    ----------
    modulus : numpy.ndarray
        Gradient moduli of the cell's pixels.
    smooth_share : float
        Share of the pixels taken as smooth, in ``(0, 1]``.
    bin_width : float
        Width of a gradient bin.
    n_bins : int
        Number of gradient bins.

    Returns
    -------
    int
        Row index in ``1..n_bins``; rows ``0 .. cut-1`` are the smooth pixels.

    References
    ----------
    seeds/000, section 2.3: "the histogram is divided, discarding the pixels
    with high gradient modulus, which are the contour pixels".
    """
    level = float(np.quantile(modulus, smooth_share))
    return _row_above(level, bin_width, n_bins)


def _row_above(level: float, bin_width: float, n_bins: int) -> int:
    """The gradient row just above a modulus ``level``, at most ``n_bins``."""
    return int(min(n_bins, int(level / bin_width) + 1))


@numba.njit(cache=True, nogil=True)
def _count(
    grey: np.ndarray, rows: np.ndarray, mask: np.ndarray, n_bins: int
) -> tuple[np.ndarray, np.ndarray]:
    """Joint histogram of the pixels under ``mask`` (``rows`` from :func:`gradient_bins`) and its row totals."""
    histogram = np.zeros((n_bins, GREY_LEVELS), dtype=np.int64)
    totals = np.zeros(n_bins, dtype=np.int64)
    height, width = grey.shape
    for r in range(height):
        for c in range(width):
            if mask[r, c]:
                histogram[rows[r, c], grey[r, c]] += 1
                totals[rows[r, c]] += 1
    return histogram, totals


@numba.njit(cache=True, nogil=True)
def _order_statistics(
    modulus: np.ndarray, rows: np.ndarray, mask: np.ndarray, totals: np.ndarray, low_rank: int, high_rank: int
) -> tuple[float, float]:
    """The ``low_rank``-th and ``high_rank``-th smallest moduli under ``mask``, sought in the rows holding them."""
    first = 0
    below = 0
    while below + totals[first] <= low_rank:
        below += totals[first]
        first += 1
    last = first
    size = totals[first]
    while below + size <= high_rank:
        last += 1
        size += totals[last]
    members = np.empty(size, dtype=modulus.dtype)
    count = 0
    height, width = modulus.shape
    for r in range(height):
        for c in range(width):
            if mask[r, c] and first <= rows[r, c] <= last:
                members[count] = modulus[r, c]
                count += 1
    # numpy.partition's two order statistics: the values are the same whichever way they are selected.
    n = members.shape[0]
    low = _select(members, np.int64(0), n, low_rank - below)
    return low, _select(members, low_rank - below, n, high_rank - below)


@numba.njit(cache=True, nogil=True)
def _select(values: np.ndarray, lo: int, hi: int, k: int) -> float:
    """The ``k``-th smallest of ``values[lo:hi]`` (Hoare's selection), moved to ``values[k]``.

    The values before ``k`` in ``lo:hi`` are left no larger and those after
    it no smaller, so a larger rank is then sought in ``k:hi``.
    """
    hi -= 1
    while lo < hi:
        pivot = values[(lo + hi) // 2]
        i, j = lo, hi
        while i <= j:
            while values[i] < pivot:
                i += 1
            while values[j] > pivot:
                j -= 1
            if i <= j:
                values[i], values[j] = values[j], values[i]
                i += 1
                j -= 1
        if k <= j:
            hi = j
        elif k >= i:
            lo = i
        else:
            break
    return values[k]


def counted_cut(
    modulus: np.ndarray,
    rows: np.ndarray,
    mask: np.ndarray,
    totals: np.ndarray,
    smooth_share: float,
    bin_width: float,
    n_bins: int,
) -> int:
    """:func:`contour_cut` of the moduli under ``mask``, mostly without sorting them all.

    The quantile interpolates between two neighbouring order statistics and
    the cut is a non-decreasing function of it, so when order statistics a
    little below and above them give the same cut, that is the cut; only
    otherwise is the quantile itself computed.  When ``bin_width`` is a power
    of two, a modulus' gradient row (:func:`gradient_bins`, in single
    precision) and its cut (in double precision) divide it exactly, so every
    modulus of row ``k`` has the cut ``k + 1`` and the rows' totals suffice
    when both order statistics share a row.

    Parameters
    ----------
    modulus, rows, mask : numpy.ndarray
        The cell's moduli, their gradient rows (:func:`gradient_bins`) and the
        counted pixels, all ``(h, w)``; at least one pixel is counted.
    totals : numpy.ndarray
        Counted pixels per gradient row (the row sums of the joint histogram).
    smooth_share, bin_width, n_bins : float, float, int
        As in :func:`contour_cut`.

    Returns
    -------
    int
        Exactly ``contour_cut(modulus[mask], smooth_share, bin_width, n_bins)``.
    """
    last = int(totals.sum()) - 1
    middle = int(smooth_share * last)
    low_rank, high_rank = max(middle - 1, 0), min(middle + 2, last)
    low_row, high_row = np.searchsorted(np.cumsum(totals), [low_rank, high_rank], side="right")
    if low_row == high_row and _is_power_of_two(bin_width):
        return int(low_row) + 1
    low_modulus, high_modulus = _order_statistics(modulus, rows, mask, totals, low_rank, high_rank)
    low, high = _row_above(float(low_modulus), bin_width, n_bins), _row_above(float(high_modulus), bin_width, n_bins)
    return low if low == high else contour_cut(modulus[mask], smooth_share, bin_width, n_bins)


def _is_power_of_two(value: float) -> bool:
    """Whether ``value`` is ``2^k`` with ``|k| <= 32``: moduli divide by it exactly in single and double precision."""
    mantissa, exponent = math.frexp(value)
    return mantissa == 0.5 and -31 <= exponent <= 33


def grey_projection(histogram: np.ndarray, cut: int) -> np.ndarray:
    """Project the smooth rows of the joint histogram on the grey-level axis.

    Parameters
    ----------
    histogram : numpy.ndarray
        Joint histogram of shape ``(n_bins, 256)`` (:func:`joint_histogram`).
    cut : int
        First contour row (:func:`contour_cut`); rows from it on are discarded.

    Returns
    -------
    numpy.ndarray
        ``int64`` array of length 256: the number of low-gradient pixels of
        each grey level.

    References
    ----------
    seeds/000, section 2.3: projection "on the plane {gray-level, number of
    pixels}".
    """
    return histogram[:cut].sum(axis=0)


def mountains(projection: np.ndarray, sigma: float, valley_ratio: float) -> np.ndarray:
    """Split a grey-level projection at its valleys.

    The projection is smoothed by a Gaussian of ``sigma`` grey levels; every
    local minimum between two rises is a candidate valley.  Repeatedly, the
    shallowest valley whose height exceeds ``valley_ratio`` times the lower
    of its two neighbouring peaks (the highest points between it and the
    next valleys) is removed, joining its two mountains, until every valley
    left is deep.

    Parameters
    ----------
    projection : numpy.ndarray
        Pixel counts per grey level, length 256 (:func:`grey_projection`).
    sigma : float
        Smoothing of the projection, grey levels; 0 does not smooth.
    valley_ratio : float
        Largest height of a valley relative to its lower neighbouring peak,
        in ``[0, 1]``; 0 keeps only valleys that fall to zero pixels.

    Returns
    -------
    numpy.ndarray
        ``int64`` array of the grey levels where a new mountain starts,
        increasing; mountain ``k`` spans the grey levels from the ``k-1``-th
        to the ``k``-th of them (empty: one mountain, the whole range).

    References
    ----------
    seeds/000, section 2.3 and Fig. 2.4: the hills of the histogram.
    """
    values = np.asarray(projection, dtype=np.float64)
    if sigma > 0:
        kernel = _smoothing_kernel(sigma)
        radius = len(kernel) // 2
        padded = np.concatenate((np.full(radius, values[0]), values, np.full(radius, values[-1])))
        values = np.convolve(padded, kernel, mode="valid")
    return _valleys(values, float(valley_ratio))


@numba.njit(cache=True, nogil=True)
def _valleys(values: np.ndarray, valley_ratio: float) -> np.ndarray:
    """The deep valleys of a smoothed projection (see :func:`mountains`)."""
    cuts = np.empty(len(values), dtype=np.int64)
    count = 0
    # A valley: the profile stops falling and later rises; plateaus are cut at their first level.
    falling_before = -1
    for i in range(len(values) - 1):
        rise = values[i + 1] - values[i]
        if rise > 0 and falling_before >= 0:
            cuts[count] = falling_before + 1
            count += 1
        if rise != 0:
            falling_before = i if rise < 0 else -1
    peaks = np.empty(count + 1)
    while count > 0:
        start = 0
        for k in range(count + 1):
            stop = cuts[k] if k < count else len(values)
            # numpy's max of a non-empty slice of finite values, without its nan checks.
            peak = values[start]
            for i in range(start + 1, stop):
                peak = max(peak, values[i])
            peaks[k] = peak
            start = stop
        worst, worst_ratio = -1, valley_ratio
        for k in range(count):
            lower_peak = min(peaks[k], peaks[k + 1])
            ratio = values[cuts[k]] / lower_peak if lower_peak > 0 else 1.0
            if ratio > worst_ratio:
                worst, worst_ratio = k, ratio
        if worst < 0:
            break
        for k in range(worst, count - 1):
            cuts[k] = cuts[k + 1]
        count -= 1
    return cuts[:count].copy()


@functools.lru_cache(maxsize=8)
def _smoothing_kernel(sigma: float) -> np.ndarray:
    """The normalised Gaussian of ``sigma`` grey levels over ``+-ceil(3 sigma)`` that :func:`mountains` smooths with."""
    radius = int(np.ceil(3.0 * sigma))
    offsets = np.arange(-radius, radius + 1)
    with np.errstate(over="ignore"):
        kernel = np.exp(-0.5 * (offsets / sigma) ** 2)
    kernel = kernel / kernel.sum()
    kernel.flags.writeable = False
    return kernel


def back_project(grey: np.ndarray, starts: np.ndarray) -> np.ndarray:
    """Label every pixel by the mountain its grey level belongs to.

    Parameters
    ----------
    grey : numpy.ndarray
        ``uint8`` grey image (or cell) of any shape.
    starts : numpy.ndarray
        Grey levels where mountains start (:func:`mountains`).

    Returns
    -------
    numpy.ndarray
        ``uint8`` labels of the same shape, ``0 .. len(starts)``.

    References
    ----------
    seeds/000, section 2.3: "the back projection of the 'mountains' of this
    histogram define the segmentation of the image cell".
    """
    table = np.searchsorted(np.asarray(starts), np.arange(GREY_LEVELS), side="right").astype(np.uint8)
    return table[grey]


def segment_cell(
    grey: np.ndarray,
    modulus: np.ndarray,
    *,
    smooth_share: float,
    bin_width: float,
    n_bins: int,
    sigma: float,
    valley_ratio: float,
    mask: np.ndarray | None = None,
) -> np.ndarray:
    """Segment one cell: joint histogram, projection of its smooth part, mountains, back projection.

    Parameters
    ----------
    grey, modulus : numpy.ndarray
        The cell's ``uint8`` grey levels and gradient moduli, shape ``(h, w)``.
    smooth_share, bin_width, n_bins : float, float, int
        See :func:`contour_cut` and :func:`joint_histogram`.
    sigma, valley_ratio : float
        See :func:`mountains`.
    mask : numpy.ndarray, optional
        Boolean ``(h, w)``: only these pixels are counted in the histogram
        (the region of interest while tracking); all pixels are labelled.

    Returns
    -------
    numpy.ndarray
        ``uint8`` labels of shape ``(h, w)`` (:func:`back_project`).

    References
    ----------
    seeds/000, section 2.3 and Fig. 2.4.
    """
    if bin_width <= 0 or n_bins < 1:
        raise ValueError(f"need a positive bin width and at least one bin, got {bin_width} and {n_bins}")
    starts = mountain_starts(
        grey,
        modulus,
        gradient_bins(modulus, bin_width, n_bins),
        smooth_share=smooth_share,
        bin_width=bin_width,
        n_bins=n_bins,
        sigma=sigma,
        valley_ratio=valley_ratio,
        mask=mask,
    )
    return np.zeros(grey.shape, np.uint8) if starts is None else back_project(grey, starts)


def mountain_starts(
    grey: np.ndarray,
    modulus: np.ndarray,
    rows: np.ndarray,
    *,
    smooth_share: float,
    bin_width: float,
    n_bins: int,
    sigma: float,
    valley_ratio: float,
    mask: np.ndarray | None = None,
) -> np.ndarray | None:
    """The mountains of one cell's histogram, the segmentation of :func:`segment_cell` before back projection.

    Parameters
    ----------
    grey, modulus : numpy.ndarray
        The cell's ``uint8`` grey levels and gradient moduli, shape ``(h, w)``.
    rows : numpy.ndarray
        The moduli's gradient rows (:func:`gradient_bins` with ``bin_width``
        and ``n_bins``), shape ``(h, w)``.
    smooth_share, bin_width, n_bins, sigma, valley_ratio, mask
        As in :func:`segment_cell`.

    Returns
    -------
    numpy.ndarray or None
        The grey levels where mountains start (:func:`mountains`); None when
        no pixel is counted, and every pixel is then labelled 0.

    References
    ----------
    seeds/000, section 2.3 and Fig. 2.4.
    """
    # Contiguous arrays and a fresh mask whatever the cell: one compiled form of the counting and the order statistics.
    grey, modulus, rows = np.ascontiguousarray(grey), np.ascontiguousarray(modulus), np.ascontiguousarray(rows)
    counted = np.ones(grey.shape, dtype=np.bool_) if mask is None else np.array(mask, dtype=np.bool_, order="C")
    histogram, totals = _count(grey, rows, counted, n_bins)
    if not totals.any():
        return None
    cut = counted_cut(modulus, rows, counted, totals, smooth_share, bin_width, n_bins)
    return mountains(grey_projection(histogram, cut), sigma, valley_ratio)


def compile_kernels() -> None:
    """Compile (or load from numba's cache) the histogram kernels now, on a tiny cell."""
    grey = np.zeros((4, 4), np.uint8)
    modulus = np.zeros((4, 4), np.float32)
    rows = gradient_bins(modulus, 1.0, 2)
    # Whole images and the cells cut out of them are compiled for separately; a bin width that is not a power
    # of two needs the order statistics.
    for cell in (np.s_[:, :], np.s_[:2, :2]):
        for bin_width in (1.0, 1.5):
            mountain_starts(grey[cell], modulus[cell], rows[cell], smooth_share=0.5, bin_width=bin_width, n_bins=2,
                            sigma=1.0, valley_ratio=1.0)
    mountains(np.zeros(GREY_LEVELS, np.int64), 0.0, 1.0)
