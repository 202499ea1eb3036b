"""Faults as values: how one unit of work ended, as plain data.

A unit of work (a cell, a phase of a cell such as ``creating the tracker``
or ``frame 12``, a check of the conformance kit, a task handed to a worker
process) ends in one of five ways (:data:`Ending`): ``ok`` with a result,
``error`` with an exception, ``timeout``, ``died`` when the worker process
running it ended (an exit status or a signal), or ``retired`` when the
worker refused it untouched (:data:`benchmark.workers.RETIRED_STATUS`).
:class:`Call` records which, with the phase, the frame when there is one
and the time it took, as pytest's ``CallInfo`` records a test's phase.  An
exception is kept as a :class:`Fault`: its type's name, its message on one
line and its traceback as text, never the live object, so that a call's
value pickles as plain data and compares by value.

:meth:`Call.of` runs a function and catches whatever it raises, of any
class (``SystemExit`` and a tracker's own ``KeyboardInterrupt`` included),
except what it is told to let through: by default the user's Ctrl-C
(:class:`UserInterrupt`).  Phases nest: :meth:`Call.value` hands a failed
call on as :class:`Stopped`, and the enclosing :meth:`Call.of` returns that
inner call as its own, so that the innermost phase names the fault.

The runner, the executors and the conformance kit all phrase a fault from
here: :attr:`Fault.text` (``ExceptionType: message``), :attr:`Call.summary`
and :attr:`Call.message` (the summary and, in parentheses, the phase).
"""

from __future__ import annotations

import signal
import time
import traceback
from collections.abc import Callable
from dataclasses import dataclass
from types import TracebackType
from typing import Any, Generic, Literal, TypeVar

Ending = Literal["ok", "error", "timeout", "died", "retired"]
"""How a unit of work ended."""

T = TypeVar("T")

_STATUS = {"ok": "ok", "timeout": "timeout"}
"""The status of a cell's row for each ending; every other ending is an error."""


class UserInterrupt(KeyboardInterrupt):
    """The user's Ctrl-C or a ``SIGTERM``, as told apart from a ``KeyboardInterrupt`` a tracker raises itself.

    Parameters
    ----------
    signum : int
        The signal that stopped the run.
    """

    def __init__(self, signum: int = signal.SIGINT) -> None:
        super().__init__(signum)
        self.signum = signum


def safe_text(render: Callable[[Any], Any], value: Any) -> str:
    """``render(value)`` as text, or a placeholder when rendering raises (a tracker's broken ``__str__``)."""
    try:
        return str(render(value))
    except Exception:
        return f"<{type(value).__name__} that cannot be shown>"


def death(exit_code: int | None) -> str:
    """How a process ended, from its exit code (negative: the signal that killed it).

    Examples
    --------
    >>> death(-11), death(7)
    ('killed by SIGSEGV', 'exit status 7')
    """
    if exit_code is not None and exit_code < 0:
        try:
            return f"killed by {signal.Signals(-exit_code).name}"
        except ValueError:
            return f"killed by signal {-exit_code}"
    return f"exit status {exit_code}"


def _below_this_frame(exc: BaseException) -> TracebackType | None:
    """``exc``'s traceback without its first frame, :meth:`Call.of`'s own, which says nothing of the fault."""
    return exc.__traceback__.tb_next if exc.__traceback__ is not None else None


def _qualified(kind: type) -> str:
    return f"{kind.__module__}.{kind.__qualname__}"


@dataclass(frozen=True, slots=True)
class Fault:
    """An exception as plain data.

    Attributes
    ----------
    type_name : str
        The exception's class name (``SystemExit``).
    message : str
        Its text, as ``str`` gives it, or a placeholder when its ``__str__`` raises; may be empty.
    traceback : str
        Its formatted traceback, causes included, or a placeholder when formatting raises.
    lineage : tuple of str
        The qualified names of its class and the classes it derives from, so
        that :meth:`is_a` tells its kind without the class.
    """

    type_name: str
    message: str
    traceback: str
    lineage: tuple[str, ...] = ()

    @classmethod
    def of(cls, exc: BaseException, frames: TracebackType | None | Literal["own"] = "own") -> Fault:
        """The fault of a caught exception; its traceback from ``frames`` on (by default its own, whole)."""
        start = exc.__traceback__ if frames == "own" else frames
        return cls(
            type(exc).__name__,
            safe_text(str, exc),
            safe_text(lambda e: "".join(traceback.format_exception(type(e), e, start)), exc),
            tuple(_qualified(kind) for kind in type(exc).__mro__),
        )

    def is_a(self, kind: type[BaseException]) -> bool:
        """Whether the exception was an instance of ``kind``, told by the qualified names of its classes."""
        return _qualified(kind) in self.lineage

    @property
    def text(self) -> str:
        """``ExceptionType: message`` on one line, whitespace runs made one space (no message: the type alone)."""
        line = " ".join(self.message.split())
        return f"{self.type_name}: {line}" if line else self.type_name

    def __str__(self) -> str:
        return self.text


class Stopped(Exception):
    """A call that did not end ok, on its way out to the :meth:`Call.of` around it, which returns it.

    Parameters
    ----------
    call : Call
        The call.
    """

    def __init__(self, call: Call[Any]) -> None:
        super().__init__(call.message)
        self.call = call


@dataclass(frozen=True, slots=True)
class Call(Generic[T]):
    """How one unit of work ended: what ran, at which frame, and its result or its fault.

    Attributes
    ----------
    phase : str
        What ran (``"creating the tracker"``, ``"frame 12"``, ``"worker process"``).
    ending : {"ok", "error", "timeout", "died", "retired"}
        How it ended.
    result : object
        The function's value when it ended ok, else None.
    frame : int or None
        The index of the frame the phase is about, when there is one.
    fault : Fault or None
        The exception that ended it (an error, or the worker's death as the executor saw it).
    exit_code : int or None
        For a worker that died or retired: its exit status, or minus the signal that killed it.
    note : str
        What ended it when no exception says so (a timeout: which limit).
    duration_s : float
        Time the call took, s (``time.perf_counter``); 0 where it ran elsewhere.
    """

    phase: str
    ending: Ending = "ok"
    result: T | None = None
    frame: int | None = None
    fault: Fault | None = None
    exit_code: int | None = None
    note: str = ""
    duration_s: float = 0.0

    @classmethod
    def of(
        cls,
        function: Callable[[], T],
        phase: str,
        frame: int | None = None,
        *,
        reraise: tuple[type[BaseException], ...] = (UserInterrupt,),
        timeouts: tuple[type[BaseException], ...] = (),
    ) -> Call[T]:
        """Call ``function()`` and record how it ended; never raises but what ``reraise`` names.

        Parameters
        ----------
        function : callable
            The work, without arguments.
        phase : str
            What it is, for messages.
        frame : int, optional
            The frame it is about.
        reraise : tuple of exception classes
            What is let through rather than recorded: the user's Ctrl-C by default.
        timeouts : tuple of exception classes
            Exceptions that mean the time ran out: recorded as a ``timeout``
            with the exception's text as :attr:`note`.

        Returns
        -------
        Call
            ``ok`` with the value; ``error`` with the fault of whatever else
            was raised; or, when ``function`` handed on a failed call
            (:meth:`value`), that call itself.
        """
        started = time.perf_counter()
        try:
            result = function()
        except Stopped as stop:
            return stop.call
        except reraise:
            raise
        except timeouts as exc:
            note = safe_text(str, exc)
            return cls(phase, "timeout", frame=frame, note=note, duration_s=time.perf_counter() - started)
        except BaseException as exc:  # whatever the work raises, SystemExit included, is its own ending
            fault = Fault.of(exc, _below_this_frame(exc))
            return cls(phase, "error", frame=frame, fault=fault, duration_s=time.perf_counter() - started)
        return cls(phase, "ok", result=result, frame=frame, duration_s=time.perf_counter() - started)

    @classmethod
    def timed_out(cls, phase: str, note: str, frame: int | None = None) -> Call[Any]:
        """A call stopped at its time limit; ``note`` says which."""
        return cls(phase, "timeout", frame=frame, note=note)

    @property
    def ok(self) -> bool:
        """Whether it ended ok."""
        return self.ending == "ok"

    @property
    def status(self) -> Literal["ok", "error", "timeout"]:
        """The status of a cell that ended so: ``ok``, ``timeout``, or ``error`` for every other ending."""
        return _STATUS.get(self.ending, "error")  # type: ignore[return-value]

    @property
    def summary(self) -> str:
        """What ended it, on one line, without the phase: the fault, the note, or the worker's death."""
        if self.ending in ("died", "retired"):
            return f"the worker process ended ({death(self.exit_code)})"
        if self.fault is not None:
            return self.fault.text
        return self.note

    @property
    def message(self) -> str:
        """``summary (phase)``; empty when it ended ok."""
        if self.ok:
            return ""
        return f"{self.summary} ({self.phase})" if self.phase else self.summary

    @property
    def detail(self) -> str:
        """The fault's traceback, or empty when no exception was seen."""
        return "" if self.fault is None else self.fault.traceback

    def value(self) -> T:
        """The result of a call that ended ok.

        Raises
        ------
        Stopped
            Carrying this call, for the :meth:`of` around the caller.
        """
        if not self.ok:
            raise Stopped(self)
        return self.result  # type: ignore[return-value]
