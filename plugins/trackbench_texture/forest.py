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

import numba
import numpy as np
from numba.cpython.unsafe.numbers import trailing_zeros
from sklearn.ensemble import HistGradientBoostingClassifier

MAX_LEAVES = 64
"""The most leaves a tree may have: one bit of a ``uint64`` mask each."""


@numba.njit(cache=True, nogil=True)
def _add_leaf_values(
    x: np.ndarray,
    thresholds: np.ndarray,
    starts: np.ndarray,
    reachable: np.ndarray,
    leaf_values: np.ndarray,
    columns: np.ndarray,
    raw: np.ndarray,
) -> None:
    """Add to ``raw[i, columns[t]]`` the value of the leaf point ``x[i]`` reaches in tree ``t``, tree by tree.

    The arrays are those of :class:`Forest`.
    """
    trees = reachable.shape[1]
    mask = np.empty(trees, np.uint64)
    for i in range(x.shape[0]):
        for f in range(x.shape[1]):
            first, stop = starts[f], starts[f + 1]
            if np.isnan(x[i, f]):
                bin_ = stop - first + 1
            else:
                bin_ = np.searchsorted(thresholds[first:stop], x[i, f])
            row = reachable[first + 2 * f + bin_]
            if f == 0:
                mask[:] = row
            else:
                for t in range(trees):
                    mask[t] &= row[t]
        for t in range(trees):
            raw[i, columns[t]] += leaf_values[t, trailing_zeros(mask[t])]


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
        ``uint64`` array of shape ``(rows, trees)``: per feature bin, the
        mask of each tree's leaves a point of that bin can reach (bit
        ``k``: the ``k``-th leaf from the left).  Feature ``f`` has a row
        for each of its bins (``starts[f + 1] - starts[f] + 1`` of them),
        then one for NaN; its rows start at ``starts[f] + 2 * f``.
    leaf_values : numpy.ndarray
        ``(trees, MAX_LEAVES)``: the value of each tree's ``k``-th leaf from the left.
    columns : numpy.ndarray
        ``(trees,)``: the raw prediction column (class) each tree adds to.
        Trees are in scikit-learn's order: iteration by iteration, column
        by column.
    baseline : numpy.ndarray
        ``(1, columns)``: the raw prediction before any tree.
    """

    thresholds: np.ndarray
    starts: np.ndarray
    reachable: np.ndarray
    leaf_values: np.ndarray
    columns: np.ndarray
    baseline: np.ndarray

    @classmethod
    def of(cls, classifier: HistGradientBoostingClassifier) -> Forest:
        """The tables of a fitted classifier.

        Raises
        ------
        ValueError
            If a tree splits a categorical feature or has more than :data:`MAX_LEAVES` leaves.
        """
        trees = [(k, predictor.nodes) for iteration in classifier._predictors for k, predictor in enumerate(iteration)]
        splits = np.concatenate([nodes[nodes["is_leaf"] == 0] for _, nodes in trees])
        if splits["is_categorical"].any():
            raise ValueError("texture: the region classifier splits a categorical feature")
        per_feature = [
            np.unique(splits["num_threshold"][splits["feature_idx"] == f]) for f in range(classifier.n_features_in_)
        ]
        starts = np.cumsum([0] + [len(t) for t in per_feature]).astype(np.intp)
        reachable = np.full((starts[-1] + 2 * len(per_feature), len(trees)), np.iinfo(np.uint64).max, dtype=np.uint64)
        leaf_values = np.zeros((len(trees), MAX_LEAVES))
        for t, (_, nodes) in enumerate(trees):
            leaves = _leaves(nodes, 0)
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
        return cls(
            thresholds=np.concatenate(per_feature).astype(np.float64),
            starts=starts,
            reachable=reachable,
            leaf_values=leaf_values,
            columns=np.array([k for k, _ in trees], dtype=np.intp),
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
        _add_leaf_values(points, self.thresholds, self.starts, self.reachable, self.leaf_values, self.columns, raw)
        return raw
