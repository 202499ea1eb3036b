"""Canny edges with their modulus and phase (seeds/004, section IV, Fig. 6).

"The Canny filter [23] is applied to extract edges from the input image
I(x, y).  It furnishes also information about the phase F(k) and the
modulus M(k) of the detected edges."  The grey image is smoothed with a
Gaussian, its gradient is taken with the 3 x 3 Sobel operator, and the same
two gradient images feed OpenCV's Canny (non-maximum suppression and
hysteresis) and the modulus and phase, so that every edge's ``M(k)`` and
``F(k)`` are exactly the gradient Canny thresholded.  Only the edge pixels
need them, so they are computed there alone.

The phase is the direction of the gradient (from dark to bright) in the
model coordinates of conventions.md section 1 (``x`` right, ``y`` up): with
the Sobel derivatives ``gu`` along the columns and ``gv`` down the rows,
``F = atan2(-gv, gu)``, since ``y`` runs against ``v``.  A straight edge's
phase is then the normal angle of its line in the same coordinates, up to
the half turn that the edge's polarity adds.
"""

from __future__ import annotations

from dataclasses import dataclass

import cv2
import numpy as np

from benchmark.modalities.camera.io.video import check_grey_image, grey_image


@dataclass(frozen=True, eq=False)
class EdgeMap:
    """The edges of one grey image.

    Attributes
    ----------
    mask : numpy.ndarray
        ``bool`` array of shape ``(H, W)``: True on Canny edge pixels.
    pixels : numpy.ndarray
        ``int64`` array of shape ``(n,)``: the flat indices ``v W + u`` of the
        edge pixels, increasing (row-major order).
    modulus : numpy.ndarray
        ``float32`` array of shape ``(n,)``: gradient magnitude ``M(k)`` of
        the smoothed image at each edge pixel (Sobel units, about ``2.1``
        times a blurred step's height in grey levels for ``sigma = 1.5``).
    phase : numpy.ndarray
        ``float32`` array of shape ``(n,)``: gradient direction ``F(k)`` in
        rad, in ``[-pi, pi]``, counter-clockwise from model ``+x``
        (``atan2(-gv, gu)``), at each edge pixel.
    """

    mask: np.ndarray
    pixels: np.ndarray
    modulus: np.ndarray
    phase: np.ndarray

    @classmethod
    def from_images(cls, mask: np.ndarray, modulus: np.ndarray, phase: np.ndarray) -> EdgeMap:
        """The edge map of a mask, with the modulus and phase images of shape ``(H, W)`` read at its pixels."""
        pixels = np.flatnonzero(mask)
        return cls(mask, pixels, modulus.ravel()[pixels], phase.ravel()[pixels])

    @property
    def size(self) -> tuple[int, int]:
        """Image ``(W, H)`` in px."""
        return self.mask.shape[1], self.mask.shape[0]


def as_grey(image: np.ndarray) -> np.ndarray:
    """A camera observation as the ``uint8`` grey image of shape ``(H, W)`` the module works on.

    See :func:`benchmark.modalities.camera.io.video.grey_image`; ValueError for anything it cannot read.
    """
    return grey_image(image)


def gradient_modulus(gu: np.ndarray, gv: np.ndarray) -> np.ndarray:
    """``M = sqrt(gu^2 + gv^2)`` of Sobel derivatives, correctly rounded to ``float32``.

    Parameters
    ----------
    gu, gv : numpy.ndarray
        ``int16`` derivatives along the columns and down the rows, at most
        ``2^11`` in magnitude (the 3 x 3 Sobel operator on a ``uint8`` image
        gives at most 1020).

    Returns
    -------
    numpy.ndarray
        ``float32`` moduli.  The sum of squares stays below ``2^24``, so it is
        exact in ``int32`` and in ``float32``, and its ``float32`` square root is
        the exact modulus rounded once: the same on every machine.
    """
    gu, gv = gu.astype(np.int32), gv.astype(np.int32)
    return np.sqrt((gu * gu + gv * gv).astype(np.float32))


def gradient_phase(gu: np.ndarray, gv: np.ndarray) -> np.ndarray:
    """``F = atan2(-gv, gu)`` of Sobel derivatives, ``float32``: the gradient direction in model coordinates."""
    return np.arctan2(-gv.astype(np.float32), gu.astype(np.float32))


def smoothed_gradient(image: np.ndarray, sigma: float) -> tuple[np.ndarray, np.ndarray]:
    """Sobel derivatives ``(gu, gv)`` of a grey image after Gaussian smoothing, ``int16`` of shape ``(H, W)``.

    Parameters
    ----------
    image : numpy.ndarray
        ``uint8`` grey image of shape ``(H, W)``.
    sigma : float
        Standard deviation in px of the Gaussian smoothing; 0 skips it.

    References
    ----------
    seeds/004, section IV (the Canny filter [23] furnishes phase and modulus).
    """
    check_grey_image(image)
    if not sigma >= 0:
        raise ValueError(f"sigma must be >= 0, got {sigma}")
    smooth = image if sigma == 0 else cv2.GaussianBlur(image, (0, 0), sigmaX=sigma, borderType=cv2.BORDER_REPLICATE)
    gu = cv2.Sobel(smooth, cv2.CV_16S, 1, 0, ksize=3, borderType=cv2.BORDER_REPLICATE)
    gv = cv2.Sobel(smooth, cv2.CV_16S, 0, 1, ksize=3, borderType=cv2.BORDER_REPLICATE)
    return gu, gv


def canny_from_gradient(gu: np.ndarray, gv: np.ndarray, low: float, high: float) -> EdgeMap:
    """Canny's non-maximum suppression and hysteresis on given Sobel derivatives, with each edge's modulus and phase.

    Parameters
    ----------
    gu, gv : numpy.ndarray
        ``int16`` derivatives along the columns and down the rows (:func:`smoothed_gradient`).
    low, high : float
        Hysteresis thresholds on the L2 gradient magnitude, ``0 <= low <= high``.

    References
    ----------
    seeds/004, section IV (edge extraction with the Canny filter [23]).
    """
    if not 0 <= low <= high:
        raise ValueError(f"Canny thresholds must satisfy 0 <= low <= high, got low={low}, high={high}")
    mask = cv2.Canny(gu, gv, float(low), float(high), L2gradient=True) > 0
    pixels = np.flatnonzero(mask)
    gu, gv = gu.ravel()[pixels], gv.ravel()[pixels]
    return EdgeMap(mask, pixels, gradient_modulus(gu, gv), gradient_phase(gu, gv))


def canny_edges(image: np.ndarray, sigma: float, low: float, high: float) -> EdgeMap:
    """Canny edges of a grey image, with the modulus and phase of each.

    Parameters
    ----------
    image : numpy.ndarray
        ``uint8`` grey image of shape ``(H, W)``.
    sigma : float
        Standard deviation in px of the Gaussian smoothing; 0 skips it.
    low, high : float
        Canny's hysteresis thresholds on the L2 Sobel gradient magnitude of
        the smoothed image, ``0 <= low <= high``.

    Returns
    -------
    EdgeMap
        The edge mask and the modulus and phase of its pixels.

    References
    ----------
    seeds/004, section IV (edge extraction with the Canny filter [23]).
    """
    if not 0 <= low <= high:
        raise ValueError(f"Canny thresholds must satisfy 0 <= low <= high, got low={low}, high={high}")
    return canny_from_gradient(*smoothed_gradient(image, sigma), low, high)
