import dataclasses

import pytest

from benchmark.errors import PluginError
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
    def __init__(self, name):
        self._info = SequenceInfo(name, "camera", 0)

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
def test_invalid_tracker_classes_name_the_plugin(registry, tracker_class, message):
    with pytest.raises(PluginError, match=message) as info:
        registry.add_tracker(tracker_class)
    assert "'acme' (acme-trackers 2.0)" in str(info.value)


def test_duplicate_tracker_name_names_both_plugins(registry):
    registry.add_tracker(Good)
    with registry.acting_for(Origin("copycat")):
        with pytest.raises(PluginError, match=r"plugin 'copycat'.*'good' is already registered by plugin 'acme'"):
            registry.add_tracker(Good)


def test_unknown_parameter_names_the_plugin(registry):
    with pytest.raises(PluginError, match=r"plugin 'acme'.*no parameter 'sise'"):
        registry.add_tracker(Good, name="typo", params={"sise": 2})


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
