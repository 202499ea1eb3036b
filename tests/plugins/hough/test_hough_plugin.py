"""The Hough baseline and its paper variant are registered through the trackbench entry point."""

from __future__ import annotations

from trackbench_hough import VARIANTS, HoughTracker

import benchmark.plugins


def test_hough_is_registered_as_a_camera_tracker():
    entry = benchmark.plugins.load_registry().trackers["hough"]
    assert entry.tracker_class is HoughTracker
    assert entry.modality == "camera" and entry.version == "2.0"
    assert entry.origin.plugin == "hough"
    assert entry.params == HoughTracker.Params()


def test_the_paper_variant_has_the_fixed_thresholds_and_pixel_sizes():
    entry = benchmark.plugins.load_registry().trackers["hough-paper"]
    assert entry.tracker_class is HoughTracker
    params = entry.params
    assert (params.edge_rule, params.edge_step, params.log_sigma) == ("step", 12.0, 3.0)
    assert params.reference_side_px is None and params.max_width_px == 100.0
    assert params.vote_fraction == params.partner_fraction == 0.3
    assert set(VARIANTS) == {"hough-paper"}


def test_disabling_the_plugin_removes_the_trackers():
    trackers = benchmark.plugins.load_registry(disable=["hough"]).trackers
    assert "hough" not in trackers and "hough-paper" not in trackers
