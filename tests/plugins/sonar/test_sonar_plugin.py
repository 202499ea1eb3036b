"""Both sonar trackers are registered through the trackbench entry point and listed with their parameters."""

from __future__ import annotations

import dataclasses

from click.testing import CliRunner
from trackbench_sonar import SonarDetector, SonarParticleFilter
from trackbench_sonar.params import DetectorParams, ParticleFilterParams

import benchmark.plugins
from benchmark.cli import main


def test_both_trackers_are_registered_as_sonar_trackers():
    trackers = benchmark.plugins.load_registry().trackers
    for name, cls in (("sonar_detector", SonarDetector), ("sonar_pf", SonarParticleFilter)):
        entry = trackers[name]
        assert entry.tracker_class is cls
        assert entry.modality == "sonar"
        assert entry.origin.plugin == "sonar"
    assert trackers["sonar_pf"].params == ParticleFilterParams()


def test_disabling_the_plugin_removes_both_trackers():
    trackers = benchmark.plugins.load_registry(disable=["sonar"]).trackers
    assert "sonar_detector" not in trackers and "sonar_pf" not in trackers


def test_trackbench_list_shows_both_with_every_parameter():
    result = CliRunner().invoke(main, ["list"])
    assert result.exit_code == 0, result.output
    lines = result.stdout.splitlines()
    for name, params in (("sonar_detector", DetectorParams), ("sonar_pf", ParticleFilterParams)):
        start = next(i for i, line in enumerate(lines) if line.startswith(f"{name} "))
        assert "modality sonar" in lines[start] and "plugin sonar" in lines[start]
        block = []
        for line in lines[start + 1 :]:
            if not line.startswith("    "):
                break
            block.append(line.strip())
        expected = [f"{field.name} = {getattr(params(), field.name)!r}" for field in dataclasses.fields(params)]
        assert block == expected


def test_parameters_are_documented():
    for params in (DetectorParams, ParticleFilterParams):
        source = __import__("inspect").getsource(params)
        for field in dataclasses.fields(params):
            if field.name in {f.name for f in dataclasses.fields(DetectorParams)} and params is ParticleFilterParams:
                continue
            assert f'    {field.name}:' in source
            after = source.split(f"    {field.name}:", 1)[1].splitlines()[1].strip()
            assert after.startswith('"""'), f"{params.__name__}.{field.name} has no docstring"
