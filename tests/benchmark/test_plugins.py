"""Plugin discovery through entry points, with fake distributions as pluggy's own tests do."""

import re
import os
import sys
import types
from dataclasses import dataclass

import pandas as pd
import pytest
from click.testing import CliRunner

from benchmark import Tracker, hookimpl
from benchmark.cli import main
from benchmark.errors import PluginError
from benchmark.modality import Modality
from benchmark.model import Frame, Sequence, SequenceInfo
from benchmark.plugins import DISABLE_ENV, REGISTER_HOOKS, load_registry
from benchmark.registry import Origin


class ThirdParty(Tracker):
    name, version, modality = "acme", "0.3", "camera"

    def reset(self, info, rng, init=None):
        pass

    def step(self, frame):
        return None


def plugin_module(monkeypatch, module_name, **hooks):
    """A plugin module with these hook implementations (marked with a plain ``hookimpl`` unless marked already)."""
    module = types.ModuleType(module_name)
    for hook_name, function in hooks.items():
        setattr(module, hook_name, function if hasattr(function, "trackbench_impl") else hookimpl(function))
    monkeypatch.setitem(sys.modules, module_name, module)
    return module


def register_third_party(registry):
    registry.add_tracker(ThirdParty)


def test_third_party_tracker_is_found_through_its_entry_point(monkeypatch, installed):
    plugin_module(monkeypatch, "acme_trackers", trackbench_register_trackers=register_third_party)
    installed("acme-trackers", [("acme", "acme_trackers")])
    registry = load_registry()
    entry = registry.trackers["acme"]
    assert entry.tracker_class is ThirdParty
    assert (entry.origin.plugin, entry.origin.distribution) == ("acme", "acme-trackers 0.3")


def test_first_party_plugins_come_through_the_same_entry_points():
    registry = load_registry()
    for name in ("hough",):
        assert registry.trackers[name].origin.distribution.startswith("subsea-trackbench ")


def test_a_plugin_that_fails_to_import_is_left_out_and_named_or_is_an_error_when_strict(installed):
    installed("broken-dist", [("broken", "no_such_module_anywhere")])
    message = r"plugin 'broken' \(broken-dist 0.3\) failed to import.*--disable broken"
    registry = load_registry()
    assert len(registry.problems) == 1 and re.match(message, registry.problems[0])
    assert "hough" in registry.trackers
    with pytest.raises(PluginError, match=message):
        load_registry(strict=True)


def test_a_disabled_plugin_is_not_imported(monkeypatch, installed):
    installed("broken-dist", [("broken", "no_such_module_anywhere")])
    assert "hough" in load_registry(disable=["broken"]).trackers
    monkeypatch.setenv(DISABLE_ENV, "broken, hough")
    assert "hough" not in load_registry().trackers


def test_a_duplicate_tracker_name_is_named(monkeypatch, installed):
    def register_copy(registry):
        registry.add_tracker(ThirdParty)

    plugin_module(monkeypatch, "acme_trackers", trackbench_register_trackers=register_third_party)
    plugin_module(monkeypatch, "copycat_trackers", trackbench_register_trackers=register_copy)
    installed("acme-trackers", [("acme", "acme_trackers")])
    installed("copycat", [("copycat", "copycat_trackers")])
    # pluggy calls the plugin registered last first: copycat adds 'acme', then acme is refused.
    with pytest.raises(PluginError, match=r"tracker name 'acme' is already registered by plugin") as info:
        load_registry(strict=True)
    message = str(info.value)
    assert "plugin 'acme' (acme-trackers 0.3)" in message and "by plugin 'copycat'" in message


def test_a_tracker_whose_params_are_not_frozen_costs_only_itself(monkeypatch, installed):
    @dataclass
    class Loose:
        size: int = 1

    class Unfrozen(ThirdParty):
        name = "acme-loose"
        Params = Loose

    def register(registry):
        registry.add_tracker(Unfrozen)
        registry.add_tracker(ThirdParty)

    plugin_module(monkeypatch, "acme_trackers", trackbench_register_trackers=register)
    installed("acme-trackers", [("acme", "acme_trackers")])
    listing = CliRunner().invoke(main, ["list"])
    assert listing.exit_code == 1, listing.output
    assert "tracker 'acme-loose': Params must be a frozen dataclass; the tracker is left out" in listing.output
    registry = load_registry()
    assert "acme" in registry.trackers and "acme-loose" not in registry.trackers and "hough" in registry.trackers
    assert CliRunner().invoke(main, ["--strict-plugins", "list"]).exit_code == 2


def test_an_unknown_parameter_is_named(monkeypatch, installed):
    def register(registry):
        registry.add_tracker(ThirdParty, name="acme-fast", params={"speed": 2})

    plugin_module(monkeypatch, "acme_trackers", trackbench_register_trackers=register)
    installed("acme-trackers", [("acme", "acme_trackers")])
    with pytest.raises(PluginError, match=r"plugin 'acme'.*no parameter 'speed'"):
        load_registry(strict=True)


def test_a_misspelt_hook_fails_loudly(monkeypatch, installed):
    plugin_module(monkeypatch, "acme_trackers", trackbench_register_trackerz=register_third_party)
    installed("acme-trackers", [("acme", "acme_trackers")])
    registry = load_registry()
    assert "acme" not in registry.trackers and "hough" in registry.trackers
    assert [problem.split(":")[0] for problem in registry.problems] == ["plugin 'acme' (acme-trackers 0.3)"]
    with pytest.raises(PluginError, match=r"plugin 'acme'.*trackbench_register_trackerz"):
        load_registry(strict=True)


def test_a_tracker_plugin_that_implements_the_commands_hook_fails_loudly(monkeypatch, installed):
    plugin_module(
        monkeypatch,
        "acme_trackers",
        trackbench_register_trackers=register_third_party,
        trackbench_register_commands=lambda registry: None,
    )
    installed("acme-trackers", [("acme", "acme_trackers")])
    registry = load_registry()
    assert "acme" not in registry.trackers and "hough" in registry.trackers
    assert registry.problems == [
        "plugin 'acme' (acme-trackers 0.3) of the 'trackbench' entry-point group implements "
        "trackbench_register_commands, which is called only on the plugins of another group "
        "(left out: its trackers are unavailable)"
    ]
    with pytest.raises(PluginError, match=r"plugin 'acme'.*trackbench_register_commands"):
        load_registry(strict=True)


def test_an_exception_in_a_hook_is_named(monkeypatch, installed):
    def register(registry):
        raise RuntimeError("database offline")

    plugin_module(monkeypatch, "acme_trackers", trackbench_register_datasets=register)
    installed("acme-trackers", [("acme", "acme_trackers")])
    with pytest.raises(PluginError, match=r"plugin 'acme'.*trackbench_register_datasets.*database offline"):
        load_registry(strict=True)


@pytest.mark.parametrize("failure", [RuntimeError("database offline"), SystemExit(0)], ids=["raises", "exits"])
def test_a_plugin_whose_hook_fails_is_left_out_with_what_it_added_and_the_others_are_kept(
    monkeypatch, installed, failure
):
    def register(registry):
        registry.add_tracker(ThirdParty)
        raise failure

    def register_other(registry):
        registry.add_tracker(ThirdParty, name="acme-other")

    plugin_module(monkeypatch, "acme_trackers", trackbench_register_trackers=register)
    plugin_module(monkeypatch, "other_trackers", trackbench_register_trackers=register_other)
    installed("acme-trackers", [("acme", "acme_trackers")])
    installed("other", [("other", "other_trackers")])
    registry = load_registry()
    assert "acme" not in registry.trackers
    assert {"acme-other", "hough"} <= set(registry.trackers)
    (problem,) = registry.problems
    assert problem.startswith("plugin 'acme' (acme-trackers 0.3) raised in trackbench_register_trackers")
    with pytest.raises(PluginError, match=r"^plugin 'acme' \(acme-trackers 0.3\) raised"):
        load_registry(strict=True)


def test_a_plugin_that_exits_at_import_is_a_warning_and_a_failed_exit_status(monkeypatch, installed, tmp_path):
    (tmp_path / "exiting_plugin.py").write_text("import sys\nsys.exit(0)\n")
    monkeypatch.syspath_prepend(str(tmp_path))
    installed("exiting", [("exiting", "exiting_plugin")])
    listing = CliRunner().invoke(main, ["list"])
    assert listing.exit_code == 1, listing.output
    assert "plugin 'exiting' (exiting 0.3) failed to import 'exiting_plugin': SystemExit" in listing.output
    assert "hough" in listing.output
    assert CliRunner().invoke(main, ["--strict-plugins", "list"]).exit_code == 2


@pytest.mark.parametrize(
    ("source", "changed"),
    [
        ("import numpy\nnumpy.mean = lambda *a, **k: 0.0\n", "numpy.mean"),
        ("import os\nos.chdir('/')\n", "the working folder"),
    ],
    ids=["numpy", "folder"],
)
def test_a_plugin_that_changes_what_trackers_share_at_import_is_left_out_and_the_process_restored(
    monkeypatch, installed, tmp_path, request, source, changed
):
    import numpy as np

    mean = np.mean
    monkeypatch.chdir(tmp_path)
    module = f"patching_{request.node.callspec.id}"
    (tmp_path / f"{module}.py").write_text(source)
    monkeypatch.syspath_prepend(str(tmp_path))
    installed("patching", [("patching", module)])
    registry = load_registry()
    assert np.mean is mean and np.mean([1.0, 3.0]) == 2.0 and os.getcwd() == str(tmp_path)
    (problem,) = [problem for problem in registry.problems if "patching" in problem]
    assert problem.startswith(f"plugin 'patching' (patching 0.3) changed {changed} when imported")
    assert "hough" in registry.trackers
    monkeypatch.delitem(sys.modules, module)  # imported afresh
    with pytest.raises(PluginError, match=f"changed {changed}"):
        load_registry(strict=True)
    assert np.mean is mean and os.getcwd() == str(tmp_path)


def test_an_invalid_suite_file_costs_only_its_suite(monkeypatch, tmp_path):
    import trackbench_suites

    shipped = list(trackbench_suites.suite_files())
    bad = tmp_path / "zz_broken.toml"
    bad.write_text("[suite]\nname = 'broken'\nkind = 'camera'\n[[sequence]]\nname = 'a'\nfocal_px = 'wide'\n")
    monkeypatch.setattr(trackbench_suites, "suite_files", lambda: iter([*shipped, bad]))
    registry = load_registry()
    assert "broken" not in registry.suites and {"camera", "sonar", "stereo"} <= set(registry.suites)
    (problem,) = registry.problems
    assert problem.startswith("plugin 'suites' (subsea-trackbench ") and "zz_broken.toml" in problem
    assert problem.endswith("(suite left out)")
    with pytest.raises(PluginError, match=r"zz_broken\.toml"):
        load_registry(strict=True)

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
    installed("acme-trackers", [("acme", "acme_trackers")])
    arguments = ["run", "--suite", "acme-suite", "--tracker", "acme", "--tracker", "blind"]
    result = CliRunner().invoke(main, [*arguments, "--in-process", "--out", str(tmp_path)])
    assert result.exit_code == 0, result.output
    board = pd.read_csv(tmp_path / "leaderboard.csv")
    row = board[(board.tracker == "acme") & (board.dataset == "acme-suite/mini")].iloc[0]
    assert row["rank"] == 1 and row["correct_pct"] == 100.0
    assert board[(board.tracker == "blind") & (board.dataset == "acme-suite/mini")].iloc[0]["rank"] == 2


# ---------------------------------------------------------------- entry-point names
def test_two_distributions_offering_the_same_plugin_name_are_an_error_naming_both(monkeypatch, installed):
    plugin_module(monkeypatch, "acme_trackers", trackbench_register_trackers=register_third_party)
    plugin_module(monkeypatch, "impostor_trackers", trackbench_register_trackers=register_third_party)
    installed("acme-trackers", [("acme", "acme_trackers")])
    installed("impostor", [("acme", "impostor_trackers")], version="6.6")
    with pytest.raises(PluginError, match=r"plugin name 'acme' .* is taken twice") as info:
        load_registry()
    assert "by acme-trackers 0.3 and impostor 6.6" in str(info.value) and "--disable acme" in str(info.value)
    assert "acme" not in load_registry(disable=["acme"]).trackers


def test_a_distribution_seen_twice_on_the_path_is_no_duplicate(monkeypatch, installed):
    plugin_module(monkeypatch, "acme_trackers", trackbench_register_trackers=register_third_party)
    installed("acme-trackers", [("acme", "acme_trackers")])
    installed("acme-trackers", [("acme", "acme_trackers")])
    installed("acme-trackers", [("acme", "acme_trackers")], version="0.2.dev0")
    entry = load_registry().trackers["acme"]
    assert entry.tracker_class is ThirdParty
    assert entry.origin.distribution == "acme-trackers 0.3"


# ---------------------------------------------------------------- pluggy's ordering and wrappers
def named_tracker(tracker_name):
    return type(f"Tracker_{tracker_name}", (ThirdParty,), {"name": tracker_name})


def adds(*names):
    def register(registry):
        for tracker_name in names:
            registry.add_tracker(named_tracker(tracker_name))

    return register


def test_tryfirst_and_trylast_order_the_implementations_of_a_hook(monkeypatch, installed):
    plugin_module(monkeypatch, "early_trackers", trackbench_register_trackers=hookimpl(tryfirst=True)(adds("early")))
    plugin_module(monkeypatch, "last_trackers", trackbench_register_trackers=hookimpl(trylast=True)(adds("last")))
    plugin_module(monkeypatch, "plain_trackers", trackbench_register_trackers=adds("plain"))
    for name in ("early", "last", "plain"):
        installed(f"{name}-dist", [(name, f"{name}_trackers")])
    order = list(load_registry().trackers)
    # Without the markers pluggy would call plain, last, early (last registered first), then the first-party plugins.
    assert order[:2] == ["early", "plain"]
    assert order[-1] == "last" and order.index("plain") < order.index("hough") < order.index("last")


def test_a_wrapper_sees_the_registry_before_and_after_the_other_implementations(monkeypatch, installed):
    seen = {}

    @hookimpl(wrapper=True)
    def wrap(registry):
        seen["before"] = list(registry.trackers)
        result = yield
        seen["after"] = list(registry.trackers)
        registry.add_tracker(named_tracker("after-all"))
        return result

    plugin_module(monkeypatch, "wrapping_trackers", trackbench_register_trackers=wrap)
    plugin_module(monkeypatch, "acme_trackers", trackbench_register_trackers=register_third_party)
    installed("wrapping-dist", [("wrapping", "wrapping_trackers")])
    installed("acme-trackers", [("acme", "acme_trackers")])
    registry = load_registry()
    assert seen["before"] == []
    assert {"acme", "hough"} <= set(seen["after"]) and "after-all" not in seen["after"]
    assert list(registry.trackers)[-1] == "after-all"
    assert registry.trackers["after-all"].origin.plugin == "wrapping"
    assert registry.trackers["acme"].origin.plugin == "acme"


# ---------------------------------------------------------------- hook order: modalities, trackers, datasets
class Columns:
    error_columns = ("err_range_m",)

    def check(self, estimate):
        pass

    def score(self, estimate, truth, info):
        return None, (float("nan"),)


@dataclass(frozen=True)
class ScanSequence(Sequence):
    name: str

    @property
    def info(self):
        return SequenceInfo(self.name, "scan", 1)

    def frames(self):
        yield Frame(0, 1.0)


SCAN = Modality("scan", float, float, float, Columns(), scene_kinds={"scan-sim": lambda t, w: ScanSequence(t["name"])})


class ScanTracker(ThirdParty):
    name, modality = "scanner", "scan"


def test_hooks_run_modalities_then_trackers_then_datasets(monkeypatch, installed):
    calls = []

    def register_modalities(registry):
        calls.append(("scan-modality", "modalities"))
        registry.add_modality(SCAN)

    def register_trackers(registry):
        calls.append(("scan-trackers", "trackers"))
        registry.add_tracker(ScanTracker)

    def register_datasets(registry):
        calls.append(("scan-trackers", "datasets"))
        registry.add_suite("scans", [registry.scene_kinds["scan-sim"]({"name": "scans/a"}, "here")])

    # The trackers' plugin is loaded before the modality's: only calling every plugin's modalities hook
    # first lets its tracker find its modality.
    plugin_module(
        monkeypatch,
        "scan_trackers",
        trackbench_register_trackers=register_trackers,
        trackbench_register_datasets=register_datasets,
    )
    plugin_module(monkeypatch, "scan_modality", trackbench_register_modalities=register_modalities)
    installed("scan-trackers", [("scan-trackers", "scan_trackers")])
    installed("scan-modality", [("scan-modality", "scan_modality")])
    registry = load_registry()
    assert REGISTER_HOOKS == (
        "trackbench_register_modalities",
        "trackbench_register_metrics",
        "trackbench_register_trackers",
        "trackbench_register_datasets",
    )
    assert calls == [("scan-modality", "modalities"), ("scan-trackers", "trackers"), ("scan-trackers", "datasets")]
    assert registry.modalities["scan"] is SCAN and registry.trackers["scanner"].origin.plugin == "scan-trackers"
    assert registry.suites["scans"].sequences == (ScanSequence("scans/a"),)
    assert {"camera", "sonar", "stereo", "scan"} <= set(registry.modalities)


def test_a_plugin_may_register_a_modality_and_its_trackers_in_one_module(monkeypatch, installed):
    def register_modalities(registry):
        registry.add_modality(SCAN)

    def register_trackers(registry):
        registry.add_tracker(ScanTracker)

    plugin_module(
        monkeypatch,
        "scan_plugin",
        trackbench_register_modalities=register_modalities,
        trackbench_register_trackers=register_trackers,
    )
    installed("scan-plugin", [("scan", "scan_plugin")])
    registry = load_registry()
    assert registry.trackers["scanner"].modality == "scan"
    assert registry.modalities["scan"] is SCAN
    assert registry.trackers["scanner"].origin.distribution == "scan-plugin 0.3"


def register_scan(registry):
    registry.add_modality(SCAN)


def register_scan_again(registry):
    registry.add_modality(SCAN)


@pytest.mark.parametrize(
    ("second_hook", "message"),
    [
        # Two functions: the plugin that adds the modality a second time is named.
        (register_scan_again, r"^plugin 'scan-one' \(scan-one 0.3\): modality 'scan' is already"),
        # One plain function serving both plugins cannot be told apart: both are named.
        (register_scan, r"^plugin 'scan-one or scan-two' \(scan-one 0.3 or scan-two 0.3\): modality 'scan' is already"),
    ],
)
def test_a_modality_added_twice_names_the_plugin_that_did_it(monkeypatch, installed, second_hook, message):
    plugin_module(monkeypatch, "scan_one", trackbench_register_modalities=second_hook)
    plugin_module(monkeypatch, "scan_two", trackbench_register_modalities=register_scan)
    installed("scan-one", [("scan-one", "scan_one")])
    installed("scan-two", [("scan-two", "scan_two")])
    with pytest.raises(PluginError, match=message):
        load_registry(strict=True)


def test_methods_of_one_plugin_class_are_told_apart_by_their_object(monkeypatch, installed):
    class TrackerPlugin:
        def __init__(self, tracker_name):
            self.tracker_name = tracker_name

        @hookimpl
        def trackbench_register_trackers(self, registry):
            registry.add_tracker(named_tracker(self.tracker_name))

    monkeypatch.setitem(sys.modules, "p_trackers", types.SimpleNamespace(plugin=TrackerPlugin("p")))
    monkeypatch.setitem(sys.modules, "q_trackers", types.SimpleNamespace(plugin=TrackerPlugin("q")))
    for name in ("p", "q"):
        installed(f"{name}-dist", [(name, f"{name}_trackers:plugin")])
    trackers = load_registry().trackers
    assert (trackers["p"].origin, trackers["q"].origin) == (Origin("p", "p-dist 0.3"), Origin("q", "q-dist 0.3"))


# ---------------------------------------------------------------- exceptions name the plugin that raised
def raise_offline(registry):
    raise RuntimeError("database offline")


def test_an_exception_names_its_plugin_after_another_plugin_ran_in_the_same_call(monkeypatch, installed):
    plugin_module(monkeypatch, "acme_trackers", trackbench_register_trackers=raise_offline)
    plugin_module(monkeypatch, "helper_trackers", trackbench_register_trackers=adds("helped"))
    installed("acme-trackers", [("acme", "acme_trackers")])
    installed("helper-dist", [("helper", "helper_trackers")])  # called before acme
    with pytest.raises(PluginError) as info:
        load_registry(strict=True)
    assert str(info.value) == (
        "plugin 'acme' (acme-trackers 0.3) raised in trackbench_register_trackers: RuntimeError: database offline"
    )


def test_an_exception_names_its_plugin_inside_another_plugin_s_wrapper(monkeypatch, installed):
    @hookimpl(wrapper=True)
    def wrap(registry):
        registry.add_tracker(named_tracker("wrapped"))
        return (yield)

    def deep(registry):
        adds("fine")(registry)
        raise_offline(registry)

    plugin_module(monkeypatch, "wrapping_trackers", trackbench_register_trackers=wrap)
    plugin_module(monkeypatch, "acme_trackers", trackbench_register_trackers=deep)
    installed("acme-trackers", [("acme", "acme_trackers")])
    installed("wrapping-dist", [("wrapping", "wrapping_trackers")])
    with pytest.raises(PluginError, match=r"^plugin 'acme' \(acme-trackers 0.3\) raised in trackbench_register_tr"):
        load_registry(strict=True)


def test_a_bad_addition_after_another_plugin_ran_names_the_plugin_that_made_it(monkeypatch, installed):
    def bad(registry):
        registry.add_tracker(named_tracker("fine-too"))
        registry.add_tracker(ThirdParty, name="acme-bad", params={"speed": 2})

    plugin_module(monkeypatch, "acme_trackers", trackbench_register_trackers=bad)
    plugin_module(monkeypatch, "helper_trackers", trackbench_register_trackers=adds("helped"))
    installed("acme-trackers", [("acme", "acme_trackers")])
    installed("helper-dist", [("helper", "helper_trackers")])
    with pytest.raises(PluginError, match=r"^plugin 'acme' \(acme-trackers 0.3\): .*no parameter 'speed'"):
        load_registry(strict=True)


def test_plugins_sharing_the_closures_of_one_factory_get_their_own_additions(monkeypatch, installed):
    plugin_module(monkeypatch, "x_trackers", trackbench_register_trackers=adds("x"))
    plugin_module(monkeypatch, "y_trackers", trackbench_register_trackers=adds("y"))
    for name in ("x", "y"):
        installed(f"{name}-dist", [(name, f"{name}_trackers")])
    trackers = load_registry().trackers
    assert (trackers["x"].origin, trackers["y"].origin) == (Origin("x", "x-dist 0.3"), Origin("y", "y-dist 0.3"))
