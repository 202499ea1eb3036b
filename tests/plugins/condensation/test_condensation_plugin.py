"""The condensation tracker and its variants are registered through the trackbench entry point.

Each test loads the plugins afresh with every other entry point of the
group blocked but the built-in modalities, so that the tests see this
plugin's trackers alone.
"""

from __future__ import annotations

import dataclasses
import importlib.metadata

from click.testing import CliRunner
from trackbench_condensation import VARIANTS, CondensationTracker

import benchmark.plugins
from benchmark.cli import main

OTHERS = sorted(
    ep.name
    for ep in importlib.metadata.entry_points(group="trackbench")
    if ep.name != "condensation" and not ep.name.startswith("modality-")
)
"""Every other plugin but the modalities, which the tracker's modality needs."""


def registry():
    return benchmark.plugins.load_registry(disable=OTHERS)


def test_tracker_and_variants_are_registered_with_their_parameters():
    trackers = registry().trackers
    names = {"condensation", "condensation-thesis", "condensation-fast", "condensation-8d", "condensation-centre"}
    assert names <= set(trackers)
    for name in names:
        entry = trackers[name]
        assert entry.tracker_class is CondensationTracker
        assert entry.modality == "camera" and entry.origin.plugin == "condensation"
        expected = CondensationTracker.make_params(VARIANTS.get(name, {}))
        assert entry.params == expected
    assert trackers["condensation"].params == CondensationTracker.Params()
    fast = trackers["condensation-fast"].params
    assert (fast.n_particles, fast.filter_size_px, fast.sample_distance_px) == (300, 5, 20.0)
    assert trackers["condensation-8d"].params.width_skew_velocities
    assert trackers["condensation-centre"].params.centre_weight > 0
    # Variants differ in parameters, hence in their cache keys.
    assert len({trackers[name].cache_key for name in names}) == len(names)


def test_defaults_carry_the_thesis_values():
    params = CondensationTracker.Params()
    assert params.n_particles == 500 and params.filter_size_px == 11 and params.sample_distance_px == 20.0
    table_5_1 = (params.var_d_px2, params.var_alpha_deg2, params.var_w_px2, params.var_beta_deg2, params.var_v_d_px2)
    assert table_5_1 == (0.5, 0.01, 4.0, 0.1, 8.0)
    thesis = CondensationTracker.make_params(VARIANTS["condensation-thesis"])
    assert (thesis.weight_exponent, thesis.var_v_alpha_deg2, thesis.redetect_fraction) == (1.0, 0.005, 0.0)
    assert not params.width_skew_velocities and params.centre_weight == 0.0 and params.reinit_every == 0


def test_list_command_shows_the_variants_and_their_parameters():
    result = CliRunner().invoke(main, [arg for name in OTHERS for arg in ("--disable", name)] + ["list"])
    assert result.exit_code == 0, result.output
    for name in ("condensation-fast", "condensation-8d", "condensation-centre"):
        assert name in result.output
    for field in dataclasses.fields(CondensationTracker.Params):
        assert field.name in result.output


def test_disabling_the_plugin_removes_all_its_trackers():
    trackers = benchmark.plugins.load_registry(disable=[*OTHERS, "condensation"]).trackers
    assert not any(name.startswith("condensation") for name in trackers)
