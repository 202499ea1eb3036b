"""Faults as values: a call's ending, phase, frame and fault, as plain data that pickles and compares by value."""

from __future__ import annotations

import pickle
import signal

import pytest
from hypothesis import given
from hypothesis import strategies as st

from benchmark.faults import Call, Fault, Stopped, UserInterrupt, death, safe_text


class Unprintable(Exception):
    def __str__(self) -> str:
        raise RuntimeError("no words")


class Custom(ValueError):
    pass


def raising(exc: BaseException):
    def function() -> None:
        raise exc

    return function


@pytest.mark.parametrize(
    ("exc", "text"),
    [
        (SystemExit(3), "SystemExit: 3"),
        (KeyboardInterrupt(), "KeyboardInterrupt"),
        (ValueError("two\n  lines"), "ValueError: two lines"),
        (Unprintable(), "Unprintable: <Unprintable that cannot be shown>"),
    ],
    ids=["exit", "interrupt", "lines", "unprintable"],
)
def test_whatever_a_function_raises_is_an_error_naming_its_phase_and_frame(exc: BaseException, text: str) -> None:
    call = Call.of(raising(exc), "frame 2", 2)
    assert (call.ending, call.status, call.frame, call.result) == ("error", "error", 2, None)
    assert call.summary == text and call.message == f"{text} (frame 2)"
    assert call.detail.startswith("Traceback") and type(exc).__name__ in call.detail
    assert call.detail.count("  File ") == 1 and "in function" in call.detail  # the fault's frame, not the machinery's


def test_a_function_that_returns_is_ok_with_its_value_and_no_message() -> None:
    call = Call.of(lambda: 41 + 1, "reading the sequence's info")
    assert (call.ok, call.status, call.value(), call.message, call.detail) == (True, "ok", 42, "", "")
    assert call.duration_s >= 0.0


def test_the_user_s_interrupt_and_what_the_caller_names_go_through() -> None:
    with pytest.raises(UserInterrupt):
        Call.of(raising(UserInterrupt(signal.SIGTERM)), "frame 0")
    with pytest.raises(Custom):
        Call.of(raising(Custom("kept")), "frame 0", reraise=(ValueError,))


def test_an_exception_named_a_timeout_is_a_timeout_with_its_text_as_the_note() -> None:
    call = Call.of(raising(Custom("did not finish within 1 s")), "step, frame 4", 4, timeouts=(Custom,))
    assert (call.ending, call.status, call.fault) == ("timeout", "timeout", None)
    assert call.message == "did not finish within 1 s (step, frame 4)"


def test_the_innermost_failed_phase_is_the_call_of_the_whole() -> None:
    def cell() -> None:
        Call.of(lambda: "tracker", "creating the tracker").value()
        Call.of(raising(RuntimeError("lost the cable")), "frame 4", 4).value()
        raise AssertionError("not reached")

    call = Call.of(cell, "before frame 0")
    assert (call.phase, call.frame, call.message) == ("frame 4", 4, "RuntimeError: lost the cable (frame 4)")


def test_a_failed_call_s_value_hands_it_on() -> None:
    failed = Call.timed_out("frame 7", "exceeded the 1 s limit after 7 frames", 7)
    with pytest.raises(Stopped) as stop:
        failed.value()
    assert stop.value.call is failed
    assert failed.message == "exceeded the 1 s limit after 7 frames (frame 7)"


@pytest.mark.parametrize(
    ("ending", "code", "text"),
    [("died", -signal.SIGSEGV, "killed by SIGSEGV"), ("died", 7, "exit status 7"), ("retired", 75, "exit status 75")],
)
def test_a_worker_s_death_says_how_it_ended(ending: str, code: int, text: str) -> None:
    call = Call("", ending, exit_code=code)  # type: ignore[arg-type]
    assert call.status == "error"
    assert call.message == f"the worker process ended ({text})"


def test_a_signal_without_a_name_is_given_by_number() -> None:
    assert death(-200) == "killed by signal 200"


def test_a_fault_knows_its_kind_by_name_only() -> None:
    fault = Call.of(raising(Custom("x")), "check").fault
    assert fault is not None
    assert fault.is_a(Custom) and fault.is_a(ValueError) and fault.is_a(BaseException)
    assert not fault.is_a(TypeError) and not fault.is_a(AssertionError)
    assert fault.message == "x" and fault.type_name == "Custom"


def test_safe_text_gives_a_placeholder_for_a_value_that_cannot_be_shown() -> None:
    assert safe_text(str, Unprintable()) == "<Unprintable that cannot be shown>"
    assert safe_text(repr, 3) == "3"


messages = st.text(st.characters(blacklist_categories=("Cs",)), max_size=40)


@given(messages)
def test_a_fault_s_text_is_one_line_starting_with_its_type(message: str) -> None:
    fault = Call.of(raising(ValueError(message)), "frame 0").fault
    assert fault is not None and fault.message == message
    assert fault.text.startswith("ValueError") and "\n" not in fault.text and "\r" not in fault.text
    assert fault.text.split(None, 1)[1:] in ([], [" ".join(message.split())])


calls = st.builds(
    Call,
    phase=messages,
    ending=st.sampled_from(["ok", "error", "timeout", "died", "retired"]),
    result=st.none() | st.integers() | messages,
    frame=st.none() | st.integers(0, 10_000),
    fault=st.none() | st.builds(Fault, messages, messages, messages, st.tuples(messages)),
    exit_code=st.none() | st.integers(-64, 255),
    note=messages,
    duration_s=st.floats(0.0, 1e6),
)


@given(calls)
def test_a_call_pickles_as_plain_data_and_compares_by_value(call: Call) -> None:
    copy = pickle.loads(pickle.dumps(call))
    assert copy == call and copy.message == call.message
    assert call.status == {"ok": "ok", "timeout": "timeout"}.get(call.ending, "error")
    assert (call.message == "") == call.ok
