"""The texture plugin's hook registers its tracker as a camera tracker that learns."""

from __future__ import annotations

import trackbench_texture
from trackbench_texture import TextureParams, TextureTracker

import benchmark.plugins
from benchmark.tracker import Learns


def test_the_hook_registers_the_texture_tracker():
    # The registry is loaded without any plugin named "texture", so that the
    # hook's own registration is what is tested, entry point or not.
    registry = benchmark.plugins.load_registry(disable=["texture"])
    assert "texture" not in registry.trackers
    trackbench_texture.trackbench_register_trackers(registry)
    entry = registry.trackers["texture"]
    assert entry.tracker_class is TextureTracker
    assert entry.modality == "camera" and entry.version == "1.0"
    assert entry.params == TextureParams()
    assert isinstance(entry.create(), Learns)
