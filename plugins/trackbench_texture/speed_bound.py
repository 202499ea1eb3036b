"""The speed bounds of the texture tracker: its own stages, each timed alone, and OpenCV's box filters.

A texture step (seeds/000, section 2.2, Grau's method) finds the kinds of
pixel its five descriptors count on the working image, the descriptors'
densities on a grid, and the region class of each grid point by the
forest, before it fits the borders.  Each of the first three stages is
timed alone here, with the trained model and the tracker's settings, its
input worked out once a frame, untimed (:class:`benchmark.speed.bounds.PerFrame`);
and so is the bound of the densities, OpenCV's ``boxFilter`` over the five
layers at the window's size.  The goal, issue 34's, holds the whole step
under 4 ms.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import cv2
import numpy as np

from benchmark import hookimpl
from benchmark.modalities.camera.io.video import grey_frame
from benchmark.model import Frame, SequenceInfo
from benchmark.speed.bounds import BoundContext, MsAtMost, PerFrame, SpeedBound, SpeedBounds
from trackbench_texture.descriptors import PixelKinds, densities_at
from trackbench_texture.model import TextureModel, prepare, working_kinds

DATASET = "camera/S1"
"""The sequence timed: the thesis' first test sequence (seeds/000, Fig. 5.2)."""


@dataclass(frozen=True)
class Analysed:
    """What each stage needs of a frame: the working image, the kinds, the grid and the descriptors on it."""

    work: Any
    kinds: PixelKinds
    rows: np.ndarray
    cols: np.ndarray
    descriptors: np.ndarray


def analyse(model: TextureModel, frame: Frame) -> Analysed:
    """The stages' inputs, as :meth:`TextureModel.analyse_grid` computes them."""
    settings = model.descriptors
    work = prepare(grey_frame(frame.observation, f"texture: frame {frame.index}"), settings)
    kinds = working_kinds(work, settings)
    height, width = work.image.shape
    step = settings.grid_px
    rows = np.arange(min(step // 2, height - 1), height, step)
    cols = np.arange(min(step // 2, width - 1), width, step)
    return Analysed(work, kinds, rows, cols, densities_at(kinds, settings.window_px, rows, cols))


def edge_kinds(model: TextureModel, analysed: Analysed) -> Any:
    return working_kinds(analysed.work, model.descriptors)


def densities(model: TextureModel, analysed: Analysed) -> Any:
    return densities_at(analysed.kinds, model.descriptors.window_px, analysed.rows, analysed.cols)


def forest(model: TextureModel, analysed: Analysed) -> Any:
    return model.regions.classify(analysed.descriptors)


def box_filters(model: TextureModel, analysed: Analysed) -> Any:
    size = model.descriptors.window_px | 1
    return [
        cv2.boxFilter(layer.astype(np.float32, copy=False), cv2.CV_32F, (size, size), borderType=cv2.BORDER_REFLECT)
        for layer in analysed.kinds.layers()
    ]


Part = Callable[[TextureModel, Analysed], Any]


class Stage:
    """One stage of the texture step on the frame's analysed inputs."""

    def __init__(self, model: TextureModel, part: Part) -> None:
        self.model = model
        self.part = part
        self.inputs: PerFrame[Analysed] = PerFrame(lambda frame: analyse(model, frame))

    def reset(self, info: SequenceInfo, rng: np.random.Generator, init: Any = None) -> None:
        """Nothing to reset: each frame stands alone."""

    def step(self, frame: Frame) -> Any:
        return self.part(self.model, self.inputs(frame))


def stage(part: Part) -> Callable[[BoundContext], Stage]:
    def make(context: BoundContext) -> Stage:
        return Stage(context.model, part)

    return make


STAGES = (
    ("its edge kinds", edge_kinds, None),
    ("its densities on the grid", densities, None),
    ("its forest on the grid", forest, None),
    ("OpenCV boxFilter of the five layers", box_filters, MsAtMost(4)),
)
"""Each row: what is timed, the stage, and the goal (the whole step's, on the bound's row)."""


@hookimpl
def trackbench_register_speed_bounds(registry: SpeedBounds) -> None:
    """texture against each of its stages and OpenCV's box filters of its five layers."""
    for bound, part, goal in STAGES:
        registry.add_bound(SpeedBound("texture", bound, stage(part), DATASET, goal))
