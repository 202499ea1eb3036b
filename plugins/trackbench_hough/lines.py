"""Straight lines from the edge image: the Hough transform and its bookkeeping.

The Hough transform for lines (seeds/000, section 2.1; seeds/004,
section IV) votes every edge pixel into a ``(rho, theta)`` accumulator;
OpenCV's ``HoughLinesWithAccumulator`` returns the local maxima above a vote
threshold together with their votes.  OpenCV's ``(rho, theta)`` are pixel
coordinates with the origin at the top-left pixel centre:
``u cos(theta) + v sin(theta) = rho``, ``theta`` in ``[0, pi)``.

The tracker compares lines in a centred normal form instead,
``x cos(phi) + y sin(phi) = r`` in model coordinates (origin at the image
centre, ``y`` up; conventions.md section 1) with ``phi`` in
``(-pi/2, pi/2]``.  There a near-vertical line, the usual cable border, has
``phi`` near 0 and ``r`` its signed horizontal offset from the centre, so
distances in ``(r, phi)`` stay meaningful where OpenCV's ``theta`` wraps from
``pi`` to 0.  A search window in ``phi`` is translated back into one or two
``theta`` intervals, which is how the transform is limited around a
previous result (seeds/000, section 2.1, after Balasuriya et al.).

The accumulator's local maxima still come in clusters along one blurred
edge; :func:`distinct_lines` keeps the strongest line of each cluster
so that the two borders of a pair are two different edges.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import cv2
import numpy as np

from benchmark.lazy import lazy_module
from benchmark.modalities.camera.geometry import ImageSize, Line

# The compiled loops load on the first frame, so that listing the trackers does not import numba.
line_loops = lazy_module("trackbench_hough.line_loops")


def wrap_half_turn(angle: float) -> float:
    """Wrap an angle to ``(-pi/2, pi/2]``: line normals are equal modulo ``pi``."""
    wrapped = math.remainder(angle, math.pi)
    return math.pi / 2 if wrapped == -math.pi / 2 else wrapped


@dataclass(frozen=True, slots=True)
class HoughLine:
    """One accumulator maximum.

    Attributes
    ----------
    rho : float
        OpenCV distance in px from the top-left pixel centre.
    theta : float
        OpenCV normal angle in rad, in ``[0, pi)``.
    votes : float
        Accumulator value: the number of edge pixels on the line.
    r : float
        Signed distance in px of the line from the image centre, along
        ``(cos phi, sin phi)`` in model coordinates.
    phi : float
        Normal angle in model coordinates, in ``(-pi/2, pi/2]``.
    """

    rho: float
    theta: float
    votes: float
    r: float
    phi: float

    @classmethod
    def from_opencv(cls, rho: float, theta: float, votes: float, size: ImageSize) -> HoughLine:
        """Build a line from OpenCV's ``(rho, theta)`` and fill in ``(r, phi)``.

        In model coordinates ``u = x + (W-1)/2``, ``v = (H-1)/2 - y``, so the
        line reads ``x cos(theta) - y sin(theta) = rho - cu cos(theta) - cv
        sin(theta)``: normal angle ``-theta``, folded into ``(-pi/2, pi/2]``.
        """
        cu, cv = (size[0] - 1) / 2.0, (size[1] - 1) / 2.0
        r = rho - cu * math.cos(theta) - cv * math.sin(theta)
        phi = -theta
        if phi <= -math.pi / 2:
            phi, r = phi + math.pi, -r
        return cls(float(rho), float(theta), float(votes), float(r), float(phi))

    def line(self, size: ImageSize) -> Line:
        """The line in model coordinates (:class:`benchmark.modalities.camera.geometry.Line`)."""
        c, s = math.cos(self.theta), math.sin(self.theta)
        foot = (self.rho * c, self.rho * s)
        return Line.from_pixels(foot, (foot[0] - s, foot[1] + c), size)

    def distance_to(self, r: float, phi: float) -> tuple[float, float]:
        """Absolute differences ``(|dr|, |dphi|)`` to a line ``(r, phi)``, modulo the half turn."""
        dphi = self.phi - phi
        # wrap_half_turn(dphi), written out: this runs for every pair of lines compared.
        wrapped = math.remainder(dphi, math.pi)
        if wrapped == -math.pi / 2:
            wrapped = math.pi / 2
        # Wrapping by a half turn flips the other normal, and with it the sign of r.
        other_r = -r if abs(dphi - wrapped) > math.pi / 2 else r
        return abs(self.r - other_r), abs(wrapped)


def normal_form(line: Line) -> tuple[float, float]:
    """Centred normal form ``(r, phi)`` of a model-coordinate line, ``phi`` in ``(-pi/2, pi/2]``."""
    nx, ny = -line.dy, line.dx
    r = line.x0 * nx + line.y0 * ny
    phi = math.atan2(ny, nx)
    folded = wrap_half_turn(phi)
    return (r if abs(folded - phi) < math.pi / 2 else -r), folded


def theta_intervals(phi_low: float, phi_high: float) -> list[tuple[float, float]]:
    """OpenCV ``theta`` intervals that cover the model angles ``[phi_low, phi_high]``.

    Parameters
    ----------
    phi_low, phi_high : float
        A window of normal angles in rad with ``phi_low <= phi_high``; a
        window of ``pi`` or more covers every line.

    Returns
    -------
    list of (float, float)
        One or two ``(min_theta, max_theta)`` pairs inside ``[0, pi]``.
    """
    if phi_high - phi_low >= math.pi:
        return [(0.0, math.pi)]
    # theta = -phi modulo pi, so the window reverses and may wrap at 0 / pi.
    low = (-phi_high) % math.pi
    high = low + (phi_high - phi_low)
    if high <= math.pi:
        return [(low, high)]
    return [(low, math.pi), (0.0, high - math.pi)]


def hough_lines(
    edges: np.ndarray,
    rho_step: float,
    theta_step: float,
    min_votes: int,
    intervals: list[tuple[float, float]] | None = None,
) -> list[HoughLine]:
    """Lines of a binary edge image by the standard Hough transform.

    Parameters
    ----------
    edges : numpy.ndarray
        ``uint8`` binary image of shape ``(H, W)``; it is not modified.
    rho_step : float
        Accumulator resolution in distance, px.
    theta_step : float
        Accumulator resolution in angle, rad.
    min_votes : int
        Only lines with more votes than this are returned.
    intervals : list of (float, float), optional
        OpenCV ``theta`` intervals to search (:func:`theta_intervals`); the
        whole range ``[0, pi)`` when None.

    Returns
    -------
    list of HoughLine
        Most votes first; lines of equal votes in OpenCV's order, interval by interval.

    References
    ----------
    seeds/000, section 2.1 (Hough transform [HA62], limited parameter space);
    seeds/004, section IV (normal parametrisation, Fig. 7a).
    """
    raw = accumulator_maxima(edges, rho_step, theta_step, min_votes, intervals)
    # No tolerance: no line is another's duplicate, so every line is kept.
    return distinct_lines(raw, (edges.shape[1], edges.shape[0]), 0.0, 0.0, max(len(raw), 1))


def accumulator_maxima(
    edges: np.ndarray,
    rho_step: float,
    theta_step: float,
    min_votes: int,
    intervals: list[tuple[float, float]] | None = None,
) -> np.ndarray:
    """OpenCV's ``(rho, theta, votes)`` of the accumulator maxima above ``min_votes``, as OpenCV gives them.

    The transform without the bookkeeping, so that a caller that reads only
    the strongest few lines makes a :class:`HoughLine` of only those
    (:func:`distinct_lines`).  Parameters as :func:`hough_lines`.

    Returns
    -------
    numpy.ndarray
        ``float32`` array of shape ``(n, 3)``: each interval's maxima in
        OpenCV's order (most votes first), one interval after the other.

    References
    ----------
    seeds/000, section 2.1 (Hough transform [HA62], limited parameter space).
    """
    found = []
    for low, high in intervals or [(0.0, math.pi)]:
        if high - low < theta_step:
            low, high = max(0.0, 0.5 * (low + high) - theta_step), min(math.pi, 0.5 * (low + high) + theta_step)
        # OpenCV reads the edge image and does not write to it.
        raw = cv2.HoughLinesWithAccumulator(
            edges, rho_step, theta_step, int(min_votes), min_theta=float(low), max_theta=float(high)
        )
        if raw is not None:
            found.append(raw.reshape(-1, 3))
    if not found:
        return np.zeros((0, 3), np.float32)
    return found[0] if len(found) == 1 else np.concatenate(found)


def distinct_lines(
    raw: np.ndarray,
    size: ImageSize,
    r_tolerance: float,
    phi_tolerance: float,
    limit: int,
    borders: Sequence[tuple[float, float]] = (),
    r_half: float = math.inf,
    phi_half: float = math.inf,
) -> list[HoughLine]:
    """The strongest lines of the transform that a window admits, after non-maximum suppression in ``(r, phi)``.

    Walking from the strongest line down, a line is admitted when it lies
    within ``r_half`` px and ``phi_half`` rad of one of ``borders`` (every
    line when there are none), and dropped when a kept one lies within
    less than ``r_tolerance`` px and ``phi_tolerance`` rad of it.  The walk
    stops once ``limit`` lines are kept, which gives the first ``limit``
    lines of the whole walk.  One compiled loop
    (:func:`trackbench_hough.line_loops.distinct_lines`) makes the
    :class:`HoughLine` of only the lines kept.

    Parameters
    ----------
    raw : numpy.ndarray
        OpenCV's ``(rho, theta, votes)`` rows (:func:`accumulator_maxima`), read most
        votes first, lines of equal votes in their order.
    size : tuple of int
        Image ``(W, H)`` in px.
    r_tolerance : float
        Distance in px below which two lines are the same edge.
    phi_tolerance : float
        Angle in rad below which two lines are the same edge.
    limit : int
        Most lines to keep.
    borders : sequence of (float, float)
        ``(r, phi)`` of the borders a window is open around
        (:class:`trackbench_hough.window.SearchWindow`); empty: no window.
    r_half, phi_half : float
        The window's half-widths, px and rad.

    Returns
    -------
    list of HoughLine
        The kept lines, strongest first.

    References
    ----------
    seeds/000, section 2.1 (the limited parameter space of Balasuriya et al.).
    """
    rows = distinct_line_rows(raw, size, r_tolerance, phi_tolerance, limit, borders, r_half, phi_half)
    return [HoughLine(*row) for row in rows.tolist()]


def distinct_line_rows(
    raw: np.ndarray,
    size: ImageSize,
    r_tolerance: float,
    phi_tolerance: float,
    limit: int,
    borders: Sequence[tuple[float, float]] = (),
    r_half: float = math.inf,
    phi_half: float = math.inf,
) -> np.ndarray:
    """:func:`distinct_lines` as rows ``(rho, theta, votes, r, phi)``, ``float64``, for the compiled pairing
    (:func:`trackbench_hough.pairing.best_pair`); parameters as :func:`distinct_lines`."""
    cu, cv = (size[0] - 1) / 2.0, (size[1] - 1) / 2.0
    return line_loops.distinct_lines(
        np.ascontiguousarray(raw),
        cu,
        cv,
        np.array(borders, dtype=np.float64).reshape(-1, 2),
        float(r_half),
        float(phi_half),
        float(r_tolerance),
        float(phi_tolerance),
        int(limit),
    )


def compile_kernels() -> None:
    """Compile (or load from numba's cache) the loops of the lines and pairs now, before the first timed frame."""
    line_loops.compile_kernels()
