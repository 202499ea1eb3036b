"""The binary edge image the Hough transform votes from.

Matsumoto and Ito and Balasuriya et al. filter the grey image with a
Laplacian of Gaussian (LoG) and take its zero crossings as borders
(seeds/000, section 2.1).  The LoG kernel of the thesis,

    Delta g(x, y) = -1 / (pi sigma^4) exp(-(x^2 + y^2) / (2 sigma^2))
                    (1 - (x^2 + y^2) / (2 sigma^2)),

is the Laplacian of a Gaussian; convolution commutes with the Laplacian, so
the filter is applied here as a separable Gaussian blur followed by the
3 x 3 discrete Laplacian, which gives the same response at a fraction of
the cost of a 25 x 25 kernel.

"Before the application of the Hough transform, the edge image is converted
into a binary image via thresholding, so that only strong borders survive"
(seeds/000, section 2.1).  The thresholded quantity is the local contrast
of each zero crossing: the jump of the LoG response between the two
neighbouring pixels that straddle it.  For an ideal step of height ``h``
grey levels that jump is ``h / (sqrt(2 pi) sigma^3)`` per pixel, so the
threshold is stated as a step height in grey levels, independent of
``sigma``.  Each crossing marks one pixel (the one nearer to zero), which
keeps the borders one pixel thin, as the Hough transform wants them.

The same step heights, gathered over a frame (:func:`crossing_steps`), show
how strong the frame's edges are as a whole; the threshold can be set
relative to them (:mod:`trackbench_hough.thresholds`).
"""

from __future__ import annotations

import math

import cv2
import numpy as np

from benchmark.lazy import lazy_module

# The compiled loops load on the first frame, so that listing the trackers does not import numba.
crossings = lazy_module("trackbench_hough.crossings")


def log_response(image: np.ndarray, sigma: float) -> np.ndarray:
    """Laplacian of Gaussian of a grey image.

    Parameters
    ----------
    image : numpy.ndarray
        Grey image of shape ``(H, W)``, any real dtype.
    sigma : float
        Standard deviation of the Gaussian in px (the thesis shows 3 and 5).

    Returns
    -------
    numpy.ndarray
        ``float32`` array of shape ``(H, W)``: the LoG response, positive on
        the dark side of a border and negative on the bright side.

    References
    ----------
    seeds/000, section 2.1, the LoG formula and Fig. 2.1-2.2.
    """
    if sigma <= 0:
        raise ValueError(f"LoG sigma must be positive, got {sigma}")
    smooth = cv2.GaussianBlur(
        image.astype(np.float32), (0, 0), sigmaX=sigma, sigmaY=sigma, borderType=cv2.BORDER_REPLICATE
    )
    return cv2.Laplacian(smooth, cv2.CV_32F, ksize=1, borderType=cv2.BORDER_REPLICATE)


def step_height_scale(sigma: float) -> float:
    """Factor turning a LoG jump across one pixel into a step height in grey levels.

    For a step of height ``h`` the LoG of the Gaussian-smoothed step,
    ``h g'(x)``, has slope ``h / (sqrt(2 pi) sigma^3)`` at its zero crossing,
    so ``h = jump * sqrt(2 pi) sigma^3``.

    References
    ----------
    seeds/000, section 2.1 (LoG with standard deviation ``sigma``).
    """
    return math.sqrt(2.0 * math.pi) * sigma**3


def crossing_steps(response: np.ndarray, sigma: float, stride: int = 2) -> np.ndarray:
    """Step heights of a sample of the zero crossings of a LoG response.

    The crossings between horizontal neighbours on every ``stride``-th row
    and between vertical neighbours on every ``stride``-th column, each as
    the grey-level step it implies (:func:`step_height_scale`): the
    quantity :func:`zero_crossings` thresholds, for one crossing rather than
    one pixel.

    Parameters
    ----------
    response : numpy.ndarray
        LoG response of shape ``(H, W)`` (:func:`log_response`).
    sigma : float
        The ``sigma`` the response was computed with, in px.
    stride : int
        Rows and columns between the sampled ones; 1 takes every crossing.

    Returns
    -------
    numpy.ndarray
        1-D ``float`` array of step heights in grey levels, in no particular order.

    References
    ----------
    seeds/000, section 2.1 (zero crossings of the LoG indicate borders).
    """
    if stride < 1:
        raise ValueError(f"stride must be at least 1, got {stride}")
    return crossings.crossing_jumps(_floating(response), stride).astype(np.float64) * step_height_scale(sigma)


def median_crossing_step(response: np.ndarray, sigma: float, stride: int = 2) -> float | None:
    """The median of :func:`crossing_steps`, exactly as ``numpy.median`` gives it, from less work.

    Scaling by ``step_height_scale(sigma) > 0`` keeps the order of the
    jumps, so the middle one or two ``float32`` jumps are found by counting
    (:func:`trackbench_hough.crossings.middle_jumps`) instead of
    partitioning every step, then scaled and averaged in ``float64`` as
    ``numpy.median`` averages the two middle steps.

    Parameters
    ----------
    response, sigma, stride
        As :func:`crossing_steps`.

    Returns
    -------
    float or None
        The median step height in grey levels; None without crossings.

    References
    ----------
    seeds/000, section 2.1 (zero crossings of the LoG indicate borders).
    """
    if stride < 1:
        raise ValueError(f"stride must be at least 1, got {stride}")
    jumps, has_nan, below, middle = crossings.middle_jumps(_floating(response), stride)
    scale = step_height_scale(sigma)
    if jumps.size < 2 or has_nan:
        return float(np.median(jumps.astype(np.float64) * scale)) if jumps.size else None
    if jumps.size % 2:
        return float(np.float64(middle) * scale)
    return float((np.float64(below) * scale + np.float64(middle) * scale) / 2.0)


def _floating(response: np.ndarray) -> np.ndarray:
    """The response as a ``float32`` or ``float64`` array, the dtypes the compiled loops are typed for."""
    response = np.asarray(response)
    return response if response.dtype in (np.float32, np.float64) else response.astype(np.float64)


def zero_crossings(response: np.ndarray, sigma: float, min_step: float) -> np.ndarray:
    """Binary image of the strong zero crossings of a LoG response.

    A crossing lies between two horizontally or vertically neighbouring
    pixels whose responses have opposite signs; it is kept when the step
    height it implies (:func:`step_height_scale`) is at least ``min_step``,
    and it marks the one of the two pixels whose response is nearer to zero.

    Parameters
    ----------
    response : numpy.ndarray
        LoG response of shape ``(H, W)`` (:func:`log_response`).
    sigma : float
        The ``sigma`` the response was computed with, in px.
    min_step : float
        Smallest step height, in grey levels, of a border that survives.

    Returns
    -------
    numpy.ndarray
        ``uint8`` image of shape ``(H, W)``: 255 on border pixels, 0 elsewhere.

    References
    ----------
    seeds/000, section 2.1: zero crossings indicate borders; thresholding
    keeps the strong ones.
    """
    response = _floating(response)
    # The jump is compared in the response's own precision, as numpy compares an array with a Python float.
    min_jump = response.dtype.type(min_step / step_height_scale(sigma))
    height, width = response.shape
    return crossings.strong_crossings_in(response, min_jump, np.array([[0, height, 0, width]], np.int64))


def zero_crossings_in(
    response: np.ndarray, sigma: float, min_step: float, rectangles: np.ndarray | list[tuple[int, int, int, int]]
) -> np.ndarray:
    """:func:`zero_crossings` inside the rectangles, 0 elsewhere.

    Each rectangle ``(row0, row1, col0, col1)`` (ends excluded) is judged in
    place, each pixel against the same four neighbours as in the whole
    frame, so it gets the same value
    (:func:`trackbench_hough.crossings.strong_crossings_in`).

    Parameters
    ----------
    response, sigma, min_step
        As :func:`zero_crossings`.
    rectangles : numpy.ndarray or list of tuple of int
        Rows ``(row0, row1, col0, col1)``: where the edge image is wanted
        (:meth:`trackbench_hough.window.SearchWindow.voting_strips`).

    Returns
    -------
    numpy.ndarray
        ``uint8`` image of shape ``(H, W)``.

    References
    ----------
    seeds/000, section 2.1.
    """
    response = _floating(response)
    min_jump = response.dtype.type(min_step / step_height_scale(sigma))
    return crossings.strong_crossings_in(response, min_jump, np.asarray(rectangles, np.int64).reshape(-1, 4))


def edge_image(image: np.ndarray, sigma: float, min_step: float) -> np.ndarray:
    """The thresholded LoG edge image of seeds/000, section 2.1.

    Parameters
    ----------
    image : numpy.ndarray
        ``uint8`` grey image of shape ``(H, W)``.
    sigma : float
        LoG standard deviation in px.
    min_step : float
        Edge threshold as a step height in grey levels.

    Returns
    -------
    numpy.ndarray
        ``uint8`` binary image (0 or 255) of shape ``(H, W)``.

    References
    ----------
    seeds/000, section 2.1.
    """
    return zero_crossings(log_response(image, sigma), sigma, min_step)


def compile_kernels() -> None:
    """Compile (or load from numba's cache) the zero-crossing loops now, before the first timed frame."""
    crossings.compile_kernels()
