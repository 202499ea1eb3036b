"""Grouping candidate lines into the pipeline's two borders (seeds/004, section IV).

"During the grouping phase, only pairs of lines which are compatible with
the geometrical characteristic of the scene and the perspective laws are
considered.  For example, it is not possible that two candidate lines
representing the pipeline borders intersect or diverge.  Then, for each
compatible pair of lines, a grouping reliability parameter (Delta R), which
takes into account also the geometrical characteristics (symmetry,
convergence, etc.) of the lines, is computed."

Compatibility
-------------
Only lines within 45 deg of vertical (row domains) are paired: the EKF
measures where the borders cross the first and last image rows (Fig. 4),
and pipe borders in the benchmark's camera data stay within about 45 deg of
vertical.  With ``s_top`` and ``s_bottom`` the separations ``u_right -
u_left`` of a pair on the first row ``v = 0`` and the last row ``v = H-1``,
a pair (left, right) is compatible when

(a) it does not intersect inside the image: we ask more, ``s_top > 0`` and
    ``s_bottom > 0``, i.e. no crossing anywhere within the image's rows,
    since a pair crossing beside the image would swap left and right
    between the measures ``i1, i2`` and ``i3, i4``;
(b) it does not diverge towards the top: a forward-looking camera sees the
    borders converge towards the pipe's vanishing point above the image,
    so the separation must not shrink towards the bottom, ``s_top <=
    s_bottom``.  Addition: a slack of ``(H-1) tan(max_divergence)`` px is
    allowed, because the accumulator quantises angles and two parallel
    borders may come out one bin apart;
(c) the left line is left of the right one on the last row, ``s_bottom > 0``;
(d) the pair bounds a band: the pipe is darker or brighter than the seabed
    around it, so the grey level steps one way across one border and the
    other way across the other, and the Canny phases ``F(k)`` of their
    edges point in opposite directions along the lines' normals
    (:attr:`~trackbench_foresti.features.CandidateLine.polarity`; a line
    whose polarity is unknown, 0, passes).  This is the scene's geometry
    the paper asks pairs to fit, and the test eq. (4.11) of seeds/000 makes
    of a cable's borders.  Sand ripples make long parallel lines whose
    neighbours often step the same way; without (d), while S7's pipe was
    buried the EKF (``Q`` per frame as printed) took such pairs for it and
    followed them (S7: 43.3 %
    correct, 56.7 % false) and the extractor alone reported them on 49.3 %
    of S7's frames; with (d) the EKF is 64.7 % correct on S7 and the
    extractor reports a wrong pair on 12.0 %; no other sequence of the
    camera suite or the clutter family changed.

Grouping reliability (our reading)
----------------------------------
The paper names the ingredients of ``Delta R`` but gives no formula.  We use

    Delta R = (Lambda_left + Lambda_right) / 2 * S * C

* ``S``, symmetry: the two borders of one pipe are seen over the same rows
  (both leave the image at the same places and sand or an obstacle tends
  to hide both), while two unrelated lines are not.  With the row spans
  ``[d1, d2]`` of the two domains (eqs. 5a-5b), ``S = (1 + IoU) / 2`` where
  ``IoU`` is their intersection over union.  The other reading of symmetry,
  equal angles of the two lines about the pair's bisector, holds for every
  pair by construction of the bisector and so could not rank pairs.
* ``C``, convergence: with ``r = s_top / s_bottom`` (1 for parallel
  borders, 0 when they meet on the first row),
  ``C = 1/2 + 1/2 min(1, r / meet_ratio)`` for ``0 <= r <= 1`` and
  ``C = 1/2`` for ``r > 1`` (diverging, within the slack of rule b).  It is
  1 for borders that converge towards a vanishing point above the image or
  are parallel, and falls to 1/2 for borders that diverge or nearly meet
  inside the image (``r < meet_ratio = 0.25``: a vertex less than a third
  of the image height above the first row).  Parallel borders are not
  penalised: a camera looking down sees them, the true borders of the
  benchmark's pipes have ``r`` from 0.32 to 0.97 (camera/S6), and an angle
  error of 0.5 deg on each border moves ``r`` of a 35 px wide pipe by
  about 0.1.  A term peaking at ``r = 1/2`` (``(1 + 4 r (1 - r)) / 2``)
  made 107 of the 499 frames of camera/S2 false.

Both factors lie in ``[1/2, 1]``, so they rank pairs of similarly reliable
lines without overruling ``Lambda``, and ``Delta R`` lies in ``[0, 1]``.
On camera/S2-S4 (1080 frames) ``S`` and ``C`` change nothing against the
mean ``Lambda`` alone (99.8 % correct without a prediction); on S7, where
sand ripples compete with a partly buried pipe, ``S`` costs 6 of 150
frames.  We keep both as the paper's named ingredients.

Selection
---------
"The prediction of the position of the searched lines (when it is
available by the EKF), is also used to choose the best pair of lines among
the compatible pairs characterized by a high reliability parameter.  When
the position of the sought lines cannot be predicted, the compatible pair of
lines with the highest grouping reliability parameter, is selected."  With
a prediction, the pairs with ``Delta R >= min_pair_reliability`` compete on
the sum of squared differences between their abscissae and the predicted
``(i1, i2, i3, i4)``.  Addition: the nearest pair is rejected when it lies
outside a gate, so that a frame whose borders are hidden yields no measure
rather than a wrong one (the paper then lets the EKF run on the inertial
data alone).  When the EKF gives the covariance ``S = G P G^T + R`` of its
predicted abscissae, "nearest" is the Mahalanobis distance
``r^T S^-1 r`` and the gate is its ``gate_chi2`` quantile (the 99.9 %
point of a chi-square with 4 degrees of freedom, 18.47): the gate widens as
the filter grows uncertain over frames without a measure, so it finds the
pipe again instead of rejecting it for ever.  Without ``S`` the distance
is the root-mean-square abscissa difference and the gate ``gate_px``.

Nested bands (addition)
-----------------------
Without a prediction, the pair with the highest ``Delta R`` may lie
inside the pipe: a painted or shaded pipe draws bands along itself (a
bright crown between darker flanks, a dark rim inside each border), and
their lines are as straight and as long as the borders, often stronger.
A pipe's borders are its outline, which encloses such bands.  So when a
compatible pair encloses the best one (its left line left of the best's
left line and its right line right of the best's right line, on the first
and on the last row), runs parallel to it (each line within
``nest_max_angle`` of the line it encloses) and reaches ``(1 -
nest_slack)`` of its ``Delta R``, the widest such pair is taken instead.
Parallel is what makes the rule safe: two unrelated lines beside a pair
(a rock's edge, a ripple crossing at an angle) are not parallel to it;
without that condition the rule took such pairs on camera/S2 and S7
(:mod:`trackbench_foresti.params` gives the numbers).  ``nest_slack = 0``
is the paper's choice, the highest ``Delta R``.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from benchmark.modalities.camera.geometry import ImageSize

if TYPE_CHECKING:
    from trackbench_foresti.features import CandidateLine


@dataclass(frozen=True)
class GroupingParams:
    """Parameters of the grouping step, in the units the functions here take.

    Built from the flat, validated fields of
    :class:`trackbench_foresti.params.FeatureParams` by its
    :attr:`~trackbench_foresti.params.FeatureParams.grouping`; it does not
    check its values itself.

    Attributes
    ----------
    max_divergence : float
        Slack in rad for borders that diverge towards the top (rule b): the
        separation on the first row may exceed that on the last row by
        ``(H-1) tan(max_divergence)`` px.  One Hough angle step (1 deg).
    min_pair_reliability : float
        With a prediction, only pairs with ``Delta R`` at least this compete.
        The correct pairs of the first 100 frames of camera/S1-S7 have
        ``Delta R`` of 0.69 or more but for one (0.35); 0.3 to 0.5 give the
        same rates there.
    gate_px : float
        With a prediction, the nearest pair is rejected when its RMS
        abscissa difference from the prediction exceeds this, px.
    meet_ratio : float
        ``r = s_top / s_bottom`` below which the convergence term ``C``
        falls, for borders that nearly meet inside the image.
    gate_chi2 : float
        With the prediction's covariance, the Mahalanobis distance squared
        beyond which the nearest pair is rejected.
    nest_slack : float
        Without a prediction, a parallel pair enclosing the best one is
        taken when its ``Delta R`` reaches ``1 - nest_slack`` of the best's;
        0: never (the paper).
    nest_max_angle : float
        Largest angle in rad between an enclosing line and the line it encloses.
    """

    max_divergence: float = math.radians(1.0)
    min_pair_reliability: float = 0.4
    gate_px: float = 40.0
    meet_ratio: float = 0.25
    gate_chi2: float = 18.47
    nest_slack: float = 0.0
    nest_max_angle: float = math.radians(2.0)


@dataclass(frozen=True, eq=False)
class LinePair:
    """A compatible pair of candidate lines.

    Attributes
    ----------
    left, right : CandidateLine
        The borders, ordered by their abscissa on the last row.
    reliability : float
        The grouping reliability ``Delta R``.
    abscissae : numpy.ndarray
        ``(i1, i2, i3, i4)``: left and right on the first row, then on the last row, px.
    """

    left: CandidateLine
    right: CandidateLine
    reliability: float
    abscissae: np.ndarray


@dataclass(frozen=True)
class _Border:
    """What grouping needs of one candidate: its abscissae on the first and last rows, its row span."""

    line: CandidateLine
    top: float
    bottom: float
    span: tuple[int, int] | None
    polarity: int

    @classmethod
    def of(cls, line: CandidateLine, size: ImageSize) -> _Border:
        top, bottom = line.abscissae(size)
        ones = np.flatnonzero(line.domain)
        return cls(line, top, bottom, (int(ones[0]), int(ones[-1])) if ones.size else None, line.polarity)


def _compatible(left: _Border, right: _Border, height: int, max_divergence: float) -> bool:
    top, bottom = right.top - left.top, right.bottom - left.bottom
    bounds_a_band = left.polarity * right.polarity <= 0
    return bounds_a_band and top > 0 and bottom > 0 and top <= bottom + (height - 1) * math.tan(max_divergence)


def _symmetry(left: _Border, right: _Border) -> float:
    if left.span is None or right.span is None:
        return 0.5
    (a1, a2), (b1, b2) = left.span, right.span
    inter = max(0, min(a2, b2) - max(a1, b1) + 1)
    union = max(a2, b2) - min(a1, b1) + 1
    return 0.5 * (1.0 + inter / union)


def _convergence(left: _Border, right: _Border, meet_ratio: float) -> float:
    top, bottom = right.top - left.top, right.bottom - left.bottom
    if bottom <= 0 or not 0 <= top <= bottom:
        return 0.5
    return 0.5 + 0.5 * min(1.0, top / bottom / meet_ratio)


def _pair_reliability(left: _Border, right: _Border, meet_ratio: float) -> float:
    mean = 0.5 * (left.line.reliability + right.line.reliability)
    return mean * _symmetry(left, right) * _convergence(left, right, meet_ratio)


def compatible(
    left: CandidateLine, right: CandidateLine, size: ImageSize, max_divergence: float = math.radians(1.0)
) -> bool:
    """True when ``(left, right)`` could be the pipeline's borders, rules (a)-(d) of the module docstring.

    Parameters
    ----------
    left, right : CandidateLine
        The lines, in the order to test.
    size : tuple of int
        Image ``(W, H)`` in px.
    max_divergence : float
        Slack in rad for borders diverging towards the top.

    References
    ----------
    seeds/004, section IV: "it is not possible that two candidate lines
    representing the pipeline borders intersect or diverge".
    """
    if not (left.by_rows and right.by_rows):
        return False
    return _compatible(_Border.of(left, size), _Border.of(right, size), size[1], max_divergence)


def symmetry(left: CandidateLine, right: CandidateLine) -> float:
    """``S = (1 + IoU) / 2`` of the two domains' spans ``[d1, d2]``, in ``[1/2, 1]``; 1/2 for an empty domain.

    References
    ----------
    seeds/004, section IV ("symmetry") and eqs. (5a)-(5b); our reading, see the module docstring.
    """
    spans = [np.flatnonzero(line.domain) for line in (left, right)]
    if any(ones.size == 0 for ones in spans):
        return 0.5
    first, second = ((int(ones[0]), int(ones[-1])) for ones in spans)
    return _symmetry(_Border(left, 0.0, 0.0, first, left.polarity), _Border(right, 0.0, 0.0, second, right.polarity))


def convergence(left: CandidateLine, right: CandidateLine, size: ImageSize, meet_ratio: float = 0.25) -> float:
    """``C = 1/2 + 1/2 min(1, r / meet_ratio)`` with ``r = s_top / s_bottom``, in ``[1/2, 1]``.

    ``r < 0`` (a crossing within the rows), ``r > 1`` (divergence) and
    ``s_bottom <= 0`` (the lines in the wrong order) give 1/2.

    References
    ----------
    seeds/004, section IV ("convergence"); our reading, see the module docstring.
    """
    return _convergence(_Border.of(left, size), _Border.of(right, size), meet_ratio)


def pair_reliability(left: CandidateLine, right: CandidateLine, size: ImageSize, meet_ratio: float = 0.25) -> float:
    """``Delta R = (Lambda_left + Lambda_right) / 2 * S * C``, in ``[0, 1]``.

    References
    ----------
    seeds/004, section IV (grouping reliability); our reading, see the module docstring.
    """
    return _pair_reliability(_Border.of(left, size), _Border.of(right, size), meet_ratio)


def compatible_pairs(
    lines: Sequence[CandidateLine], size: ImageSize, params: GroupingParams | None = None
) -> list[LinePair]:
    """Every compatible pair of candidate lines with its ``Delta R``.

    Parameters
    ----------
    lines : sequence of CandidateLine
        The candidate set.
    size : tuple of int
        Image ``(W, H)`` in px.
    params : GroupingParams, optional
        ``max_divergence`` and ``meet_ratio`` are used here.

    Returns
    -------
    list of LinePair
        Each pair once, left and right ordered by their abscissa on the last row.

    References
    ----------
    seeds/004, section IV (grouping).
    """
    params = params if params is not None else GroupingParams()
    borders = sorted((_Border.of(line, size) for line in lines if line.by_rows), key=lambda border: border.bottom)
    pairs = []
    for i, left in enumerate(borders):
        for right in borders[i + 1 :]:
            if _compatible(left, right, size[1], params.max_divergence):
                pairs.append(
                    LinePair(
                        left.line,
                        right.line,
                        _pair_reliability(left, right, params.meet_ratio),
                        np.array([left.top, right.top, left.bottom, right.bottom]),
                    )
                )
    return pairs


def encloses(outer: LinePair, inner: LinePair, max_angle: float) -> bool:
    """Whether ``outer`` encloses ``inner`` on the first and last rows and runs parallel to it.

    ``outer``'s left line is at or left of ``inner``'s on both rows, its
    right line at or right of ``inner``'s, and each of its lines is within
    ``max_angle`` rad of the line it encloses.  A pair encloses itself.

    References
    ----------
    seeds/004, section IV (grouping by the scene's geometry); the rule is ours, see the module docstring.
    """
    o, i = outer.abscissae, inner.abscissae
    around = o[0] <= i[0] and o[2] <= i[2] and o[1] >= i[1] and o[3] >= i[3]
    parallel = (
        abs(outer.left.alpha - inner.left.alpha) <= max_angle
        and abs(outer.right.alpha - inner.right.alpha) <= max_angle
    )
    return around and parallel


def outline(pairs: Sequence[LinePair], best: LinePair, params: GroupingParams) -> LinePair:
    """The widest pair that encloses ``best``, runs parallel to it and reaches ``1 - nest_slack`` of its ``Delta R``.

    Parameters
    ----------
    pairs : sequence of LinePair
        The compatible pairs, ``best`` among them.
    best : LinePair
        The pair with the highest ``Delta R``.
    params : GroupingParams
        ``nest_slack`` and ``nest_max_angle``; ``nest_slack = 0`` returns ``best``.

    Returns
    -------
    LinePair
        ``best`` unless a wider pair qualifies; width is the sum of the
        separations on the first and last rows.

    References
    ----------
    seeds/004, section IV (grouping); the rule is ours, see the module docstring.
    """
    if params.nest_slack <= 0:
        return best
    floor = (1.0 - params.nest_slack) * best.reliability
    around = [
        pair
        for pair in pairs
        if pair.reliability >= floor and encloses(pair, best, params.nest_max_angle)
    ]
    return max(around, key=lambda pair: _span(pair), default=best)


def _span(pair: LinePair) -> float:
    i1, i2, i3, i4 = pair.abscissae
    return float((i2 - i1) + (i4 - i3))


def check_prediction(predicted: Sequence[float] | np.ndarray) -> np.ndarray:
    """The predicted abscissae as a float array of 4; ValueError unless they are 4 finite numbers."""
    try:
        values = np.asarray(predicted, dtype=np.float64)
    except (TypeError, ValueError) as error:
        raise ValueError(f"predicted must be 4 finite abscissae (i1, i2, i3, i4), got {predicted!r}") from error
    if values.shape != (4,) or not np.all(np.isfinite(values)):
        raise ValueError(f"predicted must be 4 finite abscissae (i1, i2, i3, i4), got {predicted!r}")
    return values


def choose_pair(
    lines: Sequence[CandidateLine],
    size: ImageSize,
    predicted: Sequence[float] | np.ndarray | None = None,
    params: GroupingParams | None = None,
    spread: np.ndarray | None = None,
) -> tuple[CandidateLine, CandidateLine] | None:
    """The pair of candidate lines most likely to be the pipeline's borders.

    Parameters
    ----------
    lines : sequence of CandidateLine
        The candidate set.
    size : tuple of int
        Image ``(W, H)`` in px.
    predicted : sequence of 4 float, optional
        The EKF's predicted abscissae ``(i1, i2, i3, i4)``: pixel columns
        where the left (``i1``) and right (``i2``) borders cross the first
        row ``v = 0``, and where the left (``i3``) and right (``i4``) cross
        the last row ``v = H-1``.
    params : GroupingParams, optional
        Thresholds; the defaults when omitted.
    spread : numpy.ndarray, optional
        ``(4, 4)`` covariance of the predicted abscissae (the EKF's
        innovation covariance); with it, distance and gate are Mahalanobis.

    Returns
    -------
    tuple of CandidateLine or None
        ``(left, right)``.  Without a prediction: the compatible pair with
        the highest ``Delta R``, or the widest parallel pair enclosing it
        (:func:`outline`).  With one: among the compatible pairs with
        ``Delta R >= min_pair_reliability``, the one nearest the prediction
        (sum of squared abscissa differences, or Mahalanobis with
        ``spread``), unless it lies outside the gate (``gate_px`` on the RMS
        difference, or ``gate_chi2`` on the Mahalanobis distance).  None
        when no pair qualifies.

    References
    ----------
    seeds/004, section IV (grouping) and Fig. 4 (the abscissae ``i1``-``i4``).
    """
    target = None if predicted is None else check_prediction(predicted)
    params = params if params is not None else GroupingParams()
    pairs = compatible_pairs(lines, size, params)
    if target is None:
        if not pairs:
            return None
        best = outline(pairs, max(pairs, key=lambda pair: pair.reliability), params)
        return best.left, best.right
    eligible = [pair for pair in pairs if pair.reliability >= params.min_pair_reliability]
    if not eligible:
        return None
    residuals = np.array([pair.abscissae - target for pair in eligible])
    if spread is None:
        costs = np.sum(residuals**2, axis=1)
        outside = math.sqrt(float(costs.min()) / 4.0) > params.gate_px
    else:
        costs = np.einsum("ki,ki->k", residuals, np.linalg.solve(np.asarray(spread, dtype=float), residuals.T).T)
        outside = float(costs.min()) > params.gate_chi2
    if outside:
        return None
    nearest = int(np.argmin(costs))
    return eligible[nearest].left, eligible[nearest].right
