"""The sonar modality: multibeam swaths over a pipe, scored against the sonar's resolution.

Registered as the entry point ``modality-sonar`` of the ``trackbench``
group, exactly as a third-party sensor would be.
"""

from __future__ import annotations

from benchmark.hookspecs import hookimpl
from benchmark.modalities.sonar.draw import draw_sonar_frame
from benchmark.modalities.sonar.hard_observations import hard_observations
from benchmark.modalities.sonar.io import SWATH_SUFFIX, SwathFile, export_swath_file
from benchmark.modalities.sonar.model import PipeEstimate, SonarTruth, Swath
from benchmark.modalities.sonar.scenes.scene import SonarScene
from benchmark.modalities.sonar.scoring import SonarScorer
from benchmark.modality import Modality, Reader, Starter, sequences_in
from benchmark.registry import Registry

SONAR = Modality(
    name="sonar",
    observation_type=Swath,
    truth_type=SonarTruth,
    estimate_type=PipeEstimate,
    scorer=SonarScorer(),
    readers=(Reader(SwathFile, f"a swath file ({SWATH_SUFFIX})", suffixes=(SWATH_SUFFIX,)),),
    exporter=export_swath_file,
    scene_kinds={"sonar": SonarScene.from_dict},
    description="multibeam echo-sounder swaths over a pipe; estimates are across-track positions",
    draw=draw_sonar_frame,
    hard_observations=hard_observations,
    example_sequences=sequences_in("benchmark.modalities.sonar.strategies"),
    starter=Starter(
        imports="from benchmark.modalities.sonar.model import PipeEstimate, SonarTruth",
        truth="SonarTruth",
        estimate="PipeEstimate",
        hold="PipeEstimate(init.across_m)",
        observation="frame.observation is a Swath: across_m and depth_m per beam, NaN where a beam has no return",
        dataset="sonar/concrete",
    ),
)
"""Sonar frames hold one ping of a multibeam echo sounder (seeds/003)."""


@hookimpl
def trackbench_register_modalities(registry: Registry) -> None:
    """Register the sonar modality."""
    registry.add_modality(SONAR)
