"""The one-dimensional edge filter applied across each hypothetical border.

The observation model of the thesis (seeds/000, section 4.5) measures the
grey-level change across a border with a derivative of Gaussian,

    f(x) = -x / (sigma^3 sqrt(2 pi)) exp(-x^2 / (2 sigma^2)),      (eq. 4.10)

sampled at the integer offsets ``x = -r .. r`` of a window of
``filter size = 2 r + 1`` px laid perpendicular to the border (Fig. 4.7).

The thesis gives the window size, not sigma, as its parameter, and quotes
``sigma ~ 1.6`` for 11 px (Table 5.1).  We tie the two by

    sigma = filter size / 7,

a window seven standard deviations wide, ``+-3.5 sigma`` (1.57 px for
11 px, 0.71 px for the 5 px of the high-speed experiment, section 5.2.5).

The taps are scaled so that the offsets ``x < 0`` sum to one: an ideal step
that is ``h`` grey levels brighter on the negative side than on the positive
side gives the response ``h``.  Border scores are therefore sums of step
heights in grey levels, whatever the filter size, which keeps the
likelihoods of different filter sizes comparable.  The sign is that of
eq. (4.10): positive when the image is brighter behind the filter's
direction than ahead of it.
"""

from __future__ import annotations

import math

import numpy as np


def dog_sigma(filter_size_px: int) -> float:
    """Standard deviation of the derivative of Gaussian for a window size.

    Parameters
    ----------
    filter_size_px : int
        Window size in px, odd and at least 3.

    Returns
    -------
    float
        ``filter_size_px / 7`` in px: 1.57 for the thesis' 11 px.

    References
    ----------
    seeds/000, Table 5.1 ("11 (sigma ~ 1.6)").
    """
    _check_size(filter_size_px)
    return filter_size_px / 7.0


def dog_taps(filter_size_px: int) -> np.ndarray:
    """The derivative-of-Gaussian taps at offsets ``-r .. r``, unit step response.

    Parameters
    ----------
    filter_size_px : int
        Window size ``2 r + 1`` in px, odd and at least 3.

    Returns
    -------
    numpy.ndarray
        ``float64`` array of ``filter_size_px`` taps: eq. (4.10) at the
        integer offsets, scaled so that the taps at negative offsets sum to 1.
        The taps are odd, ``taps[r + x] = -taps[r - x]``.

    Raises
    ------
    ValueError
        If the size is even or below 3.

    References
    ----------
    seeds/000, eq. (4.10) and Fig. 4.8.
    """
    sigma = dog_sigma(filter_size_px)
    radius = (filter_size_px - 1) // 2
    x = np.arange(-radius, radius + 1, dtype=float)
    taps = -x / (sigma**3 * math.sqrt(2.0 * math.pi)) * np.exp(-0.5 * (x / sigma) ** 2)
    return taps / taps[:radius].sum()


def _check_size(filter_size_px: int) -> None:
    if int(filter_size_px) != filter_size_px or filter_size_px < 3 or filter_size_px % 2 == 0:
        raise ValueError(f"filter size must be an odd number of px >= 3, got {filter_size_px}")
