"""Tests of benchmark.registry: modalities, trackers and suites, checked and attributed to their plugin."""

import dataclasses
import importlib
import re
import sys

import pytest

from benchmark.errors import PluginError
from benchmark.identity import code_digest
from benchmark.metrics import RATES
from benchmark.metrics.robustness import FAILURES
from benchmark.modalities.camera.modality import CAMERA
from benchmark.modalities.sonar.modality import SONAR
from benchmark.modality import ANY_FILE, Modality, Reader
from benchmark.model import Frame, Sequence, SequenceInfo
from benchmark.registry import Origin, Registry
from benchmark.tracker import Tracker


@dataclasses.dataclass(frozen=True)
class Knobs:
    size: int = 3


class Good(Tracker):
    name, version, modality = "good", "1.0", "camera"
    Params = Knobs

    def reset(self, info, rng, init=None):
        pass

    def step(self, frame):
        return None


class Empty(Sequence):
    def __init__(self, name, modality="camera"):
        self._info = SequenceInfo(name, modality, 0)

    @property
    def info(self):
        return self._info

    def frames(self):
        return iter(())


def make(**attributes):
    return type("Variant", (Good,), attributes)


@pytest.fixture
def registry():
    registry = Registry()
    with registry.acting_for(Origin("modality-camera", "subsea-trackbench 1.0")):
        registry.add_modality(CAMERA)
    with registry.acting_for(Origin("acme", "acme-trackers 2.0")):
        yield registry


def test_a_tracker_and_its_variant_are_registered(registry):
    entry = registry.add_tracker(Good)
    fast = registry.add_tracker(Good, name="good-fast", params={"size": 1})
    assert registry.trackers["good"] is entry and entry.params == Knobs()
    assert fast.params == Knobs(1) and fast.cache_key != entry.cache_key
    assert entry.origin.distribution == "acme-trackers 2.0"
    assert isinstance(fast.create(), Good) and fast.create().params == Knobs(1)


@pytest.mark.parametrize(
    "tracker_class, message",
    [
        (object, "not a subclass"),
        (make(name=""), "non-empty str 'name'"),
        (make(version=None), "'version'"),
        (make(modality="lidar"), "modality 'lidar'"),
        (make(Params=dataclasses.make_dataclass("P", [("a", int, dataclasses.field(default=1))])), "frozen"),
        (make(Params=dataclasses.make_dataclass("P", [("a", int)], frozen=True)), "default"),
        (type("Abstract", (Tracker,), {"name": "a", "version": "1", "modality": "camera"}), "does not implement"),
    ],
)
def test_an_invalid_tracker_class_costs_only_itself_and_names_the_plugin(registry, tracker_class, message):
    assert registry.add_tracker(tracker_class) is None
    good = registry.add_tracker(Good)
    [problem] = registry.problems
    assert problem.startswith("plugin 'acme' (acme-trackers 2.0): ") and message in problem
    assert problem.endswith("; the tracker is left out")
    assert list(registry.trackers) == ["good"] and registry.trackers["good"] is good


def test_duplicate_tracker_name_names_both_plugins(registry):
    registry.add_tracker(Good)
    with registry.acting_for(Origin("copycat")):
        assert registry.add_tracker(Good) is None
    [problem] = registry.problems
    assert re.match(r"plugin 'copycat'.*'good' is already registered by plugin 'acme'", problem)
    assert registry.trackers["good"].origin.plugin == "acme"


def test_unknown_parameter_names_the_plugin(registry):
    assert registry.add_tracker(Good, name="typo", params={"sise": 2}) is None
    assert re.match(r"plugin 'acme'.*no parameter 'sise'", registry.problems[0]) and "typo" not in registry.trackers


def test_with_params_checks_names(registry):
    entry = registry.add_tracker(Good)
    assert entry.with_params({"size": "9"}).params == Knobs(9)
    with pytest.raises(Exception, match="no parameter 'nope'"):
        entry.with_params({"nope": 1})


def test_suites_and_sequence_lookup(registry):
    registry.add_suite("mini", [Empty("mini/a"), Empty("mini/b")])
    assert registry.sequence("mini/b").info.name == "mini/b"
    with pytest.raises(KeyError, match="known: mini/a, mini/b"):
        registry.sequence("mini/c")


def test_duplicate_suites_and_sequences_are_refused(registry):
    registry.add_suite("mini", [Empty("mini/a")])
    with pytest.raises(PluginError, match="suite 'mini' is already registered"):
        registry.add_suite("mini", [])
    with pytest.raises(PluginError, match="'mini/a' is already registered"):
        registry.add_suite("other", [Empty("mini/a")])
    with pytest.raises(PluginError, match="not a benchmark.model.Sequence"):
        registry.add_suite("bad", [Frame(0, None)])


# ---------------------------------------------------------------- unregistered modalities
def test_a_tracker_of_a_modality_nobody_registered_is_refused_naming_it(registry):
    assert registry.add_tracker(make(name="scanner", modality="lidar")) is None
    assert re.match(r"plugin 'acme'.*modality 'lidar', which no plugin registered", registry.problems[0])
    assert "registered: camera" in registry.problems[0] and "scanner" not in registry.trackers
    assert registry.add_tracker(make(name="pinger", modality="sonar")) is None
    assert re.search(r"modality 'sonar'.*registered: camera", registry.problems[1])
    registry.add_modality(SONAR)
    assert registry.add_tracker(make(name="pinger", modality="sonar")).modality == "sonar"


def test_a_tracker_needs_a_registered_modality_even_in_an_empty_registry():
    empty = Registry()
    assert empty.add_tracker(Good) is None
    assert "modality 'camera', which no plugin registered (registered: none)" in empty.problems[0]


def test_a_suite_sequence_of_a_modality_nobody_registered_is_refused_naming_it(registry):
    with pytest.raises(PluginError, match=r"plugin 'acme'.*suite 'scans': sequence 'scans/a' has modality 'lidar'"):
        registry.add_suite("scans", [Empty("scans/b"), Empty("scans/a", modality="lidar")])
    assert "scans" not in registry.suites


# ---------------------------------------------------------------- add_modality
class Columns:
    def __init__(self, *columns):
        self.error_columns = columns


def modality(name="scan", columns=("err_range_m",), readers=(), kinds=None):
    return Modality(name, object, object, object, Columns(*columns), readers=readers, scene_kinds=kinds or {})


def reader(**claims):
    return Reader(lambda path: None, "a scan", **claims)


def test_a_modality_is_registered_with_its_scene_kinds(registry):
    def factory(table, where):
        return Empty(table["name"], "scan")

    added = registry.add_modality(modality(readers=(reader(suffixes=(".scan",)),), kinds={"scan-sim": factory}))
    assert registry.modalities["scan"] is added
    assert list(registry.modalities) == ["camera", "scan"]
    assert registry.scene_kinds == {**CAMERA.scene_kinds, "scan-sim": factory}
    assert registry.add_tracker(make(name="scanner", modality="scan")).modality == "scan"


@pytest.mark.parametrize(
    ("item", "message"),
    [
        ("camera", r"'camera' is not a benchmark.modality.Modality"),
        ({"name": "scan"}, r"is not a benchmark.modality.Modality"),
        (modality(name=""), r"a modality needs a non-empty str name, not ''"),
        (modality(name=None), r"a modality needs a non-empty str name, not None"),
        (modality(name="camera"), r"modality 'camera' is already registered"),
        (modality(columns=("range_m",)), r"modality 'scan': error columns must be named err_<what>_<unit>"),
        (modality(columns=("err_range_m", 3)), r"modality 'scan': error columns must be named err_"),
    ],
)
def test_a_bad_modality_names_the_plugin(registry, item, message):
    with pytest.raises(PluginError, match=message) as info:
        registry.add_modality(item)
    assert str(info.value).startswith("plugin 'acme' (acme-trackers 2.0): ")
    assert list(registry.modalities) == ["camera"]


@pytest.mark.parametrize(
    ("claims", "kinds", "message"),
    [
        ({"suffixes": (".avi",)}, {}, r"files ending \.avi is already read by modality 'camera'"),
        ({"folders": True}, {}, r"folders is already read by modality 'camera'"),
        ({"suffixes": (ANY_FILE,)}, {}, r"any other file is already read by modality 'camera'"),
        ({"suffixes": (".scan",)}, {"camera": None}, r"scene kind 'camera' belongs to modality 'camera'"),
    ],
)
def test_what_another_modality_reads_or_simulates_is_refused_naming_both(registry, claims, kinds, message):
    with pytest.raises(PluginError, match=rf"plugin 'acme' \(acme-trackers 2.0\): modality 'scan': {message}"):
        registry.add_modality(modality(readers=(reader(**claims),), kinds=kinds))
    assert "scan" not in registry.modalities


def test_folders_holding_names_are_a_claim_of_their_own(registry):
    pairs = reader(folders=True, folder_holds=("left", "right"))
    assert pairs.folder_claim == "folders holding left, right" and reader(suffixes=(".scan",)).folder_claim is None
    registry.add_modality(modality(readers=(pairs,)))
    assert registry.modalities["scan"].claims == ("folders holding left, right",)
    message = r"modality 'scan2': folders holding left, right is already read by modality 'scan'"
    with pytest.raises(PluginError, match=message):
        registry.add_modality(modality("scan2", readers=(reader(folders=True, folder_holds=("left", "right")),)))


def test_modalities_that_claim_different_things_live_side_by_side(registry):
    registry.add_modality(SONAR)
    registry.add_modality(modality(readers=(reader(suffixes=(".scan", ".sc2")),), kinds={"scan": None}))
    assert list(registry.modalities) == ["camera", "sonar", "scan"]
    with pytest.raises(PluginError, match=r"modality 'scan2': files ending \.sc2 is already read by modality 'scan'"):
        registry.add_modality(modality("scan2", readers=(reader(suffixes=(".sc3", ".sc2")),)))


# ---------------------------------------------------------------- attribution
def test_additions_are_attributed_to_the_acting_plugin_else_to_the_finder():
    registry = Registry()
    assert registry.origin == Origin() == Origin("<direct>", "-")
    registry.add_modality(CAMERA)
    assert registry.add_tracker(Good).origin == Origin()
    found = Origin("found", "found-dist 1.0")
    registry.attribute_with(lambda: found)
    assert registry.add_tracker(Good, name="good-2").origin == found
    with registry.acting_for(Origin("acting", "acting-dist 2.0")):
        assert registry.add_tracker(Good, name="good-3").origin.plugin == "acting"
        assert registry.add_tracker(Good) is None
    assert registry.add_tracker(Good) is None
    assert re.match(r"^plugin 'acting' \(acting-dist 2.0\): tracker name 'good'", registry.problems[0])
    assert re.match(r"^plugin 'found' \(found-dist 1.0\): .*registered by plugin '<direct>'", registry.problems[1])
    registry.attribute_with(None)
    assert registry.origin == Origin()


def test_an_edit_of_a_tracker_s_code_without_a_version_bump_changes_its_cache_key(registry, tmp_path, monkeypatch):
    source = tmp_path / "edited_tracker.py"
    body = (
        "from benchmark.tracker import Tracker\n"
        "class Edited(Tracker):\n"
        "    name, version, modality = 'edited', '1.0', 'camera'\n"
        "    def reset(self, info, rng, init=None):\n"
        "        pass\n"
        "    def step(self, frame):\n"
        "        return {}\n"
    )
    source.write_text(body)
    monkeypatch.syspath_prepend(str(tmp_path))
    monkeypatch.delitem(sys.modules, "edited_tracker", raising=False)
    module = importlib.import_module("edited_tracker")
    entry = registry.add_tracker(module.Edited)
    before = entry.cache_key
    assert entry.cache_key == before  # the same code gives the same key
    source.write_text(body.replace("return {}", "return None"))
    code_digest.cache_clear()  # a new process reads the files again
    try:
        assert entry.cache_key != before
    finally:
        code_digest.cache_clear()


@pytest.mark.parametrize(
    ("metric", "modality", "message"),
    [
        ("not a metric", None, "'not a metric' is not a benchmark.metrics.Metric"),
        (RATES[0], None, "correct_pct"),
        (FAILURES, "lidar", "metric for unknown modality 'lidar'"),
    ],
)
def test_a_bad_metric_names_the_plugin(registry, metric, modality, message):
    with registry.acting_for(Origin("acme", "acme-metrics")):
        with pytest.raises(PluginError, match=r"plugin 'acme' \(acme-metrics\): .*" + re.escape(message)):
            registry.add_metric(metric, modality)
    assert registry.add_metric(FAILURES, "camera") is FAILURES
    assert [m.name for m in registry.metrics.for_board("camera", ())][-1] == FAILURES.name


def test_a_tracker_that_needs_what_no_sequence_info_holds_is_left_out(fakes) -> None:
    class Needy(fakes.Perfect):
        name = "needy"
        needs = ("calibration", "focal_length")

    registry = fakes.make_registry((fakes.Perfect, Needy))
    assert "needy" not in registry.trackers and "perfect" in registry.trackers
    assert "needy" in registry.problems[-1] and "'focal_length'" in registry.problems[-1]
    assert "calibration, extra, frame_interval_s" in registry.problems[-1]
