"""The region classifier's lookup tables give scikit-learn's predictions bit for bit."""

from __future__ import annotations

import functools

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from sklearn.ensemble import HistGradientBoostingClassifier
from trackbench_texture.classes import RegionClassifier
from trackbench_texture.forest import Forest, _bin_rows


def _fitted(classes: int, missing: bool, seed: int = 0, leaves: int = 31) -> HistGradientBoostingClassifier:
    """A classifier of 5 features; with ``missing``, NaN in training so that nodes learn where it goes."""
    rng = np.random.default_rng(seed)
    x = rng.random((600, 5))
    x[:, 2] = np.round(x[:, 2] * 20) / 20
    labels = np.digitize(x[:, 0] + 0.5 * x[:, 1] - 0.3 * x[:, 2] + 0.2 * rng.standard_normal(600),
                         np.linspace(-0.2, 1.4, classes + 1)[1:-1])
    if missing:
        x[rng.random(x.shape) < 0.1] = np.nan
    classifier = HistGradientBoostingClassifier(
        max_iter=30, max_leaf_nodes=leaves, min_samples_leaf=2, early_stopping=False, random_state=seed
    )
    return classifier.fit(x, labels)


CLASSIFIERS = {
    "three classes": dict(classes=3, missing=False),
    "three classes, missing values": dict(classes=3, missing=True),
    "two classes, missing values": dict(classes=2, missing=True),
    "four classes, trees of up to 60 leaves": dict(classes=4, missing=True, leaves=60),
}
"""The classifiers the tables are checked against, by name: the arguments of :func:`_fitted`."""


@functools.cache
def classifier_named(name: str) -> HistGradientBoostingClassifier:
    """The classifier ``name`` of :data:`CLASSIFIERS`, fitted on first use (not at collection, in every worker)."""
    return _fitted(**CLASSIFIERS[name])


@st.composite
def points(draw, forest: Forest) -> np.ndarray:
    """Random points whose values are often a split threshold or its neighbour, NaN or infinite."""
    count = draw(st.integers(1, 300))
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    thresholds = forest.thresholds[rng.integers(len(forest.thresholds), size=(count, 5))]
    choices = [
        rng.uniform(-0.2, 1.2, (count, 5)),
        thresholds,
        np.nextafter(thresholds, -np.inf),
        np.nextafter(thresholds, np.inf),
        np.full((count, 5), np.nan),
        np.full((count, 5), -np.inf),
        np.full((count, 5), np.inf),
    ]
    kind = rng.choice(len(choices), size=(count, 5), p=[0.4, 0.2, 0.1, 0.1, 0.1, 0.05, 0.05])
    return np.choose(kind, choices)


@pytest.mark.parametrize("name", CLASSIFIERS)
@settings(max_examples=40, deadline=None)
@given(data=st.data())
def test_the_tables_predict_exactly_what_scikit_learn_predicts(name, data):
    classifier = classifier_named(name)
    regions = RegionClassifier.of(classifier, 0.5)
    x = data.draw(points(regions.forest))
    expected = classifier.predict_proba(x)
    actual = regions.probabilities(x)
    assert actual.dtype == expected.dtype and actual.shape == expected.shape
    assert actual.tobytes() == expected.tobytes()


def test_trees_of_more_than_32_leaves_keep_64_bit_masks():
    forest = RegionClassifier.of(classifier_named("four classes, trees of up to 60 leaves"), 0.5).forest
    assert forest.reachable.dtype == np.uint64
    assert RegionClassifier.of(classifier_named("three classes"), 0.5).forest.reachable.dtype == np.uint32


@pytest.mark.parametrize("name", CLASSIFIERS)
@settings(max_examples=40, deadline=None)
@given(data=st.data())
def test_each_value_selects_the_row_of_its_bin_among_the_sorted_thresholds(name, data):
    forest = RegionClassifier.of(classifier_named(name), 0.5).forest
    x = data.draw(points(forest))
    rows = _bin_rows(x, forest.thresholds, forest.starts, forest.cell_low, forest.cell_scale, forest.cell_bins)
    for f in range(x.shape[1]):
        first, stop = forest.starts[f], forest.starts[f + 1]
        bins = np.where(np.isnan(x[:, f]), stop - first + 1, np.searchsorted(forest.thresholds[first:stop], x[:, f]))
        assert np.array_equal(rows[f], first + 2 * f + bins)


def test_float32_descriptors_are_compared_as_scikit_learn_compares_them():
    classifier = classifier_named("three classes")
    x = np.random.default_rng(1).random((2000, 5)).astype(np.float32)
    expected = classifier.predict_proba(x.astype(np.float64))
    assert RegionClassifier.of(classifier, 0.5).probabilities(x).tobytes() == expected.tobytes()


def test_a_categorical_split_is_refused():
    rng = np.random.default_rng(0)
    x = np.column_stack([rng.integers(0, 4, 300), rng.random(300)])
    classifier = HistGradientBoostingClassifier(max_iter=3, categorical_features=[0], random_state=0)
    classifier.fit(x, (x[:, 0] == 2).astype(int))
    with pytest.raises(ValueError, match="categorical"):
        Forest.of(classifier)
