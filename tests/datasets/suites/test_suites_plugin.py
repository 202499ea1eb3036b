"""The trackbench_suites plugin registers the shipped suites through the entry-point group."""

from __future__ import annotations

import pickle

import pluggy

import trackbench_suites
from benchmark import hookspecs
from benchmark.plugins import load_registry
from benchmark.registry import Registry
from benchmark.scenes import CameraScene

CAMERA_FRAMES = {"S1": 248, "S1b": 248, "S1c": 248, "S2": 499, "S3": 409, "S4": 172, "S5": 171, "S6": 129, "S7": 150}


def test_entry_point_registers_the_camera_suite() -> None:
    registry = load_registry()
    suite = registry.suites["camera"]
    assert suite.origin.plugin == "suites"
    names = [seq.info.name for seq in suite.sequences]
    assert names == [f"camera/{short}" for short in CAMERA_FRAMES]
    for seq in suite.sequences:
        info = seq.info
        assert isinstance(seq, CameraScene)
        assert info.n_frames == CAMERA_FRAMES[info.name.split("/")[1]]
        assert (info.modality, info.frame_size) == ("camera", (320, 240))
        assert info.extra["description"]
    assert registry.sequence("camera/S7").info.n_frames == 150


def test_hook_fills_a_fresh_plugin_manager() -> None:
    manager = pluggy.PluginManager(hookspecs.PROJECT_NAME)
    manager.add_hookspecs(hookspecs)
    manager.register(trackbench_suites, name="suites")
    manager.check_pending()
    registry = Registry()
    manager.hook.trackbench_register_datasets(registry=registry)
    assert sum(len(suite.sequences) for suite in registry.suites.values()) >= 7


def test_registered_sequences_pickle_small_and_equal() -> None:
    registry = Registry()
    trackbench_suites.trackbench_register_datasets(registry)
    for seq in registry.suites["camera"].sequences:
        payload = pickle.dumps(seq)
        assert len(payload) < 20_000
        assert pickle.loads(payload).spec == seq.spec
