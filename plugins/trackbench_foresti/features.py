"""The feature extraction module of seeds/004, section IV (Fig. 6).

Three submodules find "the two straight lines corresponding to the
external edges of the pipeline in the observed image": edge extraction
(:mod:`trackbench_foresti.edges`), straight-line extraction
(:mod:`trackbench_foresti.hough`, :mod:`trackbench_foresti.domains`,
:mod:`trackbench_foresti.reliability`) and straight-line grouping
(:mod:`trackbench_foresti.grouping`).  :class:`FeatureExtractor` chains
them; its :meth:`FeatureExtractor.measure` gives the pair of borders whose
abscissae on the first and last image rows are the EKF's measure
``z = (i1, i2, i3, i4)`` (Fig. 4).

Line parametrisation
--------------------
A :class:`CandidateLine` is ``x cos(alpha) + y sin(alpha) = rho`` in the
model coordinates of conventions.md section 1: origin at the image centre,
``x`` right, ``y`` up, so ``x = u - (W-1)/2`` and ``y = (H-1)/2 - v``.
``alpha`` is in rad in ``[-pi/2, pi/2)``, ``rho`` in px and signed.  A
vertical line has ``alpha = 0`` and ``rho`` equal to its offset right of
the image centre; ``alpha > 0`` turns the line counter-clockwise (its top
leans left).  This is the normal form of the cable centreline in
conventions.md, ``p . (cos alpha, sin alpha) = d``: a centreline
``(d, alpha)`` is the line ``(alpha, rho = d)``.  The line is
``geometry.Line.from_normal(rho, alpha)``.  (seeds/004's Tables I-II
measure from the top-left corner with ``alpha`` in ``[0, 180)`` deg; see
:mod:`trackbench_foresti.hough` for the conversion.)

Defaults
--------
The parameters are the flat fields of
:class:`~trackbench_foresti.params.FeatureParams`; where their defaults
come from, and the evidence for each departure from the paper, is in
:mod:`trackbench_foresti.params`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from benchmark.lazy import lazy_module
from benchmark.modalities.camera.geometry import ImageSize, Line
from benchmark.modalities.camera.io.video import check_grey_image
from trackbench_foresti.edges import EdgeMap, as_grey, canny_from_gradient, smoothed_gradient
from trackbench_foresti.grouping import choose_pair
from trackbench_foresti.params import FeatureParams
from trackbench_foresti.reliability import is_reliable, length_and_robustness, reliability, strength
from trackbench_foresti.thresholds import THRESHOLD_RULES

# The numba kernels load on the first frame, so that listing the trackers does not import numba.
domains = lazy_module("trackbench_foresti.domains")
hough = lazy_module("trackbench_foresti.hough")

__all__ = ["CandidateLine", "FeatureExtractor", "FeatureParams", "as_grey", "compile_kernels"]


@dataclass(frozen=True, eq=False)
class CandidateLine:
    """A straight line that survived the filtering of seeds/004, section IV.

    Attributes
    ----------
    alpha : float
        Normal angle in rad, in ``[-pi/2, pi/2)``, model coordinates (module docstring).
    rho : float
        Signed distance in px from the image centre along ``(cos alpha, sin alpha)``.
    modulus : float
        Mean gradient modulus ``M`` of the edges that vote for the line.
    domain : numpy.ndarray
        The restored ``bool`` domain ``dom[i]``: over rows ``v = i`` when
        :attr:`by_rows`, over columns ``u = i`` otherwise.
    pl, pr, pf : float
        Length, robustness and strength, eqs. (6a)-(6c).
    reliability : float
        ``Lambda``, eq. (6d).
    polarity : int
        +1 when the grey level rises across the line along its normal
        ``(cos alpha, sin alpha)`` (its edges' phases point that way), -1
        when it falls, 0 when unknown.
    """

    alpha: float
    rho: float
    modulus: float
    domain: np.ndarray = field(repr=False)
    pl: float
    pr: float
    pf: float
    reliability: float
    polarity: int = 0

    @property
    def by_rows(self) -> bool:
        """True when the line is within 45 deg of vertical, so its domain runs over rows."""
        return abs((self.alpha + math.pi / 2) % math.pi - math.pi / 2) <= math.pi / 4 + 1e-12

    def line(self, size: ImageSize) -> Line:
        """The line in model coordinates, ``Line.from_normal(rho, alpha)``.

        ``size`` is not needed by the model-coordinate line; it is taken so
        that every conversion of a candidate names the image it lives in.
        """
        _check_size(size)
        return Line.from_normal(self.rho, self.alpha)

    def abscissae(self, size: ImageSize) -> tuple[float, float]:
        """Pixel columns ``u`` where the line crosses the first row ``v = 0`` and the last row ``v = H-1``.

        These are the EKF's measures ``i1``/``i2`` and ``i3``/``i4`` (Fig. 4).

        Raises
        ------
        ValueError
            For a line parallel to the rows (``cos(alpha) == 0``).
        """
        width, height = _check_size(size)
        c, s = math.cos(self.alpha), math.sin(self.alpha)
        if abs(c) < 1e-12:
            raise ValueError(f"a horizontal line (alpha={self.alpha}) does not cross the rows at one column")
        half_w, half_h = (width - 1) / 2.0, (height - 1) / 2.0
        return tuple(half_w + (self.rho - y * s) / c for y in (half_h, -half_h))  # type: ignore[return-value]


def _check_size(size: ImageSize) -> tuple[int, int]:
    if len(size) != 2 or not all(isinstance(n, (int, np.integer)) and n > 1 for n in size):
        raise ValueError(f"size must be (W, H) with integers > 1, got {size}")
    return int(size[0]), int(size[1])


class FeatureExtractor:
    """Finds the pipeline's two border lines in a grey image (seeds/004, section IV, Fig. 6).

    Parameters
    ----------
    params : FeatureParams, optional
        Thresholds; the defaults when omitted.
    """

    def __init__(self, params: FeatureParams | None = None) -> None:
        self.params = params if params is not None else FeatureParams()
        self._hough = self.params.hough
        self._grouping = self.params.grouping

    def edges(self, image: np.ndarray) -> EdgeMap:
        """Canny edges with modulus and phase of a ``uint8`` grey image of shape ``(H, W)``.

        The hysteresis thresholds follow ``canny_rule`` (:mod:`trackbench_foresti.thresholds`).
        """
        p = self.params
        gu, gv = smoothed_gradient(image, p.blur_sigma_px)
        low, high = THRESHOLD_RULES[p.canny_rule](gu, gv, p.canny_low, p.canny_high, p.canny_percentile)
        return canny_from_gradient(gu, gv, low, high)

    def _hough_for(self, height: int) -> dict[str, Any]:
        """The transform's keyword arguments for a frame of ``height`` rows: ``min_votes`` scaled to it."""
        return {**self._hough, "min_votes": self.params.scaled_count(self.params.min_votes, height)}

    def candidates(self, image: np.ndarray) -> list[CandidateLine]:
        """The candidate set ``R``: lines with ``PL > min_pl`` and ``PR > min_pr``, most reliable first.

        ``min_votes``, ``max_gap`` and ``min_run`` are scaled to the frame's
        height (:meth:`~trackbench_foresti.params.FeatureParams.scaled_count`).

        ``PF`` (eq. 6c) is normalised over this filtered set: Tables I-II
        list only the surviving lines of Fig. 8(e)-(f) and each holds a
        ``PF`` of 1.00.

        Parameters
        ----------
        image : numpy.ndarray
            ``uint8`` grey image of shape ``(H, W)``.

        Returns
        -------
        list of CandidateLine
            Sorted by decreasing ``Lambda``.

        References
        ----------
        seeds/004, section IV, eqs. (5a)-(6d) and Fig. 8.
        """
        check_grey_image(image)
        p = self.params
        height = image.shape[0]
        found = hough.hough_lines(self.edges(image), **self._hough_for(height))
        max_gap, min_run = p.scaled_count(p.max_gap, height), p.scaled_count(p.min_run, height)
        kept = []
        for line in found:
            domain = domains.restore_domain(line.domain, max_gap, min_run)
            pl, pr = length_and_robustness(domain)
            if is_reliable(pl, pr, p.min_pl, p.min_pr):
                kept.append((line, domain, pl, pr))
        pfs = strength([line.modulus for line, *_ in kept])
        result = [
            CandidateLine(
                alpha=line.alpha,
                rho=line.rho,
                modulus=line.modulus,
                domain=domain,
                pl=pl,
                pr=pr,
                pf=float(pf),
                reliability=reliability(pl, pr, float(pf), p.weights),
                polarity=line.polarity,
            )
            for (line, domain, pl, pr), pf in zip(kept, pfs, strict=True)
        ]
        result.sort(key=lambda c: -c.reliability)
        return result

    def measure(
        self,
        image: np.ndarray,
        predicted: tuple[float, float, float, float] | np.ndarray | None = None,
        spread: np.ndarray | None = None,
    ) -> tuple[CandidateLine, CandidateLine] | None:
        """The pipeline's borders ``(left, right)`` in an image, or None.

        Parameters
        ----------
        image : numpy.ndarray
            ``uint8`` grey image of shape ``(H, W)``.
        predicted : sequence of 4 float, optional
            The EKF's predicted abscissae ``(i1, i2, i3, i4)``: pixel columns
            where the left and right borders cross the first row ``v = 0``
            (``i1``, ``i2``) and the last row ``v = H-1`` (``i3``, ``i4``).
        spread : numpy.ndarray, optional
            ``(4, 4)`` covariance of ``predicted`` (the EKF's innovation
            covariance): the nearest pair is then found and gated by
            Mahalanobis distance (:func:`~trackbench_foresti.grouping.choose_pair`).

        Returns
        -------
        tuple of CandidateLine or None
            Left and right border; None when no compatible pair qualifies
            (seeds/004: "the feature extraction module cannot provide
            measurements to the EKF").

        References
        ----------
        seeds/004, section IV (grouping) and Fig. 4.
        """
        check_grey_image(image)
        size = (image.shape[1], image.shape[0])
        return choose_pair(self.candidates(image), size, predicted, self._grouping, spread)


def compile_kernels() -> None:
    """Compile (or load from numba's cache) the kernels of the Hough transform and the domain restoration now.

    Trackers call this before their first timed frame, so that frames per
    second measure the extractor rather than the compiler.
    """
    hough.compile_kernels()
    domains.compile_kernels()
