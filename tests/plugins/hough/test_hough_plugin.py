"""The Hough baseline is registered through the trackbench entry point."""

from __future__ import annotations

from trackbench_hough import HoughTracker

import benchmark.plugins


def test_hough_is_registered_as_a_camera_tracker():
    entry = benchmark.plugins.load_registry().trackers["hough"]
    assert entry.tracker_class is HoughTracker
    assert entry.modality == "camera" and entry.version == "1.0"
    assert entry.origin.plugin == "hough"
    assert entry.params == HoughTracker.Params()


def test_disabling_the_plugin_removes_the_tracker():
    assert "hough" not in benchmark.plugins.load_registry(disable=["hough"]).trackers
