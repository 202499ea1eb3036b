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

import cv2
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
        grey levels read ``h``.  The responses are integers, computed
        exactly, so the result does not depend on how the image happens to
        lie in memory (OpenCV's floating-point paths do).

    References
    ----------
    seeds/000, section 2.3: "a digital approximation of the gradient
    modulus ... computed using the Sobel operator".
    """
    gx = cv2.Sobel(image, cv2.CV_16S, 1, 0, ksize=3, borderType=cv2.BORDER_REPLICATE).astype(np.int32)
    gy = cv2.Sobel(image, cv2.CV_16S, 0, 1, ksize=3, borderType=cv2.BORDER_REPLICATE).astype(np.int32)
    return np.sqrt((gx * gx + gy * gy).astype(np.float32)) * np.float32(0.25)


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
    return int(min(n_bins, int(level / bin_width) + 1))


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
        radius = int(np.ceil(3.0 * sigma))
        offsets = np.arange(-radius, radius + 1)
        with np.errstate(over="ignore"):
            kernel = np.exp(-0.5 * (offsets / sigma) ** 2)
        values = np.convolve(np.pad(values, radius, mode="edge"), kernel / kernel.sum(), mode="valid")
    rises = np.diff(values)
    # A valley: the profile stops falling and later rises; plateaus are cut at their first level.
    signs = np.sign(rises)
    nonzero = np.flatnonzero(signs)
    cuts: list[int] = []
    for before, after in zip(nonzero[:-1], nonzero[1:]):
        if signs[before] < 0 and signs[after] > 0:
            cuts.append(int(before) + 1)
    while cuts:
        edges = [0, *cuts, len(values)]
        peaks = [float(values[a:b].max()) for a, b in zip(edges[:-1], edges[1:])]
        worst, worst_ratio = -1, valley_ratio
        for k, cut in enumerate(cuts):
            lower_peak = min(peaks[k], peaks[k + 1])
            ratio = values[cut] / lower_peak if lower_peak > 0 else 1.0
            if ratio > worst_ratio:
                worst, worst_ratio = k, ratio
        if worst < 0:
            break
        del cuts[worst]
    return np.asarray(cuts, dtype=np.int64)


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
    counted_grey, counted_modulus = (grey, modulus) if mask is None else (grey[mask], modulus[mask])
    if counted_grey.size == 0:
        return np.zeros(grey.shape, np.uint8)
    histogram = joint_histogram(counted_grey, counted_modulus, bin_width, n_bins)
    cut = contour_cut(counted_modulus, smooth_share, bin_width, n_bins)
    return back_project(grey, mountains(grey_projection(histogram, cut), sigma, valley_ratio))
