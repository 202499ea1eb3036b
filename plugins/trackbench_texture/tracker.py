"""The texture tracker of Grau et al. (seeds/000, section 2.2), the benchmark's first that learns.

Grau et al. tell the cable from the seabed by its texture: five descriptors
measured around every pixel (straightness, abruptness, discontinuity,
granularity and blurriness; :mod:`trackbench_texture.descriptors`) are
classified into region classes learned from labelled images (cable, sand,
stones and vegetation, undefined; :mod:`trackbench_texture.classes`,
:mod:`trackbench_texture.model`).  The thesis leaves open how the cable's
position follows from the classified image; here its two borders are
fitted to the edges of the cable region (:mod:`trackbench_texture.borders`)
and moved out to the feet of those edges on the frame itself
(:mod:`trackbench_texture.feet`).  The descriptors are measured on a
working image, the frame resampled to a fixed height with its grey levels
normalised (:mod:`trackbench_texture.working`), so that a model learned on
frames of one size and exposure applies to others.

Each frame is classified on its own: the tracker keeps no state between
frames but its random generator, never reads a frame's truth and ignores
``init``.  Randomness comes only from the generators handed to
:meth:`TextureTracker.fit` (frames and pixels learned from, the seeds of
the clustering and the classifier) and :meth:`TextureTracker.reset` (the
pairs of pixels the border fits try), so a seed replays a run bit for bit.

Expected weakness, as the thesis puts it: "because of marine growth beside
and on top of cables, the cable often has a similar texture to its
environment (cf. figure 2.3).  I assume that in these cases this approach
tends to fail."  Nothing here tries to make up for it.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import functools
import math
from collections.abc import Sequence as SequenceOf

import cv2
import numpy as np

from benchmark.lazy import lazy_module
from benchmark.modalities.camera.io.video import grey_frame
from benchmark.modalities.camera.model import CableState, CameraFrame, CameraTruth
from benchmark.model import Sequence, SequenceInfo
from benchmark.tracker import Tracker
from trackbench_texture.classes import Region
from trackbench_texture.feet import border_feet
from trackbench_texture.model import TextureModel, train
from trackbench_texture.params import TextureParams

if TYPE_CHECKING:
    from trackbench_texture.descriptors import PixelKinds

# The numba kernels load on the first frame, so that listing the trackers does not import numba.
borders = lazy_module("trackbench_texture.borders")


class TextureTracker(Tracker[CameraTruth, CableState]):
    """Texture descriptors, learned region classes and border lines fitted to the cable region.

    Use: :meth:`fit` on labelled training sequences (or :meth:`use_model`
    with a model an earlier fit returned), then :meth:`reset` and
    :meth:`step` as for any tracker.

    References
    ----------
    seeds/000, section 2.2 and Fig. 2.3 (Grau et al., [GCA98]).
    """

    name = "texture"
    version = "2.0"
    modality = "camera"
    deterministic = True
    Params = TextureParams

    def __init__(self, params: TextureParams | None = None) -> None:
        super().__init__(params)
        self._model: TextureModel | None = None
        self._rng: np.random.Generator | None = None

    @property
    def model(self) -> TextureModel | None:
        """The adopted model, or None before :meth:`fit` or :meth:`use_model`."""
        return self._model

    def fit(self, training: SequenceOf[Sequence], rng: np.random.Generator) -> TextureModel:
        """Learn the region classes from the labelled frames of ``training``; adopt the model and return it.

        Parameters
        ----------
        training : sequence of benchmark.model.Sequence
            Camera sequences; frames without truth or with an unknown cable
            are skipped.
        rng : numpy.random.Generator
            Draws the frames and pixels learned from and seeds the
            clustering and the classifier.

        Returns
        -------
        TextureModel
            Picklable.

        Raises
        ------
        DataError
            If the training set has no labelled frame, shows no cable or no
            ground, or a drawn frame is not an image (naming it).
        """
        self._model = train(training, self.params, rng)
        return self._model

    def use_model(self, model: TextureModel) -> None:
        """Adopt a model an earlier :meth:`fit` returned, perhaps in another process.

        Raises
        ------
        TypeError
            If ``model`` is not a :class:`~trackbench_texture.model.TextureModel`.
        """
        if not isinstance(model, TextureModel):
            raise TypeError(f"texture: expected a TextureModel from TextureTracker.fit, got {type(model).__name__}")
        self._model = model

    def _require_model(self) -> TextureModel:
        if self._model is None:
            raise RuntimeError("texture: no model; call fit(training, rng) or use_model(model) before reset and step")
        return self._model

    def reset(self, info: SequenceInfo, rng: np.random.Generator, init: CameraTruth | None = None) -> None:
        """Prepare for a new sequence: keep the random generator; the model must be there.

        Parameters
        ----------
        info : SequenceInfo
            Not used: the image size is read from each frame.
        rng : numpy.random.Generator
            Draws the pairs of pixels the border fits try.
        init : CameraTruth, optional
            Not used: every frame is classified on its own.

        Raises
        ------
        RuntimeError
            If no model was fitted or given.
        """
        self._require_model()
        self._rng = rng

    def classify(self, frame: CameraFrame) -> tuple[PixelKinds, np.ndarray]:
        """The descriptors' pixels and the :class:`~trackbench_texture.classes.Region` of every pixel of a frame.

        Raises
        ------
        RuntimeError
            If no model was fitted or given.
        DataError
            If the observation is not an image, naming the frame.
        """
        return self._require_model().analyse(_grey(frame))

    def step(self, frame: CameraFrame) -> CableState | None:
        """Classify one frame and fit the cable's borders along its cable region.

        Parameters
        ----------
        frame : CameraFrame
            Its observation is a ``uint8`` grey (or BGR) image.

        Returns
        -------
        CableState or None
            None when the cable region is not cable-shaped
            (:mod:`trackbench_texture.borders`).

        Raises
        ------
        RuntimeError
            If no model was fitted or given, or :meth:`reset` was not called.
        DataError
            If the observation is not an image, naming the frame.
        """
        image = _grey(frame)
        kinds, grid, work = self._require_model().analyse_grid(image)
        if self._rng is None:
            raise RuntimeError("texture: call reset(info, rng) before step")
        p = self.params
        on_cable = grid.classes == Region.CABLE
        strip = borders.cable_strip(on_cable, p.min_region_px, grid.rows, grid.cols)
        if strip is None:
            return None
        state = borders.fit_borders(
            strip,
            kinds.straight,
            self._rng,
            work,
            on_cable[grid.rows][:, grid.cols] if p.border_search == "region" else None,
            p.border_pairing,
            inlier_px=p.inlier_px,
            trials=p.ransac_trials,
            min_length_share=p.min_length_share,
            min_inlier_share=p.min_inlier_share,
            min_width_px=p.min_width_px,
            max_width_px=p.max_width_px,
            max_skew=math.radians(p.max_skew_deg),
            # Smoothed only if a profile pairing reads the grey levels: most frames pair straight pieces.
            grey=functools.partial(_smoothed, work.grey, p.smoothing_sigma)
            if p.border_pairing in borders.PROFILE_PAIRINGS
            else None,
        )
        if state is None or p.foot_reach_px == 0:
            return state
        scale = work.frame_size[1] / work.size[1]
        return border_feet(image, state, p.foot_reach_px * scale, p.smoothing_sigma * scale, p.foot_share)


def _smoothed(grey: np.ndarray, sigma: float) -> np.ndarray:
    """``grey`` as ``float32``, smoothed by a Gaussian of standard deviation ``sigma`` px (0: not smoothed)."""
    grey = grey.astype(np.float32)
    return cv2.GaussianBlur(grey, (0, 0), sigma, borderType=cv2.BORDER_REFLECT) if sigma > 0 else grey


def _grey(frame: CameraFrame) -> np.ndarray:
    """The frame's observation as a ``uint8`` grey image; a :class:`DataError` naming the frame if it is none."""
    return grey_frame(frame.observation, f"texture: frame {frame.index}")
