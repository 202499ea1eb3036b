"""How a check ended becomes its outcome, and where a tracker's fault happened becomes its message."""

from __future__ import annotations

import types
from typing import Any

import pytest

from benchmark.faults import UserInterrupt
from benchmark.model import Frame
from benchmark.testing import Check, NotApplicable, Subject, entry_of, prepare, run_check
from benchmark.testing.checks import DEFAULT_FRAMES
from benchmark.testing.time_limit import CheckTimeout

from .conftest import Steady


def subject_of(tracker: type[Steady], fakes: types.ModuleType) -> Subject:
    registry = fakes.make_registry()
    return prepare(entry_of(tracker), registry, fakes.FakeSequence("fake/S1", 6), DEFAULT_FRAMES)


def ending_with(exc: BaseException) -> Check:
    def check(subject: Subject) -> str:
        raise exc

    return Check("probe", check)


@pytest.mark.parametrize(
    ("check", "outcome", "message"),
    [
        (Check("probe", lambda subject: "3 frames"), "passed", ""),
        (ending_with(NotApplicable("declares no belief")), "skipped", "declares no belief"),
        (ending_with(AssertionError("tracker 'steady': broke\nat frame 2")), "failed", "tracker 'steady': broke\nat frame 2"),
        (ending_with(CheckTimeout("did not finish within 1 s of CPU time")), "failed",
         "tracker 'steady': the check did not finish within 1 s of CPU time: does it hang?"),
        (ending_with(SystemExit(4)), "failed", "tracker 'steady': the check raised SystemExit: 4"),
    ],
    ids=["passed", "skipped", "failed", "timeout", "raised"],
)
def test_how_a_check_ended_is_its_outcome(
    fakes: types.ModuleType, check: Check, outcome: str, message: str
) -> None:
    result = run_check(check, subject_of(Steady, fakes), time_limit_s=None)
    assert (result.outcome, result.message) == (outcome, message)
    assert result.detail == ("3 frames" if outcome == "passed" else "")


def test_the_user_s_ctrl_c_stops_the_check(fakes: types.ModuleType) -> None:
    with pytest.raises(UserInterrupt):
        run_check(ending_with(UserInterrupt()), subject_of(Steady, fakes), time_limit_s=None)


class ExitsAtTwo(Steady):
    name = "exits-at-two"

    def step(self, frame: Frame) -> Any:
        if frame.index == 2:
            raise SystemExit(3)
        return super().step(frame)


class OutOfTimeAtThree(Steady):
    name = "out-of-time"

    def step(self, frame: Frame) -> Any:
        if frame.index == 3:
            raise CheckTimeout("did not finish within 1 s of CPU time")
        return super().step(frame)


class AssertsInReset(Steady):
    name = "asserts-in-reset"

    def reset(self, *args: Any, **kwargs: Any) -> None:
        raise AssertionError("my own assert")


def test_a_run_names_the_phase_and_the_label_of_the_tracker_s_fault(fakes: types.ModuleType) -> None:
    subject = subject_of(ExitsAtTwo, fakes)
    with pytest.raises(AssertionError, match=r"^tracker 'exits-at-two': SystemExit: 3 \(step, frame 2, 'blank' frames\)$"):
        subject.run(subject.create(), label="'blank' frames")


def test_a_run_out_of_time_says_where_and_stays_a_timeout(fakes: types.ModuleType) -> None:
    subject = subject_of(OutOfTimeAtThree, fakes)
    with pytest.raises(CheckTimeout, match=r"^did not finish within 1 s of CPU time \(step, frame 3\)$"):
        subject.run(subject.create())


def test_a_tracker_s_own_assertion_is_its_fault_in_a_phase(fakes: types.ModuleType) -> None:
    subject = subject_of(AssertsInReset, fakes)
    with pytest.raises(AssertionError, match=r"^tracker 'asserts-in-reset': AssertionError: my own assert \(reset\)$"):
        subject.run(subject.create())
