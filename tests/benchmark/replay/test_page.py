"""The replay page: self-contained, its data what the recording holds, within the size budget."""

from __future__ import annotations

import base64
import dataclasses
import json
import math
import re
from pathlib import Path

import numpy as np
import pytest

from benchmark.registry import Registry
from benchmark.replay.page import LEVELS, NOT_FINITE, page_data, replay_html, write_replay
from benchmark.replay.record import Recording, record_cell
from benchmark.replay.stereo import MAP_SIZE
from benchmark.replay.views import Mark

from ..conftest import FakeSequence, make_cell
from .conftest import REAL_CELLS

BUDGET_BYTES_PER_FRAME = 5_000_000 / 300
"""At most 5 MB for 300 camera frames."""


@pytest.fixture
def recording(registry: Registry) -> Recording:
    return record_cell(make_cell(registry.trackers["fake-particles"], FakeSequence("fake/S1", 5)))


def embedded(html: str) -> dict:
    found = re.search(r'<script type="application/json" id="replay-data">(.*?)</script>', html, re.S)
    assert found is not None
    return json.loads(found.group(1))


def test_the_page_is_self_contained(recording: Recording) -> None:
    html = replay_html(recording)
    assert not re.search(r"https?://", html)
    assert not re.search(r"<(script|link|img)[^>]+(src|href)=", html)
    data = embedded(html)
    assert [frame["index"] for frame in data["frames"]] == [0, 1, 2, 3, 4]
    assert all(frame["image"].startswith("data:image/jpeg;base64,/9j/") for frame in data["frames"])


def test_the_data_cannot_close_its_script_element(recording: Recording) -> None:
    recording.ended = "ValueError: </script><script>alert(1)</script> (frame 3)"
    html = replay_html(recording)
    assert html.count("</script>") == 2  # the data's element and the player's
    assert embedded(html)["ended"] == recording.ended


def test_packed_particles_decode_to_the_recorded_ones_within_a_level(recording: Recording) -> None:
    data = page_data(recording)
    frame, kept = data["frames"][2], recording.frames[2].belief
    levels = np.frombuffer(base64.b64decode(frame["belief"]["particles"]), dtype="<u2").reshape(frame["belief"]["count"], 4)
    assert not np.any(levels == NOT_FINITE)
    ranges = np.array(data["ranges"])
    decoded = ranges[:, 0] + levels / LEVELS * (ranges[:, 1] - ranges[:, 0])
    assert np.all(np.abs(decoded - kept.particles) <= (ranges[:, 1] - ranges[:, 0]) / LEVELS)
    weights = np.frombuffer(base64.b64decode(frame["belief"]["weights"]), dtype="<u2")
    assert weights.max() == LEVELS and np.allclose(weights / LEVELS, kept.weights / kept.weights.max(), atol=1 / LEVELS)


NON_IMAGE_BYTES_PER_FRAME = 4_800
"""What a frame may cost beside its JPEG: 200 particles, their weights, the states, overlays, the borders of 24
particles drawn on the picture, and numbers.

With it and the player's 40 KB, 5 MB / 300 frames leaves 11.7 KB of base64 (8.8 KB of JPEG) per frame:
camera/S1's 320 x 240 frames take 8.7 KB on average at quality 70, and its whole page of
``trackbench replay --tracker condensation --dataset camera/S1`` comes to 4.42 MB per 300 frames.
"""


def test_a_frame_costs_little_beside_its_picture(registry: Registry, tmp_path: Path) -> None:
    """The cost of a frame is measured as the difference between pages of 6 and 3 frames, the player's code cancelled."""
    entry = registry.trackers["fake-particles"]
    whole = record_cell(make_cell(entry, FakeSequence("fake/S1", 6)))
    part = Recording(**{**whole.__dict__, "frames": whole.frames[:3]})
    sizes = [write_replay(r, tmp_path / f"{i}.html").stat().st_size for i, r in enumerate((part, whole))]
    assert all(frame.belief.particles.shape[0] == 200 for frame in whole.frames)
    jpeg = sum(4 * -(-len(frame.picture.jpeg) // 3) for frame in whole.frames[3:])
    per_frame = (sizes[1] - sizes[0] - jpeg) / 3
    assert 0 < per_frame < NON_IMAGE_BYTES_PER_FRAME
    assert sizes[0] - 3 * per_frame < 40_000  # the player itself


ROLES = {
    "sonar": {"truth", "estimate", "particle"},
    "stereo": {"truth", "estimate", "measurement", "covariance"},
    "stereo-images": {"truth", "estimate", "covariance"},
}
"""The roles of the marks each first-party filter's page draws."""


@pytest.mark.parametrize("name", sorted(REAL_CELLS))
def test_a_first_party_filter_s_page_holds_finite_marks_of_its_roles(
    real_recordings: dict[str, Recording], name: str
) -> None:
    html = replay_html(real_recordings[name])
    text = re.search(r'id="replay-data">(.*?)</script>', html, re.S).group(1)
    data = json.loads(text, parse_constant=lambda constant: pytest.fail(f"{constant} in the page's data"))
    for frame in data["frames"]:
        assert {role for role, _, _ in frame["marks"]} == ROLES[name]
        assert all(isinstance(p, (int, float)) and math.isfinite(p) for _, _, points in frame["marks"] for p in points)
        plane_top = 0 if name == "sonar" else frame["height"] - MAP_SIZE[1]  # the map is below the image pair
        assert frame["clip"] == [0, plane_top, frame["width"], frame["height"]]
        assert frame["belief"] is not None


def test_marks_with_numbers_that_are_not_finite_are_left_out(real_recordings: dict[str, Recording]) -> None:
    recording = real_recordings["stereo"]
    first = recording.frames[0]
    broken = dataclasses.replace(first, estimate_marks=[Mark.circle(math.nan, 3.0, 5.0), *first.estimate_marks[1:]])
    data = page_data(Recording(**{**recording.__dict__, "frames": [broken]}))
    estimates = [points for role, _, points in data["frames"][0]["marks"] if role == "estimate"]
    assert len(estimates) == len(first.estimate_marks) - 1 and all(None not in points for points in estimates)
