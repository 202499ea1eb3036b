"""The routes suite: every route is followed to its end by the truth, and lost by a tracker 20 px to one side.

The loop is driven by the cable's true image line computed from the
camera's pose (no rendering), with each route's own vehicle, mount, gains
and frame interval, so the test is about the routes and the controller,
not about any tracker.
"""

from __future__ import annotations

import tomllib

import numpy as np
import pytest
from trackbench_suites.loader import load_suites, suite_files

from benchmark.closedloop.loop import Loop
from benchmark.closedloop.scene import ClosedLoopSpec
from benchmark.modalities.camera.model import CableState
from benchmark.modalities.camera.scenes.silhouette import cable_truth

ROUTES = [
    sequence["name"]
    for item in suite_files()
    if item.name == "routes.toml"
    for sequence in tomllib.loads(item.read_text(encoding="utf-8"))["sequence"]
]

BIAS_PX = 20.0
"""The biased tracker's error along the cable's normal, px of the routes' 320 px wide frames."""


@pytest.fixture(scope="module")
def routes(kinds) -> dict[str, ClosedLoopSpec]:
    suite = next(suite for suite in load_suites(kinds) if suite.name == "routes")
    return {seq.info.name: seq.spec for seq in suite.sequences}


def drive(spec: ClosedLoopSpec, bias_px: float) -> Loop:
    """Steer the route's vehicle with the true cable moved ``bias_px`` along its normal, to the end or the frame limit."""
    loop = spec.loop()
    for _ in range(spec.max_frames):
        if loop.ended:
            break
        truth = cable_truth(loop.pose(), spec.pipe_diameter_m / 2, spec.focal_px, spec.frame_size)
        loop.steer(CableState(truth.d + bias_px, truth.alpha, truth.w, truth.beta))
    return loop


def test_the_suite_has_the_routes_the_issue_names(routes) -> None:
    names = ("straight", "s-bends", "burial-gap", "clutter-field", "low-contrast", "crossing")
    assert list(routes) == [f"routes/{name}" for name in ROUTES] and set(ROUTES) >= set(names)
    assert all(spec.frame_size[0] == 320 for spec in routes.values())


@pytest.mark.parametrize("name", ROUTES)
def test_the_truth_follows_each_route_to_its_end_and_a_20_px_bias_drives_off_it(routes, name) -> None:
    spec = routes[f"routes/{name}"]
    radius = spec.pipe_diameter_m / 2
    followed = drive(spec, 0.0)
    settled = np.array([place.offset_m for place in followed.track.places])[len(followed.track.places) // 3 :]
    assert followed.ended, name
    assert np.abs(settled).max() < radius, name
    for bias in (BIAS_PX, -BIAS_PX):
        biased = drive(spec, bias)
        offsets = np.array([place.offset_m for place in biased.track.places])
        assert np.all(np.abs(offsets[len(offsets) // 2 :]) > radius), (name, bias)
