"""Timing subjects against their bounds: structure of the rows, ratios that order slow above fast, goals judged."""

from __future__ import annotations

import math

import numpy as np
import pytest

from benchmark.speed.bounds import BoundContext, FpsAtLeast, MsAtMost, RatioAtMost, SpeedBound, TimesFaster
from benchmark.speed.measure import Subject, play, quartiles, read_frames, time_subject
from benchmark.speed.subjects import TrackerWorkload

from ..conftest import FakeSequence, make_registry
from .fakes import DATASET, Bound, Fast, Slow, bounds_of

ROUNDS = 3
FRAMES = 4


def subject_of(name: str, bounds: list[SpeedBound] | None = None) -> Subject:
    registry = make_registry((Fast, Slow))
    declared = bounds if bounds is not None else bounds_of().of(name)
    sequence = FakeSequence(DATASET, FRAMES)
    frames = read_frames(sequence.frames(), FRAMES)
    context = BoundContext(None, sequence.info)
    entry = registry.trackers.get(name)
    ours = declared[0].ours or (lambda context: TrackerWorkload(entry))
    return Subject(name, DATASET, frames, frames[0].truth, context, ours, tuple(declared))


def test_each_bound_is_a_row_with_medians_over_rounds_and_a_ratio_between_its_quartiles() -> None:
    reports: list[tuple[int, int]] = []
    rows = time_subject(subject_of("fast"), ROUNDS, lambda done, total: reports.append((done, total)))
    assert [row.bound for row in rows] == ["the same work", "a peer not installed"]
    timed, missing = rows
    assert (timed.subject, timed.dataset, timed.frames, timed.rounds) == ("fast", DATASET, FRAMES, ROUNDS)
    assert timed.ours_s > 0 and timed.bound_s > 0
    assert timed.ratio_low <= timed.ratio <= timed.ratio_high
    assert timed.goal == "ratio <= 1000x" and timed.met is True
    assert math.isclose(timed.ours_fps, 1 / timed.ours_s)
    # one warm-up and ROUNDS timed passes of ours and of the one bound that could be built
    assert reports[-1] == (2 * (ROUNDS + 1), 2 * (ROUNDS + 1)) and len(reports) == 2 * (ROUNDS + 1)
    assert missing.met is None and "acme-peer is not installed" in missing.note
    assert math.isnan(missing.bound_s) and math.isnan(missing.ratio) and missing.ours_s == timed.ours_s


def test_a_slow_tracker_gets_a_larger_ratio_than_a_fast_one_against_the_same_bound() -> None:
    (fast, _) = time_subject(subject_of("fast"), ROUNDS)
    (slow,) = time_subject(subject_of("slow"), ROUNDS)
    assert slow.ratio > 5 * fast.ratio
    assert slow.met is False  # "ratio <= 1x" for forty times the work


def test_a_component_subject_is_timed_through_its_own_workload() -> None:
    (row,) = time_subject(subject_of("core step"), 1)
    assert row.subject == "core step" and row.goal == ">= 0.001 fps" and row.met is True


def test_every_round_resets_the_workload_with_the_same_generator() -> None:
    seen: list[float] = []

    class Drawing(Bound):
        def reset(self, info, rng, init=None):  # type: ignore[no-untyped-def]
            seen.append(float(rng.random()))

    subject = subject_of("fast", [SpeedBound("fast", "drawing", Drawing, DATASET)])
    time_subject(subject, 2)
    assert len(seen) == 3 and len(set(seen)) == 1


def test_play_times_only_the_steps_and_gives_seconds_a_frame() -> None:
    subject = subject_of("fast")
    workload = Bound(subject.context)
    assert play(workload, subject) > 0
    assert workload.init is subject.init


@pytest.mark.parametrize(
    ("goal", "ratio", "ours_s", "met"),
    [
        (RatioAtMost(1.2), 1.19, 1.0, True),
        (RatioAtMost(1.2), 1.21, 1.0, False),
        (TimesFaster(2), 0.5, 1.0, True),
        (TimesFaster(2), 0.51, 1.0, False),
        (FpsAtLeast(3000), math.nan, 1 / 3001, True),
        (FpsAtLeast(3000), math.nan, 1 / 2999, False),
        (MsAtMost(0.6), math.nan, 0.0006, True),
        (MsAtMost(0.6), math.nan, 0.00061, False),
    ],
)
def test_goals_are_judged_on_the_ratio_or_on_ours_alone(goal: object, ratio: float, ours_s: float, met: bool) -> None:
    assert goal.met(ratio, ours_s) is met  # type: ignore[attr-defined]


@pytest.mark.parametrize("make", [lambda: RatioAtMost(0), lambda: TimesFaster(-1), lambda: FpsAtLeast(math.nan)])
def test_a_goal_must_be_positive(make: object) -> None:
    with pytest.raises(ValueError, match="greater than 0|finite"):
        make()  # type: ignore[operator]


def test_a_goal_on_ours_alone_is_judged_even_when_the_bound_is_unavailable() -> None:
    from .fakes import unavailable

    subject = subject_of("fast", [SpeedBound("fast", "gone", unavailable, DATASET, MsAtMost(1e6))])
    (row,) = time_subject(subject, 1)
    assert row.met is True and "not installed" in row.note


def test_quartiles() -> None:
    assert quartiles([3.0]) == (3.0, 3.0, 3.0)
    low, middle, high = quartiles([1.0, 2.0, 3.0, 4.0, 5.0])
    assert (low, middle, high) == (2.0, 3.0, 4.0)
    assert np.isnan(quartiles([])[1])
