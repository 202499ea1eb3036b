"""The camera view: borders of truths and estimates, and of a particle belief's particles, on the picture."""

from __future__ import annotations

import numpy as np
import pytest

from benchmark.modalities.camera.geometry import Line
from benchmark.modalities.camera.model import CableState
from benchmark.modalities.camera.scenes.scene import CameraScene
from benchmark.registry import Registry
from benchmark.replay.camera import PARTICLE_LINES, CameraView
from benchmark.replay.page import page_data
from benchmark.replay.record import Belief, record_cell
from benchmark.replay.views import Picture

from ..conftest import make_cell

VIEW = CameraView()


def picture(width: int = 160, height: int = 120, source: tuple[int, int] = (320, 240)) -> Picture:
    return Picture(b"", width, height, source_size=source)


def column_at_middle(segment: tuple[float, ...], picture: Picture) -> float:
    """Where the line through ``(u1, v1, u2, v2)`` crosses the picture's middle row."""
    u1, v1, u2, v2 = segment
    return u1 + (u2 - u1) * (picture.height / 2 - v1) / (v2 - v1)


def crossings(strokes: tuple[float, ...], picture: Picture) -> list[tuple[float, float]]:
    """``(weight, column at the picture's middle row)`` of each stroke."""
    return [(strokes[k], column_at_middle(strokes[k + 1 : k + 5], picture)) for k in range(0, len(strokes), 5)]


def test_a_belief_split_in_two_draws_two_bundles_of_borders_in_proportion() -> None:
    rng = np.random.default_rng(0)
    cable = np.array([0.0, 0.0, 30.0, 0.0])
    beside = np.array([-40.0, 0.0, 30.0, 0.0])
    particles = np.vstack([cable + rng.normal(0, 0.2, (150, 4)) * [1, 0, 1, 0], beside + np.zeros((50, 4))])
    weights = np.full(200, 1 / 200)
    shown = picture()
    (mark,) = VIEW.belief_marks(Belief("particles", particles=particles, weights=weights), shown)
    assert (mark.shape, mark.role) == ("strokes", "particle")
    lines = crossings(mark.points, shown)
    assert len(lines) == 2 * PARTICLE_LINES
    assert all(0.0 < w <= 1.0 for w, _ in lines)
    # Halved: the image's centre column 159.5 + 0.5 is the picture's 80; borders at d -+ w/2, halved again.
    on_cable = [u for _, u in lines if abs(u - 80) < 10]
    beside_it = [u for _, u in lines if abs(u - 60) < 10]
    assert len(on_cable) == pytest.approx(2 * PARTICLE_LINES * 0.75, abs=2)
    assert len(beside_it) == pytest.approx(2 * PARTICLE_LINES * 0.25, abs=2)
    assert len(on_cable) + len(beside_it) == len(lines)


def test_the_overlay_of_a_state_is_drawn_in_the_picture_s_scale() -> None:
    state = CableState(0.0, 0.0, 40.0, 0.0)
    full, half = picture(320, 240), picture(160, 120)
    for shown, expected in ((full, [140.0, 180.0]), (half, [70.0, 90.0])):
        marks = VIEW.overlay(state, None, shown)  # type: ignore[arg-type]  # the camera's overlay reads no frame
        assert sorted(column_at_middle(mark.points, shown) for mark in marks) == pytest.approx(expected)


def test_no_belief_or_not_a_particle_set_draws_nothing() -> None:
    gaussian = Belief("gaussian", mean=np.zeros(4), variance=np.ones(4), covariance=np.eye(4))
    assert VIEW.belief_marks(gaussian, picture()) == []
    nan = Belief("particles", particles=np.full((3, 4), np.nan), weights=np.full(3, 1 / 3))
    assert VIEW.belief_marks(nan, picture()) == []


def test_the_searched_region_is_drawn_as_its_bounding_lines() -> None:
    region = (Line.from_normal(-30.0, 0.0), Line.from_normal(30.0, 0.0))
    shown = picture()
    marks = VIEW.region_marks(region, shown)
    assert [mark.role for mark in marks] == ["window", "window"]
    assert sorted(column_at_middle(mark.points, shown) for mark in marks) == pytest.approx([65.0, 95.0])
    assert VIEW.region_marks(None, shown) == [] and VIEW.region_marks(("not a line",), shown) == []


@pytest.mark.parametrize(("tracker", "lines"), [("hough", 4), ("segmentation", 2)])
def test_a_tracker_that_searches_part_of_the_frame_shows_it(plugin_registry: Registry, tracker: str, lines: int) -> None:
    scene = CameraScene.from_dict({"name": "camera/demo", "n_frames": 3})
    recording = record_cell(make_cell(plugin_registry.trackers[tracker], scene))
    assert recording.ended == ""
    last = recording.frames[-1]
    assert isinstance(last.region, tuple) and len(last.region) == lines
    roles = [role for role, _, _ in page_data(recording)["frames"][-1]["marks"]]
    assert roles.count("window") == lines
