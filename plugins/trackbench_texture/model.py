"""Learning the texture model from labelled sequences (seeds/000, section 2.2).

Grau et al. "used a set of underwater cable images to learn the texture
parameters for different types of regions".  Here the set is the labelled
frames of the training sequences, subsampled so that training on ten
sequences of a few hundred frames takes seconds:

1. from each sequence, ``frames_per_sequence`` labelled frames (those whose
   truth knows the cable), drawn by reservoir sampling, so that a sequence
   of unknown length is read once and never held in memory;
2. from each of them, ``pixels_per_frame`` pixels, half inside the true
   cable and half outside (fewer when a side has fewer pixels);
3. the region classes learned from those pixels' descriptors
   (:func:`trackbench_texture.classes.train_regions`).

Every random choice draws from the generator handed to :func:`train`, and
scikit-learn's estimators get seeds drawn from it, so one seed gives the
same model bit for bit.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from collections.abc import Iterable
from collections.abc import Sequence as SequenceOf
from dataclasses import dataclass

import numpy as np

from benchmark.errors import DataError
from benchmark.lazy import lazy_module
from benchmark.modalities.camera.io.video import grey_frame
from benchmark.modalities.camera.model import CableState
from benchmark.model import Frame, Sequence
from trackbench_texture.classes import RegionClassifier, train_regions
from trackbench_texture.labels import cable_mask
from trackbench_texture.params import DescriptorParams, TextureParams
from trackbench_texture.working import WorkingImage, working_image

if TYPE_CHECKING:
    from trackbench_texture.descriptors import PixelKinds

# The numba kernels load on the first frame, so that listing the trackers does not import numba.
pixel_descriptors = lazy_module("trackbench_texture.descriptors")


@dataclass(frozen=True, eq=False)
class TextureModel:
    """What the texture tracker learned: its descriptors' settings and the region classifier.

    Attributes
    ----------
    descriptors : DescriptorParams
        The descriptor settings the classifier was trained on (used again to classify).
    regions : RegionClassifier
        The per-pixel region classifier.
    training : tuple of str
        Names of the sequences it learned from.
    n_frames : int
        Number of labelled frames whose pixels it learned from.
    """

    descriptors: DescriptorParams
    regions: RegionClassifier
    training: tuple[str, ...]
    n_frames: int

    def analyse(self, image: np.ndarray) -> tuple[PixelKinds, np.ndarray]:
        """The descriptors' pixels and the region class of every pixel of the working image of a ``uint8`` grey frame.

        The working image is the frame resampled and normalised
        (:func:`prepare`); with ``working_height_px`` 0 it has the frame's
        size.  The classes are computed on a grid of spacing ``grid_px`` (the
        descriptors vary slowly, being densities over ``window_px``), and
        each grid point's class fills the pixels nearest to it.

        Returns
        -------
        kinds : PixelKinds
            What each descriptor counts (the straight pieces locate the borders).
        regions : numpy.ndarray
            ``uint8`` array of the working image's shape of :class:`~trackbench_texture.classes.Region` values.
        """
        kinds, grid, _ = self.analyse_grid(image)
        return kinds, grid.pixels()

    def analyse_grid(self, image: np.ndarray) -> tuple[PixelKinds, RegionGrid, WorkingImage]:
        """The descriptors' pixels and the region classes of the grid of :meth:`analyse`, not yet spread to pixels.

        Returns
        -------
        kinds : PixelKinds
            What each descriptor counts.
        grid : RegionGrid
            The grid points' classes and the pixels of the working image each fills.
        work : WorkingImage
            The working image, and how it maps to the frame.
        """
        settings = self.descriptors
        work = prepare(image, settings)
        kinds = working_kinds(work, settings)
        step = settings.grid_px
        offset = step // 2
        height, width = work.image.shape
        rows = np.arange(min(offset, height - 1), height, step)
        cols = np.arange(min(offset, width - 1), width, step)
        classes = self.regions.classify(pixel_descriptors.densities_at(kinds, settings.window_px, rows, cols))
        nearest_row = np.clip(np.rint((np.arange(height) - rows[0]) / step).astype(int), 0, len(rows) - 1)
        nearest_col = np.clip(np.rint((np.arange(width) - cols[0]) / step).astype(int), 0, len(cols) - 1)
        return kinds, RegionGrid(classes, nearest_row, nearest_col), work


def working_kinds(work: WorkingImage, settings: DescriptorParams) -> PixelKinds:
    """The pixels the descriptors count on a working image: the lines on the normalised image, the
    specks and soft pixels on the normalised or the resampled one as ``settings.normalised_kinds`` says."""
    noise = work.grey if settings.normalised_kinds == "lines" else None
    return pixel_descriptors.pixel_kinds(work.image, settings, noise)


def prepare(image: np.ndarray, settings: DescriptorParams) -> WorkingImage:
    """The working image of a ``uint8`` grey frame: resampled and normalised as ``settings`` say.

    Raises
    ------
    ValueError
        If ``image`` is not a non-empty 2-D ``uint8`` array.
    """
    return working_image(
        image,
        settings.working_height_px,
        settings.normalisation,
        settings.normalised_spread,
        settings.normalisation_scale,
    )


@dataclass(frozen=True, eq=False)
class RegionGrid:
    """The region classes of the points of an image's grid, and the pixels each point's class fills.

    Attributes
    ----------
    classes : numpy.ndarray
        ``uint8`` array of shape ``(h, w)`` of :class:`~trackbench_texture.classes.Region` values.
    rows, cols : numpy.ndarray
        ``(H,)`` and ``(W,)``: the grid row (column) nearest to each pixel
        row (column).  Both are non-decreasing, and every grid row (column)
        is the nearest to at least one pixel row (column): the one it lies on.
    """

    classes: np.ndarray
    rows: np.ndarray
    cols: np.ndarray

    def pixels(self) -> np.ndarray:
        """``uint8`` array of shape ``(H, W)``: the class of every pixel, its nearest grid point's."""
        return self.classes[self.rows][:, self.cols]


@dataclass(frozen=True, eq=False)
class _Labelled:
    image: np.ndarray
    cable: CableState
    where: str


def _labelled_frames(sequence: Sequence) -> Iterable[tuple[Frame, str]]:
    name = sequence.identity.name
    for frame in sequence.frames():
        truth = frame.truth
        cable = getattr(truth, "cable", None)
        if isinstance(cable, CableState) and cable.is_known:
            yield frame, f"texture: training sequence {name!r}, frame {frame.index}"


def _reservoir(sequence: Sequence, k: int, rng: np.random.Generator) -> list[_Labelled]:
    """``k`` labelled frames drawn uniformly without replacement, in one pass."""
    kept: list[_Labelled] = []
    for seen, (frame, where) in enumerate(_labelled_frames(sequence)):
        slot = seen if seen < k else int(rng.integers(seen + 1))
        if slot < k:
            item = _Labelled(grey_frame(frame.observation, where), frame.truth.cable, where)
            if seen < k:
                kept.append(item)
            else:
                kept[slot] = item
    return kept


def _pixels(frame: _Labelled, settings: DescriptorParams, count: int, rng: np.random.Generator):
    """``count`` pixels of a frame's working image, half on the cable, half off: their descriptors and labels."""
    work = prepare(frame.image, settings)
    descriptors = pixel_descriptors.densities(working_kinds(work, settings), settings.window_px)
    on_cable = work.frame_mask(cable_mask(frame.cable, work.frame_size)).ravel()
    chosen = []
    for side in (np.flatnonzero(on_cable), np.flatnonzero(~on_cable)):
        take = min(len(side), count // 2)
        chosen.append(rng.choice(side, size=take, replace=False) if take else side[:0])
    index = np.concatenate(chosen)
    return descriptors.reshape(-1, descriptors.shape[-1])[index], on_cable[index]


def train(training: SequenceOf[Sequence], params: TextureParams, rng: np.random.Generator) -> TextureModel:
    """Learn the texture model from the labelled frames of ``training``.

    Parameters
    ----------
    training : sequence of benchmark.model.Sequence
        Camera sequences whose frames' truths know the cable.
    params : TextureParams
        Sampling sizes, descriptor settings and classifier settings.
    rng : numpy.random.Generator
        The only source of randomness.

    Returns
    -------
    TextureModel

    Raises
    ------
    DataError
        If no training sequence has a labelled frame, a frame is not an
        image (naming it), or the frames show no cable or no ground pixel.
    """
    learn: list[_Labelled] = []
    for sequence in training:
        learn += _reservoir(sequence, params.frames_per_sequence, rng)
    if not learn:
        names = [sequence.identity.name for sequence in training]
        raise DataError(f"texture: no labelled frame (truth with a known cable) in the training set {names}")
    settings = params.descriptor_params()
    samples, on_cable = [], []
    for frame in learn:
        x, y = _pixels(frame, settings, params.pixels_per_frame, rng)
        samples.append(x)
        on_cable.append(y)
    regions = train_regions(
        np.concatenate(samples), np.concatenate(on_cable), params.boosting_rounds, params.min_confidence, rng
    )
    names = tuple(sequence.identity.name for sequence in training)
    return TextureModel(settings, regions, names, len(learn))
