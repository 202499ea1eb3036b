"""The five texture descriptors of Grau et al. (seeds/000, section 2.2).

The thesis names them and what each measures, and says that the first four
are "determined using filter masks, the last one by comparing a pixel to
the pixels in its neighbourhood"; the masks themselves are not given.  The
reading implemented here takes the "lines" of the descriptions to be the
edges of the lightly smoothed image (OpenCV's Canny), looks for isolated
and soft pixels in the image itself, and makes every descriptor a density:
the share of the pixels in a square neighbourhood of side ``window_px`` (a
normalised box mask) that have a particular property.

1. **Straightness** (straight lines density): an edge pixel lies on a
   straight line piece when the ``line_length_px`` square around it holds
   at least ``straight_fill * line_length_px`` edge pixels (a line through
   it) and their directions agree: the length of the mean of their
   doubled-angle direction vectors (box masks over the Sobel gradients) is
   at least ``straight_coherence``.  Oriented line masks were tried first:
   a digital line between two mask orientations fills neither, and with
   one pixel of slack across them, any dense speckle filled them all.
2. **Abruptness** (sudden changes of line direction): at an edge pixel,
   one minus the agreement of the edge directions, as above, in the
   smaller ``turn_window_px`` square around it.  A straight or gently bending line gives 0, a corner or a
   tangle of lines up to 1.
3. **Discontinuity** (cut lines): the line ends, edge pixels with exactly
   one edge pixel among their 8 neighbours (a 3 x 3 counting mask).
4. **Granularity** (isolated pixels): specks, pixels brighter than the
   brightest or darker than the darkest of their 8 neighbours by more than
   ``granular_step`` grey levels (a grey dilation and erosion with the
   3 x 3 ring mask).
5. **Blurriness** (soft intensity changes): pixels that differ by less than
   ``soft_step`` grey levels from the mean of their 8 neighbours.

Every descriptor is a mean of values in ``[0, 1]`` and so lies in
``[0, 1]`` on any image, blank, noisy or saturated: the only division
(the coherence) has its denominator bounded away from zero.
"""

from __future__ import annotations

from dataclasses import dataclass

import cv2
import numpy as np

from benchmark.modalities.camera.io.video import check_grey_image
from trackbench_texture.params import DescriptorParams

NAMES = ("straightness", "abruptness", "discontinuity", "granularity", "blurriness")
"""The descriptors in the order of the last axis of :func:`texture_descriptors`' result."""


def _odd(size: int) -> int:
    return size if size % 2 else size + 1


_NEIGHBOURS = np.array([[1, 1, 1], [1, 0, 1], [1, 1, 1]], np.float32)
_RING = _NEIGHBOURS.astype(np.uint8)


def _density(values: np.ndarray, window: int) -> np.ndarray:
    """Mean of ``values`` over the ``window`` square around each pixel (border pixels mirrored)."""
    size = _odd(window)
    return cv2.boxFilter(values, cv2.CV_32F, (size, size), normalize=True, borderType=cv2.BORDER_REFLECT)


def _filter(values: np.ndarray, mask: np.ndarray) -> np.ndarray:
    return cv2.filter2D(values, cv2.CV_32F, mask, borderType=cv2.BORDER_REFLECT)


def _coherence(edges: np.ndarray, cos2: np.ndarray, sin2: np.ndarray, size: int) -> tuple[np.ndarray, np.ndarray]:
    """Number of edge pixels in the ``size`` square around each pixel, and how alike their directions are.

    The likeness is the length of the mean doubled-angle direction vector,
    in ``[0, 1]``: 1 when all edges there run the same way.
    """
    square = (_odd(size),) * 2
    count = cv2.boxFilter(edges, cv2.CV_32F, square, normalize=False, borderType=cv2.BORDER_REFLECT)
    c = cv2.boxFilter(cos2, cv2.CV_32F, square, normalize=False, borderType=cv2.BORDER_REFLECT)
    s = cv2.boxFilter(sin2, cv2.CV_32F, square, normalize=False, borderType=cv2.BORDER_REFLECT)
    return count, np.clip(np.sqrt(c * c + s * s) / np.maximum(count, 1.0), 0.0, 1.0)


@dataclass(frozen=True, eq=False)
class PixelKinds:
    """The pixels each descriptor counts, as ``float32`` maps of shape ``(H, W)``.

    Attributes
    ----------
    edges : numpy.ndarray
        1 on the Canny edges ("lines") of the smoothed image, else 0.
    straight : numpy.ndarray
        1 on edge pixels of straight line pieces.
    abrupt : numpy.ndarray
        At edge pixels, the spread of edge directions around them, in ``[0, 1]``.
    ends : numpy.ndarray
        1 on line ends (edge pixels with one edge neighbour).
    specks : numpy.ndarray
        1 on isolated pixels.
    soft : numpy.ndarray
        1 on pixels that differ only softly from their neighbours.
    """

    edges: np.ndarray
    straight: np.ndarray
    abrupt: np.ndarray
    ends: np.ndarray
    specks: np.ndarray
    soft: np.ndarray

    def layers(self) -> tuple[np.ndarray, ...]:
        """The maps of the five descriptors in the order of :data:`NAMES`."""
        return self.straight, self.abrupt, self.ends, self.specks, self.soft


def pixel_kinds(image: np.ndarray, params: DescriptorParams) -> PixelKinds:
    """Find the pixels the five descriptors count (see the module docstring).

    Parameters
    ----------
    image : numpy.ndarray
        A ``uint8`` grey image of shape ``(H, W)``.
    params : DescriptorParams
        Mask sizes and thresholds.

    Returns
    -------
    PixelKinds

    Raises
    ------
    ValueError
        If ``image`` is not a non-empty 2-D ``uint8`` array.

    References
    ----------
    seeds/000, section 2.2 (the descriptors of Grau et al.).
    """
    check_grey_image(image)
    grey = image.astype(np.float32)
    if params.smoothing_sigma > 0:
        grey = cv2.GaussianBlur(grey, (0, 0), params.smoothing_sigma, borderType=cv2.BORDER_REFLECT)
    smooth8 = np.clip(np.rint(grey), 0, 255).astype(np.uint8)
    edges = (cv2.Canny(smooth8, params.edge_low, params.edge_high, L2gradient=True) > 0).astype(np.float32)

    gu = cv2.Sobel(grey, cv2.CV_32F, 1, 0, ksize=3, borderType=cv2.BORDER_REFLECT)
    gv = cv2.Sobel(grey, cv2.CV_32F, 0, 1, ksize=3, borderType=cv2.BORDER_REFLECT)
    power = gu * gu + gv * gv + np.float32(1e-6)
    cos2 = edges * (gu * gu - gv * gv) / power
    sin2 = edges * (2.0 * gu * gv) / power

    line_count, line_coherence = _coherence(edges, cos2, sin2, params.line_length_px)
    straight = edges * ((line_count >= params.straight_fill * _odd(params.line_length_px)) & (
        line_coherence >= params.straight_coherence
    ))
    _, turn_coherence = _coherence(edges, cos2, sin2, params.turn_window_px)
    abrupt = edges * np.clip(1.0 - turn_coherence, 0.0, 1.0)

    ends = edges * (np.abs(_filter(edges, _NEIGHBOURS) - 1.0) < 0.5)

    raw = image.astype(np.float32)
    brightest = cv2.dilate(raw, _RING, borderType=cv2.BORDER_REFLECT)
    darkest = cv2.erode(raw, _RING, borderType=cv2.BORDER_REFLECT)
    specks = ((raw - brightest > params.granular_step) | (darkest - raw > params.granular_step)).astype(np.float32)
    soft = (np.abs(raw - _filter(raw, _NEIGHBOURS / 8.0)) < params.soft_step).astype(np.float32)
    return PixelKinds(edges, straight, abrupt, ends, specks, soft)


def densities(kinds: PixelKinds, window: int) -> np.ndarray:
    """The five descriptors: the density of each kind of pixel in the ``window`` square around every pixel.

    Returns
    -------
    numpy.ndarray
        ``float32`` array of shape ``(H, W, 5)`` with values in ``[0, 1]``, in the order of :data:`NAMES`.
    """
    return np.clip(np.stack([_density(layer, window) for layer in kinds.layers()], axis=-1), 0.0, 1.0)


def densities_at(kinds: PixelKinds, window: int, rows: np.ndarray, cols: np.ndarray) -> np.ndarray:
    """The five descriptors at the pixels of a grid, ``densities(kinds, window)[np.ix_(rows, cols)]``.

    Only the grid's values are stacked and clipped, not the whole image's.

    Parameters
    ----------
    kinds : PixelKinds
        The pixels each descriptor counts.
    window : int
        Side of the neighbourhood, px (even values rounded up to odd).
    rows, cols : numpy.ndarray
        Indices of the grid's rows and columns.

    Returns
    -------
    numpy.ndarray
        ``float32`` array of shape ``(len(rows), len(cols), 5)`` with values in ``[0, 1]``, in the order of
        :data:`NAMES`.
    """
    grid = np.ix_(rows, cols)
    return np.clip(np.stack([_density(layer, window)[grid] for layer in kinds.layers()], axis=-1), 0.0, 1.0)


def texture_descriptors(image: np.ndarray, params: DescriptorParams) -> np.ndarray:
    """The five descriptors at every pixel of a grey image.

    Parameters
    ----------
    image : numpy.ndarray
        A ``uint8`` grey image of shape ``(H, W)``.
    params : DescriptorParams
        Mask sizes and thresholds.

    Returns
    -------
    numpy.ndarray
        ``float32`` array of shape ``(H, W, 5)`` with values in ``[0, 1]``:
        straightness, abruptness, discontinuity, granularity and blurriness
        (:data:`NAMES`), each the density of its kind of pixel in the
        ``window_px`` neighbourhood.

    Raises
    ------
    ValueError
        If ``image`` is not a non-empty 2-D ``uint8`` array.

    References
    ----------
    seeds/000, section 2.2 (the descriptors of Grau et al.).
    """
    return densities(pixel_kinds(image, params), params.window_px)
