"""The region classes of Grau et al. and the classifier that learns them (seeds/000, section 2.2).

Grau et al. learn "the texture parameters for different types of regions":
the cable area (high straightness and abruptness), sand (smooth areas),
stones and vegetation (high discontinuity, low straightness) and undefined
regions (blurry texture).  The thesis says neither how the regions were
labelled nor what learned them.  The readings implemented here:

* **cable** is taught by the ground truth: the pixels between the true
  borders (:func:`trackbench_texture.labels.cable_mask`).
* **sand** and **stones and vegetation** are the two clusters k-means finds
  among the descriptor vectors of the pixels outside the cable (on
  standardised descriptors).  The truth does not tell them apart, and the
  thesis' own description of them is a description of two texture
  clusters; the cluster whose centre is the blurrier (smoother) is sand.
  When the ground's descriptor vectors are all alike (a blank ground), there
  is one cluster, and all ground is sand.
* **undefined** is a pixel whose likeliest class has a probability below
  ``min_confidence``: the thesis' "blurry texture" regions are those the
  descriptors cannot place, and no truth could label them.
* The classifier is scikit-learn's histogram gradient boosting over the
  five descriptors: it needs no scaling and handles the descriptors' skewed
  distributions (many exact zeros).  Its training pixels are balanced
  between cable and ground, so that the cable, a tenth of an image, is not
  drowned; the cable region then spills over onto the ground, which the
  border fit allows for (:mod:`trackbench_texture.borders`).
* An image is classified by the same trees turned into lookup tables
  (:mod:`trackbench_texture.forest`), with scikit-learn's probabilities bit
  for bit, in a millisecond or two: ten times faster than scikit-learn's
  own tree walks.
* scikit-learn runs on one native thread here: its OpenMP threads, spinning
  against the harness' own workers on a shared machine, made a fit forty
  times slower.
"""

from __future__ import annotations

import enum
import functools
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from threadpoolctl import threadpool_limits

from benchmark.errors import DataError
from benchmark.lazy import lazy_module

if TYPE_CHECKING:
    from sklearn._loss.loss import HalfBinomialLoss, HalfMultinomialLoss
    from sklearn.ensemble import HistGradientBoostingClassifier

    from trackbench_texture.forest import Forest

# scikit-learn and the numba kernels are imported where a model is fitted or applied, so that listing the trackers
# does not import them.
forest = lazy_module("trackbench_texture.forest")
pixel_descriptors = lazy_module("trackbench_texture.descriptors")


class Region(enum.IntEnum):
    """The region classes of seeds/000, section 2.2, as the values of a classified image."""

    UNDEFINED = 0
    CABLE = 1
    SAND = 2
    STONES_AND_VEGETATION = 3


def _seed(rng: np.random.Generator) -> int:
    return int(rng.integers(2**31 - 1))


def split_ground(ground: np.ndarray, rng: np.random.Generator) -> np.ndarray:
    """Tell sand from stones and vegetation among ground pixels' descriptor vectors.

    Parameters
    ----------
    ground : numpy.ndarray
        ``(N, 5)`` descriptor vectors of pixels outside the cable.
    rng : numpy.random.Generator
        Seeds k-means.

    Returns
    -------
    numpy.ndarray
        ``(N,)`` region classes, :attr:`Region.SAND` or
        :attr:`Region.STONES_AND_VEGETATION`: two k-means clusters of the
        standardised vectors, the one with the blurrier centre being sand;
        all sand when the vectors are all alike.
    """
    labels = np.full(len(ground), Region.SAND, dtype=np.int64)
    if len(ground) < 2 or len(np.unique(ground, axis=0)) < 2:
        return labels
    spread = ground.std(axis=0)
    scaled = (ground - ground.mean(axis=0)) / np.where(spread > 0, spread, 1.0)
    with threadpool_limits(1):
        from sklearn.cluster import KMeans

        clusters = KMeans(n_clusters=2, n_init=4, random_state=_seed(rng)).fit_predict(scaled)
    blurriness = pixel_descriptors.NAMES.index("blurriness")
    means = [ground[clusters == k, blurriness].mean() for k in (0, 1)]
    sand = int(np.argmax(means))
    labels[clusters != sand] = Region.STONES_AND_VEGETATION
    return labels


@dataclass(frozen=True, eq=False)
class RegionClassifier:
    """A learned per-pixel classifier of texture descriptors into :class:`Region` classes.

    It keeps only the fitted classifier's trees as tables (arrays and
    numbers), so that a stored model is data, never code
    (:mod:`benchmark.storage`).

    Attributes
    ----------
    forest : Forest
        The fitted classifier's trees (:meth:`of`).
    classes : tuple of int
        The :class:`Region` values the classifier learned, in the order of its probabilities.
    min_confidence : float
        Probability below which a pixel is :attr:`Region.UNDEFINED`.
    """

    forest: Forest
    classes: tuple[int, ...]
    min_confidence: float

    @classmethod
    def of(cls, classifier: HistGradientBoostingClassifier, min_confidence: float) -> RegionClassifier:
        """The region classifier of a fitted scikit-learn classifier."""
        return cls(forest.Forest.of(classifier), tuple(int(c) for c in classifier.classes_), float(min_confidence))

    @property
    def regions(self) -> tuple[Region, ...]:
        """The classes the classifier learned, in the order of its probabilities."""
        return tuple(Region(c) for c in self.classes)

    @functools.cached_property
    def _loss(self) -> HalfBinomialLoss | HalfMultinomialLoss:
        """The link from raw predictions to probabilities scikit-learn's classifier uses for this many classes."""
        from sklearn._loss.loss import HalfBinomialLoss, HalfMultinomialLoss

        return HalfBinomialLoss() if len(self.classes) == 2 else HalfMultinomialLoss(n_classes=len(self.classes))

    def probabilities(self, descriptors: np.ndarray) -> np.ndarray:
        """The class probabilities of descriptor vectors, equal to the classifier's ``predict_proba``.

        Parameters
        ----------
        descriptors : numpy.ndarray
            ``(N, 5)`` descriptor vectors.

        Returns
        -------
        numpy.ndarray
            ``(N, classes)`` probabilities, in the order of :attr:`regions`.
        """
        return self._loss.predict_proba(self.forest.raw_predict(descriptors))

    def classify(self, descriptors: np.ndarray) -> np.ndarray:
        """The region class of every pixel.

        Parameters
        ----------
        descriptors : numpy.ndarray
            ``(H, W, 5)`` descriptors (:func:`trackbench_texture.descriptors.texture_descriptors`).

        Returns
        -------
        numpy.ndarray
            ``uint8`` array of shape ``(H, W)`` of :class:`Region` values.
        """
        height, width, depth = descriptors.shape
        probabilities = self.probabilities(descriptors.reshape(-1, depth))
        best = np.argmax(probabilities, axis=1)
        regions = np.asarray(self.regions, dtype=np.uint8)[best]
        regions[probabilities.max(axis=1) < self.min_confidence] = Region.UNDEFINED
        return regions.reshape(height, width)

def train_regions(
    descriptors: np.ndarray, on_cable: np.ndarray, rounds: int, min_confidence: float, rng: np.random.Generator
) -> RegionClassifier:
    """Learn the region classes from labelled pixels.

    Parameters
    ----------
    descriptors : numpy.ndarray
        ``(N, 5)`` descriptor vectors of training pixels.
    on_cable : numpy.ndarray
        ``(N,)`` bool: True for pixels inside the true cable.
    rounds : int
        Boosting rounds.
    min_confidence : float
        Probability below which a pixel is undefined.
    rng : numpy.random.Generator
        Seeds the clustering and the classifier.

    Returns
    -------
    RegionClassifier

    Raises
    ------
    DataError
        If there is no cable pixel or no ground pixel to learn from.
    """
    if not on_cable.any() or on_cable.all():
        missing = "cable" if not on_cable.any() else "ground"
        raise DataError(f"texture: the training frames show no {missing} pixel, so the regions cannot be learned")
    labels = np.full(len(descriptors), Region.CABLE, dtype=np.int64)
    labels[~on_cable] = split_ground(descriptors[~on_cable], rng)
    from sklearn.ensemble import HistGradientBoostingClassifier

    classifier = HistGradientBoostingClassifier(max_iter=rounds, early_stopping=False, random_state=_seed(rng))
    with threadpool_limits(1):
        classifier.fit(descriptors.astype(np.float64), labels)
    return RegionClassifier.of(classifier, min_confidence)
