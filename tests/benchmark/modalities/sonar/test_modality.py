"""The sonar modality as it registers: its types, scorer, swath files and scene kind."""

from benchmark.modalities.sonar import modality
from benchmark.modalities.sonar.io import SwathFile, export_swath_file
from benchmark.modalities.sonar.model import PipeEstimate, SonarTruth, Swath
from benchmark.modalities.sonar.scenes.scene import SonarScene
from benchmark.modalities.sonar.scoring import SonarScorer
from benchmark.registry import Registry


def test_it_registers_itself_through_its_hook() -> None:
    registry = Registry()
    modality.trackbench_register_modalities(registry)
    assert registry.modalities == {"sonar": modality.SONAR}
    assert set(registry.scene_kinds) == {"sonar"}


def test_it_declares_swaths_pipe_truths_and_pipe_estimates_and_reads_swath_files() -> None:
    sonar = modality.SONAR
    assert (sonar.observation_type, sonar.truth_type, sonar.estimate_type) == (Swath, SonarTruth, PipeEstimate)
    assert isinstance(sonar.scorer, SonarScorer)
    assert [(reader.open, reader.suffixes) for reader in sonar.readers] == [(SwathFile, (".swaths",))]
    assert sonar.exporter is export_swath_file
    assert sonar.scene_kinds["sonar"] == SonarScene.from_dict
