"""Speed bounds declared through ``trackbench_register_speed_bounds``: collected, checked, attributed."""

from __future__ import annotations

import types

import pytest

from benchmark import hookimpl
from benchmark.errors import PluginError
from benchmark.plugins import entry_points
from benchmark.selection import SelectionError
from benchmark.speed.bounds import SPEED_PLUGINS, SpeedBound, load_bounds
from benchmark.speed.subjects import chosen_subjects

from .fakes import DATASET, Bound, bounds_of, component


def test_the_hook_fills_the_bounds_in_declared_order() -> None:
    bounds = bounds_of()
    assert bounds.subjects == ["fast", "slow", "core step"]
    assert [bound.bound for bound in bounds.of("fast")] == ["the same work", "a peer not installed"]
    assert all(origin.plugin == "fake-speed-0" for origin in bounds.origins)


def plugin_adding(*added: object) -> types.SimpleNamespace:
    @hookimpl
    def trackbench_register_speed_bounds(registry):  # type: ignore[no-untyped-def]
        for bound in added:
            registry.add_bound(bound)

    return types.SimpleNamespace(trackbench_register_speed_bounds=trackbench_register_speed_bounds)


@pytest.mark.parametrize(
    ("added", "message"),
    [
        (("not a bound",), "is not a benchmark.speed.bounds.SpeedBound"),
        ((SpeedBound("x", "b", Bound, DATASET), SpeedBound("x", "b", Bound, DATASET)), "already declared"),
        ((SpeedBound("x", "b", Bound, DATASET), SpeedBound("x", "c", Bound, "fake/S2")), "one dataset"),
        ((SpeedBound("x", "b", Bound, DATASET), SpeedBound("x", "c", Bound, DATASET, ours=component)), "one 'ours'"),
    ],
)
def test_a_bad_declaration_is_an_error_naming_the_plugin(added: tuple[object, ...], message: str) -> None:
    with pytest.raises(PluginError, match=f"plugin 'fake-speed-0'.*{message}"):
        bounds_of(plugin_adding(*added))


def test_unknown_subjects_are_refused_listing_those_with_a_bound() -> None:
    bounds = bounds_of()
    assert chosen_subjects(bounds, []) == ["core step", "fast", "slow"]
    assert chosen_subjects(bounds, ["slow", "fast", "slow"]) == ["slow", "fast"]
    listed = "no speed bound is declared for 'nope'; subjects with a bound: core step, fast, slow"
    with pytest.raises(SelectionError, match=listed):
        chosen_subjects(bounds, ["fast", "nope"])


def test_every_first_party_tracker_plugin_declares_its_bounds_in_the_speed_group() -> None:
    declared = entry_points(SPEED_PLUGINS.name)
    assert {"condensation", "sonar", "stereo_ekf", "foresti", "segmentation", "texture", "hough"} <= declared.keys()
    bounds = load_bounds(strict=True)
    expected = {
        "condensation",
        "condensation-thesis",
        "sonar_pf",
        "sonar_detector",
        "EKF predict+update",
        "foresti_lines",
        "foresti_ekf",
        "segmentation",
        "texture",
        "hough",
    }
    assert expected <= set(bounds.subjects)
    assert all(bound.goal is not None for name in expected - {"texture"} for bound in bounds.of(name)[:1])
