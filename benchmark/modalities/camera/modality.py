"""The camera modality: grey images of a cable or pipe, scored by Foresti's line-pair rule.

Registered as the entry point ``modality-camera`` of the ``trackbench``
group, exactly as a third-party sensor would be.
"""

from __future__ import annotations

import numpy as np

from benchmark.hookspecs import hookimpl
from benchmark.modalities.camera.draw import draw_camera_frame
from benchmark.modalities.camera.hard_observations import hard_observations
from benchmark.modalities.camera.io.export import export_camera_sequence
from benchmark.modalities.camera.io.image_folder import ImageFolder
from benchmark.modalities.camera.io.sequence_file import ImageSequenceFile
from benchmark.modalities.camera.io.video import VIDEO_EXTENSIONS, VideoFile
from benchmark.modalities.camera.model import CableState, CameraTruth
from benchmark.modalities.camera.scenes.scene import CameraScene
from benchmark.closedloop.scene import ClosedLoopScene
from benchmark.modalities.camera.scoring import CameraScorer
from benchmark.modality import ANY_FILE, Modality, Reader, Starter, sequences_in
from benchmark.registry import Registry

CAMERA = Modality(
    name="camera",
    observation_type=np.ndarray,
    truth_type=CameraTruth,
    estimate_type=CableState,
    scorer=CameraScorer(),
    readers=(
        Reader(ImageFolder, "an image folder", folders=True),
        Reader(VideoFile, f"a video ({', '.join(sorted(VIDEO_EXTENSIONS))})", suffixes=tuple(sorted(VIDEO_EXTENSIONS))),
        Reader(ImageSequenceFile, "an image sequence file", suffixes=(ANY_FILE,)),
    ),
    exporter=export_camera_sequence,
    scene_kinds={"camera": CameraScene.from_dict, "camera-route": ClosedLoopScene.from_dict},
    description="grey images of a cable or pipe; estimates are cable states (d, alpha, w, beta), maybe with a pose",
    draw=draw_camera_frame,
    hard_observations=hard_observations,
    example_sequences=sequences_in("benchmark.modalities.camera.strategies"),
    starter=Starter(
        imports="from benchmark.modalities.camera.model import CableState, CameraTruth",
        truth="CameraTruth",
        estimate="CableState",
        hold="init.cable if init.cable.is_known else None",
        observation="frame.observation is the uint8 grey image (height, width)",
        dataset="camera/S2",
    ),
)
"""Camera frames hold a ``uint8`` grey image (seeds/000 section 4.2, seeds/004 section II)."""


@hookimpl
def trackbench_register_modalities(registry: Registry) -> None:
    """Register the camera modality."""
    registry.add_modality(CAMERA)
