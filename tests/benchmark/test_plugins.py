"""Plugin discovery through entry points, with fake distributions as pluggy's own tests do."""

import importlib.metadata
import sys
import types

import pandas as pd
import pytest
from click.testing import CliRunner

from benchmark import Tracker, hookimpl
from benchmark.cli import main
from benchmark.errors import PluginError
from benchmark.plugins import DISABLE_ENV, load_registry


class ThirdParty(Tracker):
    name, version, modality = "acme", "0.3", "camera"

    def reset(self, info, rng, init=None):
        pass

    def step(self, frame):
        return None


class FakeDistribution:
    def __init__(self, name, entry_points):
        self.metadata = {"name": name}
        self.version = "0.3"
        self.entry_points = [importlib.metadata.EntryPoint(ep, value, "trackbench") for ep, value in entry_points]


def plugin_module(monkeypatch, module_name, **hooks):
    module = types.ModuleType(module_name)
    for hook_name, function in hooks.items():
        setattr(module, hook_name, hookimpl(function))
    monkeypatch.setitem(sys.modules, module_name, module)
    return module


@pytest.fixture
def installed(monkeypatch):
    """Install fake distributions next to the real ones."""
    real = list(importlib.metadata.distributions())
    fakes = []
    monkeypatch.setattr(importlib.metadata, "distributions", lambda: [*real, *fakes])
    return fakes


def register_third_party(registry):
    registry.add_tracker(ThirdParty)


def test_third_party_tracker_is_found_through_its_entry_point(monkeypatch, installed):
    plugin_module(monkeypatch, "acme_trackers", trackbench_register_trackers=register_third_party)
    installed.append(FakeDistribution("acme-trackers", [("acme", "acme_trackers")]))
    registry = load_registry()
    entry = registry.trackers["acme"]
    assert entry.tracker_class is ThirdParty
    assert (entry.origin.plugin, entry.origin.distribution) == ("acme", "acme-trackers 0.3")


def test_first_party_plugins_come_through_the_same_entry_points():
    registry = load_registry()
    for name in ("hough",):
        assert registry.trackers[name].origin.distribution.startswith("subsea-trackbench ")


def test_a_plugin_that_fails_to_import_is_named(installed):
    installed.append(FakeDistribution("broken-dist", [("broken", "no_such_module_anywhere")]))
    with pytest.raises(PluginError, match=r"plugin 'broken' \(broken-dist 0.3\) failed to import.*--disable broken"):
        load_registry()


def test_a_disabled_plugin_is_not_imported(monkeypatch, installed):
    installed.append(FakeDistribution("broken-dist", [("broken", "no_such_module_anywhere")]))
    assert "hough" in load_registry(disable=["broken"]).trackers
    monkeypatch.setenv(DISABLE_ENV, "broken, hough")
    assert "hough" not in load_registry().trackers


def test_a_duplicate_tracker_name_is_named(monkeypatch, installed):
    plugin_module(monkeypatch, "acme_trackers", trackbench_register_trackers=register_third_party)
    plugin_module(monkeypatch, "copycat_trackers", trackbench_register_trackers=register_third_party)
    installed.append(FakeDistribution("acme-trackers", [("acme", "acme_trackers")]))
    installed.append(FakeDistribution("copycat", [("copycat", "copycat_trackers")]))
    with pytest.raises(PluginError, match=r"plugin 'copycat'.*'acme' is already registered by plugin 'acme'"):
        load_registry()


def test_an_unknown_parameter_is_named(monkeypatch, installed):
    def register(registry):
        registry.add_tracker(ThirdParty, name="acme-fast", params={"speed": 2})

    plugin_module(monkeypatch, "acme_trackers", trackbench_register_trackers=register)
    installed.append(FakeDistribution("acme-trackers", [("acme", "acme_trackers")]))
    with pytest.raises(PluginError, match=r"plugin 'acme'.*no parameter 'speed'"):
        load_registry()


def test_a_misspelt_hook_fails_loudly(monkeypatch, installed):
    plugin_module(monkeypatch, "acme_trackers", trackbench_register_trackerz=register_third_party)
    installed.append(FakeDistribution("acme-trackers", [("acme", "acme_trackers")]))
    with pytest.raises(PluginError, match=r"plugin 'acme'.*trackbench_register_trackerz"):
        load_registry()


def test_an_exception_in_a_hook_is_named(monkeypatch, installed):
    def register(registry):
        raise RuntimeError("database offline")

    plugin_module(monkeypatch, "acme_trackers", trackbench_register_datasets=register)
    installed.append(FakeDistribution("acme-trackers", [("acme", "acme_trackers")]))
    with pytest.raises(PluginError, match=r"plugin 'acme'.*trackbench_register_datasets.*database offline"):
        load_registry()


def test_a_third_party_tracker_shows_up_ranked(monkeypatch, installed, fakes, tmp_path):
    class Acme(fakes.Perfect):
        name = "acme"

    def register_trackers(registry):
        registry.add_tracker(Acme)
        registry.add_tracker(fakes.Blind)

    def register_datasets(registry):
        registry.add_suite("acme-suite", [fakes.FakeSequence("acme-suite/mini", n_frames=6)])

    plugin_module(
        monkeypatch,
        "acme_trackers",
        trackbench_register_trackers=register_trackers,
        trackbench_register_datasets=register_datasets,
    )
    installed.append(FakeDistribution("acme-trackers", [("acme", "acme_trackers")]))
    arguments = ["run", "--suite", "acme-suite", "--tracker", "acme", "--tracker", "blind"]
    result = CliRunner().invoke(main, [*arguments, "--jobs", "0", "--out", str(tmp_path)])
    assert result.exit_code == 0, result.output
    board = pd.read_csv(tmp_path / "leaderboard.csv")
    row = board[(board.tracker == "acme") & (board.dataset == "acme-suite/mini")].iloc[0]
    assert row["rank"] == 1 and row["correct_pct"] == 100.0
    assert board[(board.tracker == "blind") & (board.dataset == "acme-suite/mini")].iloc[0]["rank"] == 2
