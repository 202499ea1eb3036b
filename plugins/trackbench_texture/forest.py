"""The region classifier's trees as lookup tables, for classifying a whole image at once.

scikit-learn's :class:`~sklearn.ensemble.HistGradientBoostingClassifier`
walks its trees one at a time, node by node; on the few thousand grid
points of a frame that took most of the texture tracker's time.
:class:`Forest` finds the same leaves by table look-ups instead, in the
manner of QuickScorer (Lucchese et al., SIGIR 2015):

* The leaves of each tree are numbered from left to right, and each split
  node has the mask of the leaves in its left subtree.  A point that goes
  right at a node cannot reach those leaves; the leaf it reaches is the
  leftmost one that none of the nodes it goes right at rules out.
* Whether a point goes right at a node depends only on where its value
  lies among the sorted split thresholds of the node's feature: its *bin*,
  the number of thresholds below the value (or a bin of its own for NaN,
  which goes the way the node sends missing values).  So for every feature
  and bin, the leaves that remain reachable in each tree are tabulated
  once; a point's leaf in a tree is the lowest bit of the AND of its
  features' rows.

The result is scikit-learn's own, bit for bit: every point reaches the
leaf scikit-learn's walk reaches, and each raw prediction is the baseline
plus the leaf values, added in scikit-learn's order.  Trees with more than
64 leaves or splits on categorical features are not supported; the region
classifier has at most 31 leaves per tree and only numeric descriptors.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numba
import numpy as np
from numba.cpython.unsafe.numbers import trailing_zeros

if TYPE_CHECKING:
    from sklearn.ensemble import HistGradientBoostingClassifier

MAX_LEAVES = 64
"""The most leaves a tree may have: one bit of a ``uint64`` mask each."""


SEARCH_CELLS = 1024
"""Cells of the uniform partition of each feature's thresholds that tells where to look for a value's bin."""


@numba.njit(cache=True, nogil=True)
def _bin_rows(
    x: np.ndarray, thresholds: np.ndarray, starts: np.ndarray, cell_low: np.ndarray, cell_scale: np.ndarray,
    cell_bins: np.ndarray,
) -> np.ndarray:
    """The row of :attr:`Forest.reachable` each point's value of each feature selects, ``(features, N)``.

    A value's bin is the number of thresholds below it (``np.searchsorted``).  The search steps from the
    bin of the lower edge of the value's cell (:attr:`Forest.cell_bins`), usually a step or two away; the
    arrays are those of :class:`Forest`.
    """
    rows = np.empty((x.shape[1], x.shape[0]), np.intp)
    last_cell = cell_bins.shape[1] - 1
    for f in range(x.shape[1]):
        first, stop = starts[f], starts[f + 1]
        bin_zero = first + 2 * f
        for i in range(x.shape[0]):
            value = x[i, f]
            if np.isnan(value):
                rows[f, i] = bin_zero + stop - first + 1
                continue
            cell = (value - cell_low[f]) * cell_scale[f]
            if not cell > 0.0:
                cell = 0.0
            elif cell > last_cell:
                cell = last_cell
            k = first + cell_bins[f, int(cell)]
            while k > first and thresholds[k - 1] >= value:
                k -= 1
            while k < stop and thresholds[k] < value:
                k += 1
            rows[f, i] = bin_zero + k - first
    return rows


@numba.njit(cache=True, nogil=True)
def _and_rows(rows: np.ndarray, i: int, reachable: np.ndarray, mask: np.ndarray) -> None:
    """Set ``mask`` to the AND of the rows of ``reachable`` that point ``i`` selects: per tree, its reachable leaves.

    The rows are taken two at a time (the last one twice when their number is odd), which halves the
    passes over ``mask``.
    """
    last = rows.shape[0] - 1
    first, second = reachable[rows[0, i]], reachable[rows[min(1, last), i]]
    for t in range(mask.shape[0]):
        mask[t] = first[t] & second[t]
    for f in range(2, last + 1, 2):
        first, second = reachable[rows[f, i]], reachable[rows[min(f + 1, last), i]]
        for t in range(mask.shape[0]):
            mask[t] &= first[t] & second[t]


@numba.njit(cache=True, nogil=True)
def _add_leaf_values(rows: np.ndarray, reachable: np.ndarray, leaf_values: np.ndarray, raw: np.ndarray) -> None:
    """Add to ``raw[i, c]`` the values of the leaves point ``i`` reaches in the trees of column ``c``, in order.

    ``rows`` is :func:`_bin_rows`' result; the other arrays are those of :class:`Forest`.  Points are taken
    four at a time (the last ones paired with the last point): each sum is a chain of dependent additions,
    and the four points' chains run side by side.
    """
    n, columns = raw.shape
    per_column = reachable.shape[1] // columns
    mask_a = np.empty(reachable.shape[1], reachable.dtype)
    mask_b, mask_c, mask_d = np.empty_like(mask_a), np.empty_like(mask_a), np.empty_like(mask_a)
    for a in range(0, n, 4):
        b, c, d = min(a + 1, n - 1), min(a + 2, n - 1), min(a + 3, n - 1)
        _and_rows(rows, a, reachable, mask_a)
        _and_rows(rows, b, reachable, mask_b)
        _and_rows(rows, c, reachable, mask_c)
        _and_rows(rows, d, reachable, mask_d)
        for column in range(columns):
            total_a, total_b, total_c, total_d = raw[a, column], raw[b, column], raw[c, column], raw[d, column]
            for t in range(column * per_column, (column + 1) * per_column):
                values = leaf_values[t]
                total_a += values[trailing_zeros(mask_a[t])]
                total_b += values[trailing_zeros(mask_b[t])]
                total_c += values[trailing_zeros(mask_c[t])]
                total_d += values[trailing_zeros(mask_d[t])]
            raw[a, column], raw[b, column], raw[c, column], raw[d, column] = total_a, total_b, total_c, total_d


def _search_cells(thresholds: np.ndarray) -> tuple[float, float, np.ndarray]:
    """The uniform partition of the range of the finite ones of sorted ``thresholds`` into :data:`SEARCH_CELLS` cells.

    Returns
    -------
    low, scale : float
        Value ``v`` lies in cell ``(v - low) * scale`` (clipped to the cells).
    bins : numpy.ndarray
        ``(SEARCH_CELLS,)``: the number of thresholds below each cell's lower edge.
    """
    finite = thresholds[np.isfinite(thresholds)]
    if len(finite) < 2 or finite[-1] == finite[0]:
        return 0.0, 0.0, np.zeros(SEARCH_CELLS, np.intp)
    low = float(finite[0])
    scale = SEARCH_CELLS / float(finite[-1] - low)
    return low, scale, np.searchsorted(thresholds, low + np.arange(SEARCH_CELLS) / scale).astype(np.intp)


def _leaves(nodes: np.ndarray, node: int) -> list[int]:
    """The leaves of the subtree of ``node``, from left to right."""
    if nodes["is_leaf"][node]:
        return [node]
    return _leaves(nodes, nodes["left"][node]) + _leaves(nodes, nodes["right"][node])


@dataclass(frozen=True, eq=False)
class Forest:
    """The trees of a fitted gradient-boosting classifier, tabulated by the leaves each feature bin can reach.

    Attributes
    ----------
    thresholds : numpy.ndarray
        The distinct thresholds the trees split each feature at, sorted,
        feature after feature: feature ``f``'s are
        ``thresholds[starts[f]:starts[f + 1]]``.
    starts : numpy.ndarray
        ``(features + 1,)`` offsets into :attr:`thresholds`.
    reachable : numpy.ndarray
        ``uint32`` (when no tree has more than 32 leaves) or ``uint64``
        array of shape ``(rows, trees)``: per feature bin, the
        mask of each tree's leaves a point of that bin can reach (bit
        ``k``: the ``k``-th leaf from the left).  Feature ``f`` has a row
        for each of its bins (``starts[f + 1] - starts[f] + 1`` of them),
        then one for NaN; its rows start at ``starts[f] + 2 * f``.
    leaf_values : numpy.ndarray
        ``(trees, MAX_LEAVES)``: the value of each tree's ``k``-th leaf from the left.
    cell_low, cell_scale : numpy.ndarray
        ``(features,)``: value ``v`` of feature ``f`` lies in cell
        ``(v - cell_low[f]) * cell_scale[f]`` of a uniform partition of the
        range of the feature's thresholds (:func:`_search_cells`).
    cell_bins : numpy.ndarray
        ``(features, SEARCH_CELLS)``: the bin of each cell's lower edge.
    baseline : numpy.ndarray
        ``(1, columns)``: the raw prediction before any tree.

    The trees are numbered column by column (class by class), each
    column's trees in scikit-learn's order (iteration by iteration): every
    column has as many trees as there were iterations.
    """

    thresholds: np.ndarray
    starts: np.ndarray
    reachable: np.ndarray
    leaf_values: np.ndarray
    cell_low: np.ndarray
    cell_scale: np.ndarray
    cell_bins: np.ndarray
    baseline: np.ndarray

    @classmethod
    def of(cls, classifier: HistGradientBoostingClassifier) -> Forest:
        """The tables of a fitted classifier.

        Raises
        ------
        ValueError
            If a tree splits a categorical feature or has more than :data:`MAX_LEAVES` leaves.
        """
        columns = len(classifier._predictors[0])
        trees = [iteration[k].nodes for k in range(columns) for iteration in classifier._predictors]
        splits = np.concatenate([nodes[nodes["is_leaf"] == 0] for nodes in trees])
        if splits["is_categorical"].any():
            raise ValueError("texture: the region classifier splits a categorical feature")
        per_feature = [
            np.unique(splits["num_threshold"][splits["feature_idx"] == f]) for f in range(classifier.n_features_in_)
        ]
        starts = np.cumsum([0] + [len(t) for t in per_feature]).astype(np.intp)
        reachable = np.full((starts[-1] + 2 * len(per_feature), len(trees)), np.iinfo(np.uint64).max, dtype=np.uint64)
        leaf_values = np.zeros((len(trees), MAX_LEAVES))
        most_leaves = 0
        for t, nodes in enumerate(trees):
            leaves = _leaves(nodes, 0)
            most_leaves = max(most_leaves, len(leaves))
            if len(leaves) > MAX_LEAVES:
                raise ValueError(f"texture: a tree of the region classifier has more than {MAX_LEAVES} leaves")
            leaf_values[t, : len(leaves)] = nodes["value"][leaves]
            position = {leaf: k for k, leaf in enumerate(leaves)}
            for node in np.flatnonzero(nodes["is_leaf"] == 0):
                left_leaves = np.uint64(sum(1 << position[leaf] for leaf in _leaves(nodes, nodes["left"][node])))
                f = int(nodes["feature_idx"][node])
                rank = int(np.searchsorted(per_feature[f], nodes["num_threshold"][node]))
                bin_zero, nan_row = starts[f] + 2 * f, starts[f + 1] + 2 * f + 1
                # Values above the threshold, in the bins past its rank, go right.
                reachable[bin_zero + rank + 1 : nan_row, t] &= ~left_leaves
                if not nodes["missing_go_to_left"][node]:
                    reachable[nan_row, t] &= ~left_leaves
        cells = [_search_cells(t) for t in per_feature]
        return cls(
            thresholds=np.concatenate(per_feature).astype(np.float64),
            starts=starts,
            reachable=reachable.astype(np.uint32 if most_leaves <= 32 else np.uint64),
            leaf_values=leaf_values,
            cell_low=np.array([low for low, _, _ in cells]),
            cell_scale=np.array([scale for _, scale, _ in cells]),
            cell_bins=np.array([bins for _, _, bins in cells]),
            baseline=np.asarray(classifier._baseline_prediction, dtype=np.float64),
        )

    def raw_predict(self, x: np.ndarray) -> np.ndarray:
        """The raw predictions of points, equal to the classifier's.

        Parameters
        ----------
        x : numpy.ndarray
            ``(N, features)`` points.

        Returns
        -------
        numpy.ndarray
            ``float64`` array of shape ``(N, columns)``, Fortran-ordered as
            scikit-learn's.
        """
        raw = np.zeros((len(x), self.baseline.shape[1]), dtype=np.float64, order="F")
        raw += self.baseline
        points = np.ascontiguousarray(x, dtype=np.float64)
        rows = _bin_rows(points, self.thresholds, self.starts, self.cell_low, self.cell_scale, self.cell_bins)
        _add_leaf_values(rows, self.reachable, self.leaf_values, raw)
        return raw
