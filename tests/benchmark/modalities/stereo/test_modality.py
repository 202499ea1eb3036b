"""The stereo modality as it registers: measurements or image pairs, target truths and estimates."""

import numpy as np
import pytest

from benchmark.errors import DataError
from benchmark.modalities.stereo import modality
from benchmark.modalities.stereo.io.export import export_stereo_sequence
from benchmark.modalities.stereo.io.folder import StereoFolder
from benchmark.modalities.stereo.model import StereoMeasurement, StereoTruth, TargetEstimate
from benchmark.modalities.stereo.scenes.images import StereoImageScene
from benchmark.modalities.stereo.scenes.scene import StereoScene
from benchmark.modalities.stereo.scoring import StereoScorer
from benchmark.model import Frame
from benchmark.registry import Registry


def test_it_registers_itself_through_its_hook() -> None:
    registry = Registry()
    modality.trackbench_register_modalities(registry)
    assert registry.modalities == {"stereo": modality.STEREO}
    assert registry.scene_kinds == {"stereo": StereoScene.from_dict, "stereo-images": StereoImageScene.from_dict}


def test_it_declares_target_truths_and_estimates_and_reads_and_writes_stereo_folders() -> None:
    stereo = modality.STEREO
    assert (stereo.truth_type, stereo.estimate_type) == (StereoTruth, TargetEstimate)
    assert isinstance(stereo.scorer, StereoScorer)
    assert [reader.open for reader in stereo.readers] == [StereoFolder]
    assert stereo.claims == ("folders holding left, right",)
    assert stereo.exporter is export_stereo_sequence


@pytest.mark.parametrize(
    "observation",
    [StereoMeasurement(200.0, 190.0, (14.0, 0.5)), None, (np.zeros((2, 3, 3), np.uint8),) * 2],
)
def test_a_frame_holds_a_measurement_nothing_or_an_image_pair(observation: object) -> None:
    modality.STEREO.check_frame(Frame(0, observation), "here")


def test_a_frame_holding_anything_else_is_refused() -> None:
    with pytest.raises(DataError, match="here: the observation is a ndarray"):
        modality.STEREO.check_frame(Frame(0, np.zeros((2, 3, 3))), "here")
