"""Recording a cell: the runner's estimates bit for bit, the belief subsampled, the frame range kept."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from benchmark.modalities.camera.scenes.scene import CameraScene
from benchmark.registry import Registry
from benchmark.replay.record import (
    MAX_PARTICLES,
    FrameRange,
    FrameRangeError,
    Recording,
    record_cell,
    systematic_subsample,
)
from benchmark.runner import run_cell

from ..conftest import FakeSequence, make_cell
from .conftest import REAL_CELLS, REAL_FRAMES, Particles, real_cell


def same(a: float, b: float) -> bool:
    return (math.isnan(a) and math.isnan(b)) or a == b


@pytest.mark.parametrize("seed", [0, 3])
def test_recording_gives_the_runner_s_estimates_bit_for_bit(registry: Registry, seed: int) -> None:
    cell = make_cell(registry.trackers["fake-particles"], FakeSequence("fake/S1", 8), seed)
    Particles.estimates.clear()
    result = run_cell(cell)
    assert result.status == "ok"
    by_runner = list(Particles.estimates)
    Particles.estimates.clear()
    recording = record_cell(cell)
    assert [frame.estimate_value.as_array().tobytes() for frame in recording.frames] == [
        estimate.as_array().tobytes() for estimate in by_runner
    ]
    assert [frame.outcome for frame in recording.frames] == [str(score.outcome) for score in result.scores]
    for frame, score in zip(recording.frames, result.scores, strict=True):
        assert all(same(frame.errors[name], score.errors[name]) for name in score.errors)
    other = make_cell(registry.trackers["fake-particles"], FakeSequence("fake/S1", 8), seed + 1)
    assert record_cell(other).frames[0].estimate != recording.frames[0].estimate  # the seed matters: the test can fail


def bits(estimate: object) -> bytes | None:
    """An estimate dataclass's numbers as bytes: equal only when every float is equal bit for bit."""
    return None if estimate is None else np.array(dataclasses.astuple(estimate), dtype=float).tobytes()


@pytest.mark.parametrize("name", sorted(REAL_CELLS))
def test_recording_a_first_party_filter_gives_the_runner_s_estimates_bit_for_bit(
    plugin_registry: Registry, real_recordings: dict[str, Recording], name: str
) -> None:
    by_runner: list[object] = []
    def keep(tracker: object, frame: object, estimate: object, score: object) -> None:
        by_runner.append(estimate)

    result = run_cell(real_cell(plugin_registry, name), observer=keep, until=REAL_FRAMES)
    assert result.status == "ok" and len(by_runner) == REAL_FRAMES
    recording = real_recordings[name]
    assert [bits(frame.estimate_value) for frame in recording.frames] == [bits(estimate) for estimate in by_runner]
    assert [frame.outcome for frame in recording.frames] == [str(score.outcome) for score in result.scores]
    assert all(bits(estimate) is not None for estimate in by_runner)


def test_a_frame_range_keeps_its_frames_and_the_estimates_of_the_whole_run(registry: Registry) -> None:
    cell = make_cell(registry.trackers["fake-particles"], FakeSequence("fake/S1", 8), 1)
    whole = record_cell(cell)
    part = record_cell(cell, FrameRange(3, 6))
    assert [frame.index for frame in part.frames] == [3, 4, 5]
    assert [frame.estimate for frame in part.frames] == [frame.estimate for frame in whole.frames[3:6]]


def test_beliefs_are_recorded_as_the_protocols_expose_them(registry: Registry) -> None:
    particles = record_cell(make_cell(registry.trackers["fake-particles"], FakeSequence("fake/S1", 3)))
    belief = particles.frames[0].belief
    assert belief is not None and belief.kind == "particles"
    assert belief.particles.shape[0] <= MAX_PARTICLES and belief.particles.shape[1] == 4
    assert math.isclose(belief.weights.sum(), 1.0, rel_tol=1e-12)
    gaussian = record_cell(make_cell(registry.trackers["fake-gaussian"], FakeSequence("fake/S1", 4)))
    frame = gaussian.frames[2]
    assert frame.estimate is None and frame.estimate_marks == [] and frame.truth_marks
    assert frame.belief is not None and frame.belief.kind == "gaussian"
    assert np.allclose(frame.belief.variance, np.array([4.0, 0.01, 1.0]) * 1.1**3)
    assert np.array_equal(frame.belief.covariance, np.diag(frame.belief.variance))
    assert record_cell(make_cell(registry.trackers["perfect"], FakeSequence("fake/S1", 2))).frames[0].belief is None


def test_a_tracker_that_raises_ends_the_recording_with_the_reason(registry: Registry) -> None:
    recording = record_cell(make_cell(registry.trackers["raising"], FakeSequence("fake/S1", 6)))
    assert [frame.index for frame in recording.frames] == [0, 1, 2]
    assert recording.ended == "RuntimeError: lost the cable (frame 3)"


@pytest.mark.parametrize("text", ["5", "3:3", "4:2", "a:b", "-1:4"])
def test_a_malformed_frame_range_is_refused(text: str) -> None:
    with pytest.raises(FrameRangeError, match="frame range"):
        FrameRange.parse(text)


def test_a_range_past_the_sequence_is_refused(registry: Registry) -> None:
    with pytest.raises(FrameRangeError, match="has 4 frames"):
        record_cell(make_cell(registry.trackers["perfect"], FakeSequence("fake/S1", 4)), FrameRange(4, 9))


weights_of = arrays(np.float64, st.integers(1, 900), elements=st.floats(0.0, 1e6, allow_nan=False))


@given(weights_of, st.integers(1, 300))
def test_the_subsample_is_deterministic_bounded_and_renormalised(weights: np.ndarray, limit: int) -> None:
    particles = np.arange(weights.size * 2, dtype=float).reshape(-1, 2)
    kept, kept_weights = systematic_subsample(particles, weights, limit)
    assert kept.shape[0] == kept_weights.size <= min(limit, weights.size)
    assert math.isclose(kept_weights.sum(), 1.0, rel_tol=1e-9) and np.all(kept_weights >= 0)
    rows = (kept[:, 0] / 2).astype(int)
    assert np.array_equal(kept, particles[rows])  # particles of the set, each once
    assert len(set(rows)) == rows.size
    if weights.size <= limit:
        assert rows.tolist() == list(range(weights.size))  # a small set is kept whole
    elif weights.sum() > 0:
        assert np.all(weights[rows] > 0)
        heavy = np.flatnonzero(weights / weights.sum() >= 1.0 / limit)
        assert set(heavy) <= set(rows)  # a particle heavier than the comb's spacing is always shown
    again = systematic_subsample(particles, weights, limit)
    assert np.array_equal(again[0], kept) and np.array_equal(again[1], kept_weights)


def test_the_subsample_leaves_the_generator_and_the_set_alone() -> None:
    rng = np.random.default_rng(5)
    particles, weights = rng.normal(size=(1000, 3)), rng.random(1000)
    state = rng.bit_generator.state
    copies = particles.copy(), weights.copy()
    kept, _ = systematic_subsample(particles, weights)
    assert kept.shape == (MAX_PARTICLES, 3) or kept.shape[0] < MAX_PARTICLES
    assert rng.bit_generator.state == state
    assert np.array_equal(particles, copies[0]) and np.array_equal(weights, copies[1])


def test_the_further_columns_of_a_belief_are_named_as_its_tracker_names_them(
    plugin_registry: Registry, registry: Registry
) -> None:
    scene = CameraScene.from_dict({"name": "camera/demo", "n_frames": 2, "frame_size": [96, 72], "focal_px": 114.0})
    recording = record_cell(make_cell(plugin_registry.trackers["condensation"], scene))
    assert recording.dimensions == ("d_px", "alpha_rad", "w_px", "beta_rad", "v_d_px", "v_alpha_rad")
    assert all(frame.belief.particles.shape[1] == 6 for frame in recording.frames)
    plain = record_cell(make_cell(registry.trackers["fake-particles"], FakeSequence("fake/S1", 2)))
    assert plain.dimensions == ("d_px", "alpha_rad", "w_px", "beta_rad")


def test_a_closed_loop_cell_replays_as_the_runner_steered_it_with_the_vehicle_s_values() -> None:
    from benchmark.closedloop.scene import ClosedLoopScene
    from benchmark.registry import TrackerEntry
    from benchmark.replay.page import page_data

    from ..closedloop.test_scene import Biased

    route = {"name": "routes/replay", "legs": [{"length_m": 0.6}], "frame_size": [48, 36], "focal_px": 57.0,
             "start_offset_m": 0.1}
    entry = TrackerEntry(Biased.name, Biased, Biased.make_params())
    result = run_cell(make_cell(entry, ClosedLoopScene.from_dict(route)))
    recording = record_cell(make_cell(entry, ClosedLoopScene.from_dict(route)), FrameRange(5, 20))
    assert result.status == "ok" and not recording.ended
    assert [frame.index for frame in recording.frames] == list(range(5, 20))
    steered = [score.loop.columns() for score in result.scores[5:20]]  # type: ignore[union-attr]
    assert [frame.loop for frame in recording.frames] == steered
    assert len({frame.loop["loop_offset_m"] for frame in recording.frames}) > 1  # the vehicle moved
    shown = page_data(recording)["frames"][0]["loop"]
    assert shown["offset_m"] == pytest.approx(steered[0]["loop_offset_m"], rel=1e-3) and shown["route_m"] == 0.6
