"""The stereo EKF and its variants are registered through the trackbench entry point."""

from __future__ import annotations

from trackbench_stereo_ekf import PAPER, StereoEkfTracker

import benchmark.plugins


def test_the_filter_and_its_variants_are_registered_as_stereo_trackers():
    trackers = benchmark.plugins.load_registry().trackers
    for name in ("stereo_ekf", "stereo_ekf-paper", "stereo_ekf-eq18"):
        entry = trackers[name]
        assert entry.tracker_class is StereoEkfTracker
        assert entry.modality == "stereo"
        assert entry.origin.plugin == "stereo_ekf"
    assert trackers["stereo_ekf"].params == StereoEkfTracker.Params()
    assert trackers["stereo_ekf"].params.covariance == "eq20"
    assert trackers["stereo_ekf-eq18"].params.covariance == "eq18"
    for name in ("stereo_ekf-paper", "stereo_ekf-eq18"):
        params = trackers[name].params
        assert {key: getattr(params, key) for key in PAPER} == PAPER


def test_defaults_are_the_values_of_table_5():
    params = StereoEkfTracker.Params()
    assert params.control_acceleration_mps2 == 0.003
    assert params.sigma_a_mps2 == 0.40
    assert params.pixel_variance_px2 == 0.11**2 / 2


def test_disabling_the_plugin_removes_its_trackers():
    trackers = benchmark.plugins.load_registry(disable=["stereo_ekf"]).trackers
    assert not any(name.startswith("stereo_ekf") for name in trackers)
