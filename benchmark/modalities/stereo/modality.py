"""The stereo modality: a stereo camera on a chase boat measuring a target boat.

Registered as the entry point ``modality-stereo`` of the ``trackbench``
group, exactly as a third-party sensor would be.
"""

from __future__ import annotations

from benchmark.hookspecs import hookimpl
from benchmark.modalities.stereo.draw import draw_stereo_frame
from benchmark.modalities.stereo.hard_observations import hard_observations
from benchmark.modalities.stereo.io.export import export_stereo_sequence
from benchmark.modalities.stereo.io.folder import SIDES, StereoFolder
from benchmark.modalities.stereo.model import StereoMeasurement, StereoTruth, TargetEstimate
from benchmark.modalities.stereo.scenes.images import StereoImageScene
from benchmark.modalities.stereo.scenes.scene import StereoScene
from benchmark.modalities.stereo.scoring import StereoScorer
from benchmark.modality import Modality, Reader, Starter, sequences_in
from benchmark.registry import Registry

STEREO = Modality(
    name="stereo",
    observation_type=(StereoMeasurement, tuple, list, type(None)),
    truth_type=StereoTruth,
    estimate_type=TargetEstimate,
    scorer=StereoScorer(),
    readers=(Reader(StereoFolder, "a stereo folder (left/ and right/ images)", folders=True, folder_holds=SIDES),),
    exporter=export_stereo_sequence,
    scene_kinds={"stereo": StereoScene.from_dict, "stereo-images": StereoImageScene.from_dict},
    description="a target boat seen from a chase boat; estimates are its position and velocity",
    draw=draw_stereo_frame,
    hard_observations=hard_observations,
    example_sequences=sequences_in("benchmark.modalities.stereo.strategies"),
    starter=Starter(
        imports="from benchmark.modalities.stereo.model import StereoTruth, TargetEstimate",
        truth="StereoTruth",
        estimate="TargetEstimate",
        hold="init.target",
        observation="frame.observation is a StereoMeasurement, None (target lost) or an image pair (left, right)",
        dataset="stereo/case1-slow",
    ),
)
"""Stereo frames hold a measurement of the target, None, or an image pair (seeds/002)."""


@hookimpl
def trackbench_register_modalities(registry: Registry) -> None:
    """Register the stereo modality."""
    registry.add_modality(STEREO)
