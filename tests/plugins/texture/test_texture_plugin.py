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
    assert entry.modality == "camera" and entry.version == "2.0"
    assert entry.params == TextureParams()
    assert isinstance(entry.create(), Learns)


def test_the_paper_variant_measures_on_the_frame_as_it_is():
    registry = benchmark.plugins.load_registry(disable=["texture"])
    trackbench_texture.trackbench_register_trackers(registry)
    paper = registry.trackers["texture-paper"]
    assert paper.tracker_class is TextureTracker
    assert paper.params == TextureParams(**trackbench_texture.params.PAPER)
    assert paper.params != registry.trackers["texture"].params
    assert paper.params.working_height_px == 0 and paper.params.normalisation == "none"
    assert paper.params.border_pairing == "sides" and paper.params.border_search == "strip"
