"""The feature extraction module of seeds/004 on its own: the borders it measures, frame by frame.

``foresti_lines`` reports the pair of lines section IV's grouping picks
(:meth:`~trackbench_foresti.features.FeatureExtractor.measure`, without a
prediction: the most reliable compatible pair), or no cable when there is
none.  It is what the EKF (:mod:`trackbench_foresti.tracker`) adds to: the
filter feeds the extractor its predicted borders and bridges the frames
where no pair is found.
"""

from __future__ import annotations

import numpy as np

from benchmark.modalities.camera.geometry import cable_from_borders
from benchmark.modalities.camera.io.video import grey_frame
from benchmark.modalities.camera.model import CableState, CameraFrame, CameraTruth
from benchmark.model import SequenceInfo
from benchmark.tracker import Tracker
from trackbench_foresti.features import FeatureExtractor, FeatureParams, compile_kernels


class ForestiLinesTracker(Tracker[CameraTruth, CableState]):
    """The pipe's border pair of section IV in every frame, without a filter.

    References
    ----------
    seeds/004, section IV, eqs. (5)-(6), Figs. 6-8.
    """

    name = "foresti_lines"
    version = "1.1"
    modality = "camera"
    deterministic = True
    Params = FeatureParams

    def __init__(self, params: FeatureParams | None = None) -> None:
        super().__init__(params)
        self.features = FeatureExtractor(self.params)

    def reset(self, info: SequenceInfo, rng: np.random.Generator, init: CameraTruth | None = None) -> None:
        """Nothing to set up but the compiled kernels: every frame is measured on its own."""
        compile_kernels()

    def step(self, frame: CameraFrame) -> CableState | None:
        """The chosen pair of borders as a cable state, or None when no compatible pair is found.

        Raises
        ------
        DataError
            If the observation is not a grey image, naming the frame.
        """
        image = grey_frame(frame.observation, f"foresti_lines: frame {frame.index}")
        pair = self.features.measure(image)
        if pair is None:
            return None
        size = (image.shape[1], image.shape[0])
        left, right = pair
        return cable_from_borders(left.line(size), right.line(size))
