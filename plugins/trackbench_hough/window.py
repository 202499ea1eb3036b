"""The limited Hough parameter space used while a cable is being tracked.

"Once the cable is successfully detected, the search space for line
detection can be limited around the determined parameters, i.e. the Hough
transform has to be computed only for a small range of angles and
distances" (seeds/000, section 2.1, on Balasuriya et al. and Matsumoto and
Ito).  A :class:`SearchWindow` is that range: around each of the two
borders found last, ``r_half`` px in distance and ``phi_half`` rad in
angle, in the centred normal form of :mod:`trackbench_hough.lines`.

The window restricts the transform itself to the ``theta`` range spanned by
the two borders (:meth:`SearchWindow.theta_intervals`) and then admits only
lines within the distance range (:meth:`SearchWindow.admits`).  A new pair
must have one border in the window of each previous border
(:meth:`SearchWindow.deviation`).

Only edge pixels near the two borders can vote for a line the window
admits, so the edge image is needed only there
(:meth:`SearchWindow.voting_strips`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from benchmark.lazy import lazy_module
from benchmark.modalities.camera.geometry import Line
from trackbench_hough.lines import HoughLine, normal_form, theta_intervals, wrap_half_turn

# The compiled loops load on the first frame, so that listing the trackers does not import numba.
line_loops = lazy_module("trackbench_hough.line_loops")

STRIP_ROWS = 60
"""Rows of one strip of :meth:`SearchWindow.voting_strips`: on 640 x 480 frames, eight strips follow a slanted
cable closely enough (the zero-crossing loop sweeps them all in one call,
:func:`trackbench_hough.crossings.strong_crossings_in`)."""


@dataclass(frozen=True, slots=True)
class SearchWindow:
    """Search ranges around the two borders of the previous result.

    Attributes
    ----------
    borders : tuple of (float, float)
        ``(r, phi)`` of the two previous borders (centred normal form).
    r_half : float
        Half-width of the distance range, px.
    phi_half : float
        Half-width of the angle range, rad.
    """

    borders: tuple[tuple[float, float], tuple[float, float]]
    r_half: float
    phi_half: float

    @classmethod
    def around(cls, first: HoughLine, second: HoughLine, r_half: float, phi_half: float) -> SearchWindow:
        """The window around a detected pair of Hough lines."""
        return cls(((first.r, first.phi), (second.r, second.phi)), r_half, phi_half)

    @classmethod
    def around_borders(cls, borders: tuple[Line, Line], r_half: float, phi_half: float) -> SearchWindow:
        """The window around two border lines in model coordinates (e.g. an initial state)."""
        return cls((normal_form(borders[0]), normal_form(borders[1])), r_half, phi_half)

    def bounds(self) -> tuple[Line, ...]:
        """The lines ``r -+ r_half`` at each border's angle: the two bands the window admits at that angle."""
        return tuple(Line.from_normal(r + side * self.r_half, phi) for r, phi in self.borders for side in (-1, 1))

    def theta_intervals(self) -> list[tuple[float, float]]:
        """OpenCV ``theta`` intervals covering both borders' angle ranges.

        References
        ----------
        seeds/000, section 2.1: the transform is computed only for a small
        range of angles.
        """
        (_, phi_a), (_, phi_b) = self.borders
        # The borders are nearly parallel: take phi_b relative to phi_a across the wrap.
        delta = wrap_half_turn(phi_b - phi_a)
        low, high = phi_a + min(0.0, delta), phi_a + max(0.0, delta)
        return theta_intervals(low - self.phi_half, high + self.phi_half)

    def _within(self, line: HoughLine, border: tuple[float, float]) -> tuple[float, float] | None:
        dr, dphi = line.distance_to(*border)
        if dr <= self.r_half and dphi <= self.phi_half:
            return dr / self.r_half, dphi / self.phi_half
        return None

    def admits(self, line: HoughLine) -> bool:
        """True when the line lies in the window of either previous border."""
        first, second = self.borders
        return self._within(line, first) is not None or self._within(line, second) is not None

    def fits(self, line: HoughLine) -> tuple[tuple[float, float] | None, tuple[float, float] | None]:
        """The line's normalised offsets ``(|dr| / r_half, |dphi| / phi_half)`` from each previous border.

        None for a border whose window the line lies outside.  A line takes
        part in many candidate pairs; its fits are computed once and handed
        to :meth:`deviation_of_fits`.
        """
        first, second = self.borders
        return self._within(line, first), self._within(line, second)

    def deviation(self, first: HoughLine, second: HoughLine) -> float | None:
        """How far a candidate pair lies from the previous pair, or None if outside.

        The two lines are matched to the two previous borders in the order
        that fits; the deviation is the largest normalised offset, in
        ``[0, 1]`` (0: exactly the previous pair, 1: at the window's edge).
        """
        return self.deviation_of_fits(self.fits(first), self.fits(second))

    @staticmethod
    def deviation_of_fits(
        first: tuple[tuple[float, float] | None, tuple[float, float] | None],
        second: tuple[tuple[float, float] | None, tuple[float, float] | None],
    ) -> float | None:
        """:meth:`deviation` of two lines from their :meth:`fits`."""
        best: float | None = None
        for fit_a, fit_b in ((first[0], second[1]), (second[0], first[1])):
            if fit_a is None or fit_b is None:
                continue
            worst = max(*fit_a, *fit_b)
            best = worst if best is None else min(best, worst)
        return best

    def voting_strips(self, size: tuple[int, int], rho_step: float, theta_step: float) -> np.ndarray:
        """Rectangles ``(row0, row1, col0, col1)``, ends excluded, holding every pixel that can vote for a line admitted.

        HoughLines keeps an accumulator cell when it beats its four
        neighbours, so the pixels that matter are those that vote for an
        admitted cell (:meth:`admits`) or a neighbour of one: a pixel ``p``
        (centred coordinates) votes for cell ``(r', phi')`` when
        ``|p . n(phi') - r'| <= rho_step / 2``, and such a cell has
        ``|r' - r| <= r_half + rho_step + c theta_step`` and
        ``|phi' - phi| <= phi_half + theta_step`` for a border ``(r, phi)``,
        where ``c`` is the half diagonal (a neighbour in angle keeps OpenCV's
        ``rho``, which moves the centred ``r`` by at most ``c theta_step``).  Since
        ``|p . (n(phi) - n(phi'))| <= |p| |phi - phi'|`` and ``|p| <= c``,
        every such pixel lies within

            D = r_half + 1.5 rho_step + c theta_step + 1 + c (phi_half + theta_step)

        of a border line (1 px more for rounding).  Each strip of
        :data:`STRIP_ROWS` rows is the columns of its rows within ``D`` of
        either border, plus one column each side.

        Parameters
        ----------
        size : tuple of int
            ``(W, H)`` of the frame, px.
        rho_step, theta_step : float
            The accumulator's steps, px and rad.

        Returns
        -------
        numpy.ndarray
            ``int64`` rows ``(row0, row1, col0, col1)`` of non-empty
            rectangles, top to bottom
            (:func:`trackbench_hough.line_loops.voting_strips`).

        References
        ----------
        seeds/000, section 2.1: the transform is computed only for a small
        range of angles and distances around the previous result.
        """
        width, height = size
        half_diagonal = math.hypot((width - 1) / 2.0, (height - 1) / 2.0)
        reach = (
            self.r_half
            + 1.5 * rho_step
            + half_diagonal * theta_step
            + 1.0
            + half_diagonal * (self.phi_half + theta_step)
        )
        # Per border, the columns within reach of its line at pixel row v are an interval whose ends are
        # linear in v (cos(phi) > 0), so a strip's extremes are at its first and last rows.
        return line_loops.voting_strips(np.array(self.borders, np.float64), reach, width, height, STRIP_ROWS)
