"""The region of interest's pixels in one compiled pass (:func:`trackbench_segmentation.tracking.region_of_interest`)."""

from __future__ import annotations

import numba
import numpy as np


@numba.njit(cache=True, nogil=True)
def band_mask(d: float, cos_alpha: float, sin_alpha: float, half_width: float, width: int, height: int) -> np.ndarray:
    """The pixels of a ``width`` x ``height`` image within ``half_width`` of the line ``x cos + y sin = d``.

    In ``float32``, pixel by pixel as numpy broadcasts
    ``abs(x * cos + y * sin - d) <= half_width`` over the image's model
    coordinates ``x = u - (W-1)/2``, ``y = (H-1)/2 - v`` in ``float32``, the
    Python floats ``d`` and ``half_width`` taken in ``float32`` as numpy
    takes them.
    """
    x_centre = np.float32((width - 1) / 2.0)
    y_centre = np.float32((height - 1) / 2.0)
    cos32, sin32 = np.float32(cos_alpha), np.float32(sin_alpha)
    d32, limit = np.float32(d), np.float32(half_width)
    mask = np.empty((height, width), dtype=np.bool_)
    for r in range(height):
        along = (y_centre - np.float32(r)) * sin32
        for c in range(width):
            mask[r, c] = abs((np.float32(c) - x_centre) * cos32 + along - d32) <= limit
    return mask


def compile_kernels() -> None:
    """Compile (or load from numba's cache) the mask now, on a tiny image."""
    band_mask(0.0, 1.0, 0.0, 1.0, 4, 3)
