"""The scene kinds of the built-in modalities, which the suite loader builds sequences with."""

from __future__ import annotations

from collections.abc import Mapping

import pytest

from benchmark.modalities.camera.modality import CAMERA
from benchmark.modalities.sonar.modality import SONAR
from benchmark.modalities.stereo.modality import STEREO
from benchmark.modality import SceneFactory


@pytest.fixture(scope="session")
def kinds() -> Mapping[str, SceneFactory]:
    """Scene kind name to factory, as ``Registry.scene_kinds`` has them once the built-in modalities are registered."""
    return {kind: factory for modality in (CAMERA, SONAR, STEREO) for kind, factory in modality.scene_kinds.items()}
