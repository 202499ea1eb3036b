"""How strong a zero crossing must be to count as a border: a fixed step, or one the frame sets.

Seeds/000, section 2.1 binarises the LoG edge image "so that only strong
borders survive" and gives no value.  A rule here turns the parameters into
that threshold, a step height in grey levels
(:func:`trackbench_hough.edges.zero_crossings`), for one frame:

``"step"``
    a fixed step, ``edge_step`` grey levels, whatever the frame shows: the
    reading the benchmark started from, kept for ``hough-paper``;
``"median"``
    ``edge_ratio`` times the median step of the frame's own zero crossings
    (:func:`trackbench_hough.edges.median_crossing_step`).  Most zero crossings
    of a frame belong to sensor noise and seabed texture, so their median
    says how strong an unremarkable edge of this frame is, and a border
    survives when it stands out of them.  Scaling a frame's grey levels
    (a murkier water, a weaker lamp, another camera gain) scales the median
    with the borders, so the same borders survive; a fixed step loses them.

:data:`EDGE_THRESHOLDS` maps the names :data:`trackbench_hough.params.EdgeRule`
allows to their functions.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping

import numpy as np

from trackbench_hough.edges import median_crossing_step
from trackbench_hough.params import EdgeRule, HoughParams

MEDIAN_STRIDE = 4
"""Rows and columns between those whose crossings give the median: on a 640 x 480 frame of
camera-dev/d04 the median of every fourth row's and column's 19 000 crossings is within 0.03 %
of that of all 77 000, at a third of the cost."""

EdgeThreshold = Callable[[np.ndarray, float, HoughParams], float]
"""``(response, sigma, params) -> smallest step in grey levels`` of a border in this frame."""


def fixed_step(response: np.ndarray, sigma: float, params: HoughParams) -> float:
    """The fixed threshold ``params.edge_step``, in grey levels.

    References
    ----------
    seeds/000, section 2.1: thresholding keeps only strong borders.
    """
    return params.edge_step


def median_step(response: np.ndarray, sigma: float, params: HoughParams) -> float:
    """``params.edge_ratio`` times the median step height of the frame's zero crossings.

    Parameters
    ----------
    response : numpy.ndarray
        The frame's LoG response (:func:`trackbench_hough.edges.log_response`).
    sigma : float
        Its ``sigma``, px.
    params : HoughParams
        Supplies ``edge_ratio``.

    Returns
    -------
    float
        The threshold in grey levels; 0 for a frame without zero crossings.

    References
    ----------
    seeds/000, section 2.1 (LoG zero crossings, thresholded to keep strong borders).
    """
    median = median_crossing_step(response, sigma, MEDIAN_STRIDE)
    return 0.0 if median is None else params.edge_ratio * median


EDGE_THRESHOLDS: Mapping[EdgeRule, EdgeThreshold] = {"step": fixed_step, "median": median_step}
"""The edge-threshold rules by name."""
