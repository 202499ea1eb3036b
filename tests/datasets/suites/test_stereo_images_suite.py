"""The stereo-images suite: three rendered sequences based on the stereo suite's medium-speed cases."""

from __future__ import annotations

import pickle

import numpy as np
import pytest
from trackbench_suites.loader import load_suites, parse_suite, shipped_table

from benchmark.errors import DataError
from benchmark.modalities.stereo.scenes.images import StereoImageScene
from benchmark.plugins import load_registry

NAMES = [f"stereo-images/case{case}-medium" for case in (1, 2, 3)]


@pytest.fixture(scope="module")
def suites(kinds) -> dict:
    return {suite.name: {seq.info.name: seq for seq in suite.sequences} for suite in load_suites(kinds)}


def test_plugin_registers_three_rendered_stereo_sequences() -> None:
    registry = load_registry()
    suite = registry.suites["stereo-images"]
    assert suite.origin.plugin == "suites"
    assert [seq.info.name for seq in suite.sequences] == NAMES
    for seq in suite.sequences:
        info = seq.info
        assert isinstance(seq, StereoImageScene)
        assert (info.modality, info.n_frames, info.frame_interval_s) == ("stereo", 600, 0.2)
        assert info.frame_size == (320, 240)
        assert info.extra["speed"] == "medium"
        assert info.extra["case"] == int(info.name[len("stereo-images/case")])
        assert info.extra["description"]
        assert len(pickle.dumps(seq)) < 10_000


def test_each_sequence_is_the_stereo_sequence_of_the_same_name_seen_by_a_camera(suites) -> None:
    for name, images in suites["stereo-images"].items():
        simulated = suites["stereo"][name.replace("stereo-images/", "stereo/")]
        a, b = images.spec, simulated.spec
        assert (a.target, a.chase, a.camera, a.sensors, a.seed, a.case, a.speed) == (
            b.target,
            b.chase,
            b.camera,
            b.sensors,
            b.seed,
            b.case,
            b.speed,
        )
        assert images.info.calibration == simulated.info.calibration
        for index in (0, 311, 599):
            assert images.truth(index) == simulated.truth(index)
            assert images.navigation(index) == simulated.navigation(index)


def test_first_frames_render_with_the_marker_in_view(suites) -> None:
    for seq in suites["stereo-images"].values():
        frame = next(iter(seq.frames()))
        left, right = frame.observation
        assert left.shape == right.shape == (240, 320, 3)
        b, g, r = (left[..., c].astype(int) for c in range(3))
        assert np.count_nonzero((np.minimum(r, g) - b) > 50) > 20


BASED = """
[suite]
name = "demo-images"
kind = "stereo-images"

[defaults]
n_frames = 7
[defaults.render]
noise_grey = 0.5

[[sequence]]
name = "A"
based_on = "stereo/case2-slow"
[sequence.render]
height_px = 100

[[sequence]]
name = "B"
based_on = "stereo/case1-fast"
seed = 5
"""


def test_based_on_takes_the_named_sequence_under_the_files_defaults_and_entry(kinds) -> None:
    base_a, base_b = shipped_table("stereo/case2-slow", "test"), shipped_table("stereo/case1-fast", "test")
    name, (a, b), *_ = parse_suite(BASED, "demo.toml", kinds)
    assert name == "demo-images"
    assert (a.info.name, b.info.name) == ("demo-images/A", "demo-images/B")
    assert a.spec.n_frames == b.spec.n_frames == 7
    assert a.spec.seed == base_a["seed"] and b.spec.seed == 5 != base_b["seed"]
    assert a.spec.render.height_px == 100 and b.spec.render.height_px == 240
    assert a.spec.render.noise_grey == b.spec.render.noise_grey == 0.5
    assert a.spec.target.speed_knots == tuple(tuple(k) for k in base_a["target"]["speed_knots"])
    assert a.spec.target.path.amplitude_m == base_a["target"]["path"]["amplitude_m"] == 4.0


@pytest.mark.parametrize(
    ("old", "new", "message"),
    [
        ('"stereo/case2-slow"', '"stereo/nothing"', r"demo\.toml \[sequence A\]: based_on 'stereo/nothing' names no"),
        ('"stereo/case1-fast"', "3", r"demo\.toml \[sequence B\]: based_on must be a string"),
        ("seed = 5", "seed = 5\nfocal = 1.0", r"demo\.toml \[sequence B\]: unknown key 'focal' \(known: name, "),
    ],
)
def test_bad_based_on_is_named(kinds, old: str, new: str, message: str) -> None:
    with pytest.raises(DataError, match=message):
        parse_suite(BASED.replace(old, new), "demo.toml", kinds)


def test_based_on_references_in_a_circle_are_refused() -> None:
    with pytest.raises(DataError, match="go round in a circle: stereo/case1-slow -> stereo/case1-slow"):
        shipped_table("stereo/case1-slow", "here", ("stereo/case1-slow",))
