"""The raw baseline is registered through the trackbench entry point."""

from __future__ import annotations

from trackbench_stereo_raw import StereoRawTracker

import benchmark.plugins


def test_raw_baseline_is_registered_as_a_stereo_tracker():
    entry = benchmark.plugins.load_registry().trackers["stereo_raw"]
    assert entry.tracker_class is StereoRawTracker
    assert entry.modality == "stereo"
    assert entry.origin.plugin == "stereo_raw"
    assert entry.params.window == 15


def test_disabling_the_plugin_removes_the_tracker():
    assert "stereo_raw" not in benchmark.plugins.load_registry(disable=["stereo_raw"]).trackers
