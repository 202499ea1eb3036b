"""Canny's hysteresis thresholds: the paper's fixed pair, or that pair lowered to each frame's gradients.

seeds/004 applies "the Canny filter [23]" without giving its thresholds;
the fixed pair ``(canny_low, canny_high) = (20, 60)`` on the L2 Sobel
gradient of the smoothed image (steps of about 10 and 30 grey levels) was
chosen on the camera suite.  A murky frame whose pipe stands 20-30 grey
levels out of the seabed never reaches the high threshold, and Canny then
keeps none of the border's edges, however straight and long they are.

Two rules, named by ``FeatureParams.canny_rule``:

``"fixed"``
    the pair as given, on every frame (the paper's reading);
``"percentile"``
    the pair scaled by ``min(1, P / canny_high)``, with ``P`` the
    ``canny_percentile``-th percentile of the frame's own gradient
    magnitude: a frame whose gradients are weaker than the pair assumes
    gets thresholds in proportion (their ratio, 1 : 3, stays the pair's),
    a frame as contrasted as the suite keeps the pair.  The percentile is
    taken over every second row and column, a regular grid of a quarter of
    the pixels: on 319 frames of camera-train and camera-dev (both frame
    sizes) it differs from the whole frame's by at most 4.5 % and costs
    0.9 ms a frame against 4.4 ms.

The rule only ever lowers the pair.  Raising it where a frame's gradients
are stronger (a textured seabed, overgrowth) loses the borders of the
overgrown sequences: with the percentile alone, no ceiling (``high = P``,
``low = P / 3``), every fourth frame of the camera suite and its clutter
family is 73.0 % correct against 86.7 % with the ceiling, camera-train
75.5 against 77.4 % (camera-dev 77.2 against 76.5 %;
:mod:`trackbench_foresti.params`).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Literal

import numpy as np


ThresholdRuleName = Literal["fixed", "percentile"]
"""The names of :data:`THRESHOLD_RULES`."""

ThresholdRule = Callable[[np.ndarray, np.ndarray, float, float, float], tuple[float, float]]
"""``(gu, gv, low, high, percentile) -> (low, high)``: a frame's Sobel derivatives and the configured pair."""


def fixed_thresholds(gu: np.ndarray, gv: np.ndarray, low: float, high: float, percentile: float) -> tuple[float, float]:
    """The configured pair ``(low, high)``, whatever the frame.

    References
    ----------
    seeds/004, section IV (the Canny filter [23]; the values are not given).
    """
    return low, high


def gradient_percentile(gu: np.ndarray, gv: np.ndarray, percentile: float) -> float:
    """The ``percentile``-th percentile of the L2 gradient magnitude over every second row and column.

    The percentile is the order statistic of rank ``floor(percentile (n - 1) / 100)`` among the ``n``
    sampled magnitudes (no interpolation), found on their exact integer squares.

    Parameters
    ----------
    gu, gv : numpy.ndarray
        ``int16`` Sobel derivatives of shape ``(H, W)``
        (:func:`trackbench_foresti.edges.smoothed_gradient`), at most ``2^11`` in magnitude.
    percentile : float
        In ``[0, 100]``.

    Returns
    -------
    float
        In the units of the gradient (Sobel units, about ``3.2`` times a
        step's height in grey levels over the smoothing's ``sigma`` in px).
    """
    if not 0 <= percentile <= 100:
        raise ValueError(f"percentile must be in [0, 100], got {percentile}")
    if gu.shape != gv.shape or gu.ndim != 2 or gu.size == 0:
        raise ValueError(f"gu and gv must be non-empty 2-D arrays of one shape, got {gu.shape} and {gv.shape}")
    across, down = gu[::2, ::2].astype(np.int32), gv[::2, ::2].astype(np.int32)
    squares = (across * across + down * down).ravel()
    rank = int(percentile * (squares.size - 1) // 100)
    return float(np.sqrt(np.partition(squares, rank)[rank]))


def percentile_thresholds(
    gu: np.ndarray, gv: np.ndarray, low: float, high: float, percentile: float
) -> tuple[float, float]:
    """The pair ``(low, high)`` scaled by ``min(1, P / high)``, ``P`` the frame's gradient percentile.

    Parameters
    ----------
    gu, gv : numpy.ndarray
        ``int16`` Sobel derivatives of the smoothed frame.
    low, high : float
        The configured pair, ``0 <= low <= high``: the ceiling.
    percentile : float
        Which percentile of the gradient magnitude ``P`` is (:func:`gradient_percentile`).

    Returns
    -------
    tuple of float
        ``(low s, high s)`` with ``s = min(1, P / high)`` (1 when ``high`` is 0).

    References
    ----------
    seeds/004, section IV (the Canny filter [23]); the rule is ours, see the module docstring.
    """
    if not 0 <= low <= high:
        raise ValueError(f"Canny thresholds must satisfy 0 <= low <= high, got low={low}, high={high}")
    if high == 0:
        return low, high
    scale = min(1.0, gradient_percentile(gu, gv, percentile) / high)
    return low * scale, high * scale


THRESHOLD_RULES: dict[str, ThresholdRule] = {"fixed": fixed_thresholds, "percentile": percentile_thresholds}
"""The threshold rules by name (``FeatureParams.canny_rule``)."""
