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

import math
from dataclasses import dataclass

import cv2
import numba
import numpy as np

from benchmark.modalities.camera.io.video import check_grey_image
from trackbench_texture.params import DescriptorParams

NAMES = ("straightness", "abruptness", "discontinuity", "granularity", "blurriness")
"""The descriptors in the order of the last axis of :func:`texture_descriptors`' result."""


def _odd(size: int) -> int:
    return size if size % 2 else size + 1


_NEIGHBOURS = np.array([[1, 1, 1], [1, 0, 1], [1, 1, 1]], np.float32)
_RING = _NEIGHBOURS.astype(np.uint8)
_TINY, _TWO = np.float32(1e-6), np.float32(2.0)


def _density(values: np.ndarray, window: int) -> np.ndarray:
    """Mean of ``values`` over the ``window`` square around each pixel (border pixels mirrored)."""
    size = _odd(window)
    return cv2.boxFilter(values, cv2.CV_32F, (size, size), normalize=True, borderType=cv2.BORDER_REFLECT)


def _filter(values: np.ndarray, mask: np.ndarray) -> np.ndarray:
    return cv2.filter2D(values, cv2.CV_32F, mask, borderType=cv2.BORDER_REFLECT)


def _box_sum(values: np.ndarray, size: int) -> np.ndarray:
    """Sum of ``values`` over the ``size`` square around each pixel (border pixels mirrored), ``float32``."""
    return cv2.boxFilter(values, cv2.CV_32F, (size, size), normalize=False, borderType=cv2.BORDER_REFLECT)


@numba.njit(cache=True, nogil=True)
def _rounded_grey(values: np.ndarray) -> np.ndarray:
    """``np.clip(np.rint(values), 0, 255).astype(np.uint8)`` of a ``float32`` image, in one pass."""
    out = np.empty(values.shape, np.uint8)
    flat, rounded = values.reshape(-1), out.reshape(-1)
    for k in range(flat.size):
        rounded[k] = np.uint8(min(max(np.rint(flat[k]), np.float32(0.0)), np.float32(255.0)))
    return out


@numba.njit(cache=True, nogil=True)
def _doubled_angles(gu: np.ndarray, gv: np.ndarray, at: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The doubled-angle direction vectors ``(cos 2a, sin 2a)`` of the gradients at flat indices ``at``, 0 elsewhere.

    Parameters
    ----------
    gu, gv : numpy.ndarray
        ``float32`` gradients of shape ``(H, W)``.
    at : numpy.ndarray
        Flat indices of the edge pixels.

    Returns
    -------
    cos2, sin2 : numpy.ndarray
        ``float32`` maps of shape ``(H, W)``, computed in ``float32``.
    """
    cos2, sin2 = np.zeros(gu.shape, np.float32), np.zeros(gu.shape, np.float32)
    u_at, v_at, cos2_at, sin2_at = gu.reshape(-1), gv.reshape(-1), cos2.reshape(-1), sin2.reshape(-1)
    for k in at:
        u, v = u_at[k], v_at[k]
        power = u * u + v * v + _TINY
        cos2_at[k] = (u * u - v * v) / power
        sin2_at[k] = (_TWO * u * v) / power
    return cos2, sin2


def _box_counts(on: np.ndarray, size: int) -> np.ndarray:
    """The number of True pixels of a ``bool`` map in the odd ``size`` (at most 255 px) square around each pixel.

    Border pixels are mirrored, as in every other mask here; ``uint16``.
    """
    return cv2.boxFilter(on.view(np.uint8), cv2.CV_16U, (size, size), normalize=False, borderType=cv2.BORDER_REFLECT)


@numba.njit(inline="always")
def _likeness(cos2_sum: np.float32, sin2_sum: np.float32, count: np.float32) -> np.float32:
    """How alike the directions of ``count`` edge pixels are: the length of their mean doubled-angle vector, in [0, 1].

    Computed in ``float32``; the denominator is at least 1.
    """
    mean = np.sqrt(cos2_sum * cos2_sum + sin2_sum * sin2_sum) / max(count, np.float32(1.0))
    return min(max(mean, np.float32(0.0)), np.float32(1.0))


@numba.njit(cache=True, nogil=True)
def _edge_kinds(
    at: np.ndarray,
    line_counts: np.ndarray,
    turn_counts: np.ndarray,
    around: np.ndarray,
    line_sums: tuple[np.ndarray, np.ndarray],
    turn_sums: tuple[np.ndarray, np.ndarray],
    min_count: np.float32,
    min_coherence: np.float32,
    straight: np.ndarray,
    abrupt: np.ndarray,
    ends: np.ndarray,
) -> None:
    """Mark the straight pieces, abruptness and line ends at the edge pixels ``at`` (flat indices).

    Parameters
    ----------
    at : numpy.ndarray
        Flat indices of the edge pixels.
    line_counts, turn_counts, around : numpy.ndarray
        ``(H, W)`` numbers of edge pixels in the line, turn and 3 x 3 squares around each pixel.
    line_sums, turn_sums : tuple of numpy.ndarray
        ``(H, W)`` ``float32`` sums of the doubled-angle vectors' ``cos`` and ``sin`` over the line (turn) squares.
    min_count, min_coherence : numpy.float32
        A straight piece has at least ``min_count`` edge pixels in its line square, whose directions agree
        at least ``min_coherence``.
    straight, abrupt, ends : numpy.ndarray
        ``(H, W)`` maps, 0 (False) everywhere, written at ``at``: ``bool``, ``float32`` and ``bool``.
    """
    line_counts, turn_counts, around = line_counts.reshape(-1), turn_counts.reshape(-1), around.reshape(-1)
    line_cos, line_sin = line_sums[0].reshape(-1), line_sums[1].reshape(-1)
    turn_cos, turn_sin = turn_sums[0].reshape(-1), turn_sums[1].reshape(-1)
    straight, abrupt, ends = straight.reshape(-1), abrupt.reshape(-1), ends.reshape(-1)
    one = np.float32(1.0)
    for k in at:
        count = np.float32(line_counts[k])
        straight[k] = count >= min_count and _likeness(line_cos[k], line_sin[k], count) >= min_coherence
        turn = _likeness(turn_cos[k], turn_sin[k], np.float32(turn_counts[k]))
        abrupt[k] = min(max(one - turn, np.float32(0.0)), one)
        # An edge pixel's 3 x 3 square holds itself and, at a line end, one edge neighbour.
        ends[k] = around[k] == 2


@numba.njit(cache=True, nogil=True)
def _reflected(p: int, n: int) -> int:
    """Index ``p`` mirrored into ``range(n)`` as OpenCV's ``BORDER_REFLECT`` mirrors it (``fedcba|abcdef``)."""
    if n == 1:
        return 0
    while p < 0 or p >= n:
        p = -p - 1 if p < 0 else 2 * n - p - 1
    return p


@dataclass(frozen=True, eq=False)
class PixelKinds:
    """The pixels each descriptor counts, as maps of shape ``(H, W)``: ``bool`` but for abruptness.

    Attributes
    ----------
    edges : numpy.ndarray
        True on the Canny edges ("lines") of the smoothed image.
    straight : numpy.ndarray
        True on edge pixels of straight line pieces.
    abrupt : numpy.ndarray
        ``float32``: at edge pixels, the spread of edge directions around them, in ``[0, 1]``; 0 elsewhere.
    ends : numpy.ndarray
        True on line ends (edge pixels with one edge neighbour).
    specks : numpy.ndarray
        True on isolated pixels.
    soft : numpy.ndarray
        True on pixels that differ only softly from their neighbours.
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


def pixel_kinds(image: np.ndarray, params: DescriptorParams, noise_image: np.ndarray | None = None) -> PixelKinds:
    """Find the pixels the five descriptors count (see the module docstring).

    Parameters
    ----------
    image : numpy.ndarray
        A ``uint8`` grey image of shape ``(H, W)``.
    params : DescriptorParams
        Mask sizes and thresholds.
    noise_image : numpy.ndarray, optional
        The image whose specks and soft pixels are counted (granularity and
        blurriness), of ``image``'s shape; None: ``image`` itself.

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
    raw = image.astype(np.float32)
    grey = raw
    if params.smoothing_sigma > 0:
        grey = cv2.GaussianBlur(raw, (0, 0), params.smoothing_sigma, borderType=cv2.BORDER_REFLECT)
    smooth8 = _rounded_grey(grey)
    on_edge = cv2.Canny(smooth8, params.edge_low, params.edge_high, L2gradient=True) > 0

    at = np.flatnonzero(on_edge)
    gu = cv2.Sobel(grey, cv2.CV_32F, 1, 0, ksize=3, borderType=cv2.BORDER_REFLECT)
    gv = cv2.Sobel(grey, cv2.CV_32F, 0, 1, ksize=3, borderType=cv2.BORDER_REFLECT)
    cos2, sin2 = _doubled_angles(gu, gv, at)
    line_size, turn_size = _odd(params.line_length_px), _odd(params.turn_window_px)
    straight, ends = np.zeros(on_edge.shape, bool), np.zeros(on_edge.shape, bool)
    abrupt = np.zeros(on_edge.shape, np.float32)
    _edge_kinds(
        at,
        *(_box_counts(on_edge, size) for size in (line_size, turn_size, 3)),
        (_box_sum(cos2, line_size), _box_sum(sin2, line_size)),
        (_box_sum(cos2, turn_size), _box_sum(sin2, turn_size)),
        # numpy compares a float32 array with a Python float as float32.
        np.float32(params.straight_fill * line_size),
        np.float32(params.straight_coherence),
        straight,
        abrupt,
        ends,
    )

    if noise_image is not None:
        check_grey_image(noise_image)
        image, raw = noise_image, noise_image.astype(np.float32)
    brightest = cv2.dilate(image, _RING, borderType=cv2.BORDER_REFLECT)
    darkest = cv2.erode(image, _RING, borderType=cv2.BORDER_REFLECT)
    # A whole number of grey levels exceeds the (float32) step exactly when it exceeds the step's floor.
    limit = min(math.floor(np.float32(params.granular_step)), 255)
    specks = (cv2.subtract(image, brightest) > limit) | (cv2.subtract(darkest, image) > limit)
    soft = np.abs(raw - _filter(raw, _NEIGHBOURS / 8.0)) < params.soft_step
    return PixelKinds(on_edge, straight, abrupt, ends, specks, soft)


def densities(kinds: PixelKinds, window: int) -> np.ndarray:
    """The five descriptors: the density of each kind of pixel in the ``window`` square around every pixel.

    Returns
    -------
    numpy.ndarray
        ``float32`` array of shape ``(H, W, 5)`` with values in ``[0, 1]``, in the order of :data:`NAMES`.
    """
    layers = [_density(layer.astype(np.float32, copy=False), window) for layer in kinds.layers()]
    return np.clip(np.stack(layers, axis=-1), 0.0, 1.0)


_LANE = 16
"""Bits of each count in :func:`_grid_window_sums`' packed sums: a square of at most 255 x 255 px holds < 2**16."""


@numba.njit(cache=True, nogil=True)
def _packed(counted: tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray], y: int, x: int) -> np.uint64:
    """The four 0/1 layers' values at ``(y, x)``, one in each :data:`_LANE`-bit lane of a ``uint64``."""
    straight, ends, specks, soft = counted
    return (
        np.uint64(straight[y, x])
        | (np.uint64(ends[y, x]) << _LANE)
        | (np.uint64(specks[y, x]) << 2 * _LANE)
        | (np.uint64(soft[y, x]) << 3 * _LANE)
    )


@numba.njit(cache=True, nogil=True)
def _grid_window_sums(
    counted: tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray],
    abrupt: np.ndarray,
    size: int,
    rows: np.ndarray,
    cols: np.ndarray,
    out: np.ndarray,
) -> None:
    """Fill ``out[i, j]`` with the five densities of the ``size`` square around pixel ``(rows[i], cols[j])``.

    Border pixels are mirrored as :func:`_density` mirrors them.  The sums
    are differences of running sums, down the mirrored rows to the grid's
    rows, then along each grid row's mirrored column sums.  The four 0/1
    layers of ``counted`` are summed at once, packed into the
    :data:`_LANE`-bit lanes of one ``uint64`` per pixel: the arithmetic is
    modulo ``2**64`` and linear, so a difference is exactly the packed
    counts of its square, each below ``2**16``.  The abruptness values are
    summed in ``float64``, exactly as well: each is a multiple of ``2**-24``
    in ``[0, 1]`` (one minus a ``float32`` coherence in ``[0, 1]``), so
    every running sum of fewer than ``2**29`` of them needs at most 53 bits.
    Each exact sum is scaled as OpenCV's normalised box filter scales it:
    times ``1 / size**2`` in ``float64``, rounded to ``float32``.

    Parameters
    ----------
    counted : tuple of numpy.ndarray
        Straight, ends, specks and soft: ``uint8`` 0/1 arrays of shape ``(H, W)``.
    abrupt : numpy.ndarray
        ``float32`` abruptness of shape ``(H, W)``.
    size : int
        Odd side of the square, px, at most 255.
    rows, cols : numpy.ndarray
        Indices of the grid's rows and columns.
    out : numpy.ndarray
        ``float32`` array of shape ``(len(rows), len(cols), 5)``, in the order of :data:`NAMES`.
    """
    height, width = abrupt.shape
    half = size // 2
    scale = 1.0 / (size * size)
    # Running sums over the rows of the image mirrored ``half`` rows beyond each edge: before mirrored row ``e``.
    running_counts = np.zeros(width, np.uint64)
    running_abrupt = np.zeros(width, np.float64)
    column_counts = np.empty((len(rows), width), np.uint64)
    column_abrupt = np.empty((len(rows), width), np.float64)
    for e in range(height + 2 * half + 1):
        for i in range(len(rows)):
            if rows[i] == e:
                for x in range(width):
                    column_counts[i, x] = np.uint64(0) - running_counts[x]
                    column_abrupt[i, x] = -running_abrupt[x]
            if rows[i] + size == e:
                for x in range(width):
                    column_counts[i, x] += running_counts[x]
                    column_abrupt[i, x] += running_abrupt[x]
        if e < height + 2 * half:
            y = _reflected(e - half, height)
            for x in range(width):
                running_counts[x] += _packed(counted, y, x)
                running_abrupt[x] += abrupt[y, x]
    lane = np.uint64((1 << _LANE) - 1)
    prefix_counts = np.empty(width + 2 * half + 1, np.uint64)
    prefix_abrupt = np.empty(width + 2 * half + 1, np.float64)
    for i in range(len(rows)):
        prefix_counts[0], prefix_abrupt[0] = 0, 0.0
        for e in range(width + 2 * half):
            x = _reflected(e - half, width)
            prefix_counts[e + 1] = prefix_counts[e] + column_counts[i, x]
            prefix_abrupt[e + 1] = prefix_abrupt[e] + column_abrupt[i, x]
        for j in range(len(cols)):
            counts = prefix_counts[cols[j] + size] - prefix_counts[cols[j]]
            values = (
                float(counts & lane),
                prefix_abrupt[cols[j] + size] - prefix_abrupt[cols[j]],
                float((counts >> _LANE) & lane),
                float((counts >> 2 * _LANE) & lane),
                float((counts >> 3 * _LANE) & lane),
            )
            for k in range(5):
                out[i, j, k] = min(max(np.float32(values[k] * scale), np.float32(0.0)), np.float32(1.0))


def densities_at(kinds: PixelKinds, window: int, rows: np.ndarray, cols: np.ndarray) -> np.ndarray:
    """The five descriptors at the pixels of a grid, ``densities(kinds, window)[np.ix_(rows, cols)]``.

    Only the grid's values are computed, by :func:`_grid_window_sums`: the
    normalised box filter's sum of each layer over a square is exact, and
    so is that function's, so both scale the same number the same way.

    Parameters
    ----------
    kinds : PixelKinds
        The pixels each descriptor counts.
    window : int
        Side of the neighbourhood, px (even values rounded up to odd), at most 255.
    rows, cols : numpy.ndarray
        Indices of the grid's rows and columns.

    Returns
    -------
    numpy.ndarray
        ``float32`` array of shape ``(len(rows), len(cols), 5)`` with values in ``[0, 1]``, in the order of
        :data:`NAMES`.
    """
    counted = tuple(np.ascontiguousarray(layer).view(np.uint8) for layer in (kinds.straight, kinds.ends, kinds.specks, kinds.soft))
    out = np.empty((len(rows), len(cols), len(NAMES)), np.float32)
    _grid_window_sums(
        counted,
        np.ascontiguousarray(kinds.abrupt, dtype=np.float32),
        _odd(window),
        np.asarray(rows, np.intp),
        np.asarray(cols, np.intp),
        out,
    )
    return out


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
