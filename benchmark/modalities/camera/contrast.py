"""How much the cable stands out of the seabed in an image: its contrast in grey levels.

Boards split results by the cable's contrast, so that a tracker's failures
on murky water are seen as such.  The measure needs only an image and the
true cable state: with ``e_l`` and ``e_r`` the signed distances of a pixel
from the left and right border lines (conventions.md section 1), measured
along their normals towards the cable's right, its position across the
cable is ``s = e_l / (e_l - e_r)``: 0 on the left border, 1 on the right.
The cable's grey level is the median over its central half
(``0.25 <= s <= 0.75``), the seabed's the median over two bands beside it
(``-0.75 <= s <= -0.25`` and ``1.25 <= s <= 1.75``), both on the pixels
where the cable is at least :data:`MIN_WIDTH_PX` wide; the contrast is the
absolute difference.  Medians keep a few bright particles or stones from
moving it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from benchmark.modalities.camera.geometry import Line, cable_borders
from benchmark.modalities.camera.model import CableState

MIN_WIDTH_PX = 2.0
"""Pixels where the borders are closer than this (near a skewed cable's apex) are not used."""

MIN_PIXELS = 12
"""Fewest pixels on the cable and on the seabed for a measurement."""

CABLE_BAND = (0.25, 0.75)
SEABED_BANDS = ((-0.75, -0.25), (1.25, 1.75))


@dataclass(frozen=True)
class CableContrast:
    """A contrast measurement.

    Attributes
    ----------
    contrast : float
        ``|cable_grey - seabed_grey|``.
    cable_grey, seabed_grey : float
        Median grey levels on the cable's central half and beside it.
    """

    contrast: float
    cable_grey: float
    seabed_grey: float


def _signed_distance(line: Line, x: np.ndarray, y: np.ndarray, towards: tuple[float, float]) -> np.ndarray:
    """Distance of model points from ``line`` along its normal that points (roughly) along ``towards``."""
    nx, ny = -line.dy, line.dx
    if nx * towards[0] + ny * towards[1] < 0:
        nx, ny = -nx, -ny
    return (x - line.x0) * nx + (y - line.y0) * ny


def measure_contrast(image: np.ndarray, state: CableState) -> CableContrast | None:
    """Grey levels on and beside the cable and their difference, or None where too few pixels show either.

    Parameters
    ----------
    image : numpy.ndarray
        A grey image ``(H, W)``, any real dtype.
    state : CableState
        The true cable state ``(d, alpha, w, beta)`` in the image.

    Returns
    -------
    CableContrast or None

    Raises
    ------
    ValueError
        For an image that is not 2-D or a state that is not fully known.
    """
    values = np.asarray(image, dtype=np.float64)
    if values.ndim != 2:
        raise ValueError(f"cable contrast needs a grey image (H, W), got shape {values.shape}")
    if not state.is_known:
        raise ValueError(f"cable contrast needs a known cable state, got {state}")
    height, width = values.shape
    x = np.arange(width, dtype=np.float64)[None, :] - (width - 1) / 2.0
    y = (height - 1) / 2.0 - np.arange(height, dtype=np.float64)[:, None]
    left, right = cable_borders(state)
    across = (math.cos(state.alpha), math.sin(state.alpha))
    e_left = _signed_distance(left, x, y, across)
    e_right = _signed_distance(right, x, y, across)
    local_width = e_left - e_right
    usable = local_width >= MIN_WIDTH_PX
    position = np.where(usable, e_left / np.where(usable, local_width, 1.0), np.nan)
    on_cable = usable & (position >= CABLE_BAND[0]) & (position <= CABLE_BAND[1])
    beside = np.zeros_like(on_cable)
    for low, high in SEABED_BANDS:
        beside |= usable & (position >= low) & (position <= high)
    if on_cable.sum() < MIN_PIXELS or beside.sum() < MIN_PIXELS:
        return None
    cable_grey = float(np.median(values[on_cable]))
    seabed_grey = float(np.median(values[beside]))
    return CableContrast(abs(cable_grey - seabed_grey), cable_grey, seabed_grey)


def cable_contrast(image: np.ndarray, state: CableState) -> float:
    """The cable's contrast in grey levels (:func:`measure_contrast`); NaN when it cannot be measured."""
    measured = measure_contrast(image, state)
    return math.nan if measured is None else measured.contrast


__all__ = ["CableContrast", "cable_contrast", "measure_contrast"]
