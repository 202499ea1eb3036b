"""The grey levels the histograms are built on: a smoothed image, normalised to the frame's own range.

The cuts of the method are stated in grey levels: the smoothing of the
histogram's projection (seeds/000, section 2.3, Fig. 2.4), the bins of the
gradient axis and the smallest mean gradient of a long segment.  In raw
grey levels they hold for one contrast only: a murky frame whose cable
stands 25 grey levels off its ground has gradients that never reach a cut
set for 100, and its hills merge under a smoothing set for a wider range.
So the grey levels are first normalised (:func:`normalised_grey`): the
smoothed frame's ``low`` and ``high`` quantiles are stretched to 0 and 255,
and every cut stated in grey levels is then a share of the frame's own
range.  Stretching the integer grey levels of a low-contrast frame would
leave most levels empty, a comb whose teeth the projection's valleys would
follow; the frame is therefore smoothed in floating point and only the
stretched values are rounded.

Without quantiles the frame is smoothed as a ``uint8`` image and its grey
levels kept, as in the paper.
"""

from __future__ import annotations

import cv2
import numpy as np

from trackbench_segmentation.histogram import GREY_LEVELS, ranked_bins

SMALLEST_RANGE = 1.0
"""A frame whose quantiles lie closer than this many grey levels is not stretched: it shows nothing to stretch."""


def normalised_grey(image: np.ndarray, sigma: float, quantiles: tuple[float, float] | None) -> np.ndarray:
    """The smoothed image, its grey levels stretched between two of its quantiles.

    Parameters
    ----------
    image : numpy.ndarray
        ``uint8`` grey image of shape ``(H, W)``.
    sigma : float
        Standard deviation of the Gaussian smoothing, px; 0 does not smooth.
    quantiles : tuple of float or None
        ``(low, high)`` shares of the pixels, ``0 <= low < high <= 1``; the
        smoothed grey levels at these quantiles become 0 and 255, those
        beyond them are clipped.  None keeps the grey levels.

    Returns
    -------
    numpy.ndarray
        ``uint8`` image of shape ``(H, W)``.

    References
    ----------
    seeds/000, section 2.3 (the grey levels of the bidimensional histogram).
    """
    if quantiles is None:
        return image if sigma == 0 else cv2.GaussianBlur(image, (0, 0), sigma)
    smooth = image.astype(np.float32)
    if sigma > 0:
        smooth = cv2.GaussianBlur(smooth, (0, 0), sigma)
    # The smoothed levels are not negative, so OpenCV's conversion (rounded half to even and saturated,
    # like numpy's rint and clip) needs no absolute value.
    rounded = cv2.convertScaleAbs(smooth)
    low, high = grey_quantiles(rounded, quantiles)
    if high - low < SMALLEST_RANGE:
        return rounded
    scale = (GREY_LEVELS - 1) / (high - low)
    return cv2.addWeighted(smooth, scale, smooth, 0.0, -low * scale, dtype=cv2.CV_8U)


def grey_quantiles(image: np.ndarray, quantiles: tuple[float, float]) -> tuple[float, float]:
    """Two quantiles of a ``uint8`` grey image, from its histogram.

    Parameters
    ----------
    image : numpy.ndarray
        ``uint8`` grey image.
    quantiles : tuple of float
        ``(low, high)`` shares of the pixels.

    Returns
    -------
    tuple of float
        For each share ``q``, the grey level of the pixel of rank
        ``floor(q (n - 1))`` (from 0) in increasing order of the ``n``
        pixels.
    """
    counts = cv2.calcHist([image], [0], None, [GREY_LEVELS], [0, GREY_LEVELS]).ravel()
    low, high = ranked_bins(counts, quantiles)
    return float(low), float(high)
