"""The segmentation tracker is registered through the trackbench entry point."""

from __future__ import annotations

from trackbench_segmentation import SegmentationTracker

import benchmark.plugins


def test_segmentation_is_registered_as_a_camera_tracker():
    entry = benchmark.plugins.load_registry().trackers["segmentation"]
    assert entry.tracker_class is SegmentationTracker
    assert entry.modality == "camera" and entry.version == SegmentationTracker.version
    assert entry.origin.plugin == "segmentation"
    assert entry.params == SegmentationTracker.Params()


def test_disabling_the_plugin_removes_the_tracker():
    assert "segmentation" not in benchmark.plugins.load_registry(disable=["segmentation"]).trackers
