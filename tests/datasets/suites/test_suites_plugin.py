"""The trackbench_suites plugin registers the shipped suites through the entry-point group."""

from __future__ import annotations

import pickle
import re

import pluggy
import pytest
import trackbench_suites

from benchmark import hookspecs
from benchmark.modalities.camera import modality as camera_modality
from benchmark.modalities.camera.modality import CAMERA
from benchmark.modalities.camera.scenes.scene import CameraScene
from benchmark.modalities.sonar import modality as sonar_modality
from benchmark.modalities.stereo import modality as stereo_modality
from benchmark.plugins import load_registry
from benchmark.registry import Registry

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
    for name, plugin in [
        ("modality-camera", camera_modality),
        ("modality-sonar", sonar_modality),
        ("modality-stereo", stereo_modality),
        ("suites", trackbench_suites),
    ]:
        manager.register(plugin, name=name)
    manager.check_pending()
    registry = Registry()
    manager.hook.trackbench_register_modalities(registry=registry)
    manager.hook.trackbench_register_datasets(registry=registry)
    assert sum(len(suite.sequences) for suite in registry.suites.values()) >= 7
    assert set(registry.suites) == {
        "camera",
        "camera-clutter",
        "camera-dev",
        "camera-test",
        "camera-train",
        "routes",
        "sonar",
        "sonar-dev",
        "sonar-test",
        "sonar-train",
        "stereo",
        "stereo-images",
    }
    assert [name for name, suite in registry.suites.items() if not suite.scored] == ["camera-train", "routes", "sonar-train"]
    trained = ("camera", "camera-clutter", "camera-dev", "camera-test", "routes")
    assert {registry.suites[name].training for name in trained} == {"camera-train"}
    assert {registry.suites[name].training for name in ("sonar-dev", "sonar-test")} == {"sonar-train"}


def test_the_suites_need_the_scene_kinds_of_registered_modalities() -> None:
    registry = Registry()
    trackbench_suites.trackbench_register_datasets(registry)
    assert not registry.suites
    assert registry.problems and all(
        "suite.kind: must be one of the registered scene kinds [], got" in problem
        for problem in registry.problems
    )
    registry = Registry()
    registry.add_modality(CAMERA)
    trackbench_suites.trackbench_register_datasets(registry)
    assert {"camera", "camera-clutter", "camera-dev", "camera-test", "camera-train", "routes"} == set(registry.suites)
    assert registry.problems and all(
        re.search(
            r"registered scene kinds \['camera', 'camera-route'\], got '(sonar|stereo|stereo-images)' \(suite left out\)$",
            problem,
        )
        for problem in registry.problems
    )


def test_the_registry_s_scene_kinds_are_those_of_the_built_in_modalities(kinds) -> None:
    assert load_registry().scene_kinds == kinds


def test_registered_sequences_pickle_small_and_equal() -> None:
    registry = Registry()
    registry.add_modality(CAMERA)
    registry.add_modality(sonar_modality.SONAR)
    registry.add_modality(stereo_modality.STEREO)
    trackbench_suites.trackbench_register_datasets(registry)
    for seq in registry.suites["camera"].sequences:
        payload = pickle.dumps(seq)
        assert len(payload) < 20_000
        assert pickle.loads(payload).spec == seq.spec
