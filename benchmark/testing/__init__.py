"""The conformance kit for tracker authors, in the spirit of scikit-learn's ``check_estimator``.

:func:`check_tracker` runs every check of :mod:`benchmark.testing.checks` on
one tracker, over the first few frames of a registered sequence of its
modality, and returns one :class:`CheckResult` per check; it never raises
for the tracker's faults.  In a tracker's own test suite::

    from benchmark.testing import check_tracker

    def test_conforms():
        failed = [r for r in check_tracker(MyTracker) if not r.ok]
        assert not failed, "\\n".join(r.message for r in failed)

:func:`checks` gives the individual checks, to parametrise a test over them
or to run one alone; :func:`conformance_cases` makes them pytest
parameters, so that each check shows as its own test::

    @pytest.mark.parametrize("case", conformance_cases(MyTracker))
    def test_conforms(case):
        case()

Each check runs under a time limit (:mod:`benchmark.testing.time_limit`),
so a tracker that hangs fails that check and the others still run.

A result has one of five outcomes, as scikit-learn's
``parametrize_with_checks`` reports them: ``passed``; ``failed``;
``skipped``, for a check about a capability the tracker declares it lacks
(``starts_without_truth = False``, no belief exposed); ``xfailed``, for a
check the tracker lists in ``expected_failed_checks`` with its reason, and
which failed; and ``xpassed``, for one so listed that passed, which counts
as a failure so that the list stays true.  A failure that follows from an
earlier one (a tracker that raises fails ``runs`` and most of the rest)
says so and is listed after it (:func:`with_root_causes`); a check that
comes after one that ran out of time is not run, and fails saying so,
since it would wait out the limit again (:func:`run_in_order`).
:mod:`benchmark.testing.strategies` has the modalities' hypothesis
strategies for a tracker's own property-based tests, and
:mod:`benchmark.testing.beliefs` the belief protocols a filter may expose.
``trackbench check NAME...`` runs the kit on installed trackers from the
command line.
"""

from __future__ import annotations

import dataclasses
import time
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass
from typing import Literal

from benchmark.faults import Call
from benchmark.model import Sequence
from benchmark.registry import Registry, TrackerEntry
from benchmark.runner import sigint_is_user_interrupt
from benchmark.testing.checks import (
    CHECKS,
    DEFAULT_FRAMES,
    RANDOM_FRAMES,
    Check,
    NotApplicable,
    Subject,
    global_random_state_kept,
    prepare,
    prerequisites,
)
from benchmark.testing.time_limit import CheckTimeout, time_limit
from benchmark.tracker import Tracker

__all__ = [
    "RANDOM_FRAMES",
    "Check",
    "CheckResult",
    "Subject",
    "assert_conforms",
    "check_tracker",
    "checks",
    "conformance_cases",
    "expected",
    "prepare",
    "run_check",
    "run_in_order",
    "with_root_causes",
]

DEFAULT_TIME_LIMIT_S = 60.0
"""Time one check may take by default, s: a first-party tracker needs well under one."""


Outcome = Literal["passed", "failed", "skipped", "xfailed", "xpassed"]


@dataclass(frozen=True)
class CheckResult:
    """What one check found.

    Attributes
    ----------
    tracker : str
        The tracker's name.
    check : str
        The check's name.
    outcome : {"passed", "failed", "skipped", "xfailed", "xpassed"}
        How it ended (see the module's description).
    message : str
        Why it failed, was skipped or was expected to fail; empty when it passed.
    detail : str
        What it measured or saw (``step_time``: milliseconds per frame).
    elapsed_s : float
        Time the check took, in s.
    follows : str
        The earlier check whose failure this one's follows from; empty for a root cause.
    hung : bool
        Whether it ran out of time (or its worker had to be stopped).
    """

    tracker: str
    check: str
    outcome: Outcome
    message: str = ""
    detail: str = ""
    elapsed_s: float = 0.0
    follows: str = ""
    hung: bool = False

    @property
    def ok(self) -> bool:
        """Whether the tracker is fine on this check: it passed, was skipped, or failed as it declared it would."""
        return self.outcome in ("passed", "skipped", "xfailed")


def checks(entry: TrackerEntry | type[Tracker] | None = None) -> list[Check]:
    """The checks of the kit, in the order they run (a check that does not apply to a tracker skips itself)."""
    return list(CHECKS)


def with_root_causes(results: Iterable[CheckResult]) -> list[CheckResult]:
    """One tracker's results with every failure that follows from an earlier one saying so, root causes first.

    A failed check one of whose prerequisites (:attr:`Check.after`, followed
    back) also failed, or failed as expected, follows from the first of
    them to run, the root cause: its message starts ``follows from 'runs':``.
    The failures that follow from nothing come first, then those that
    follow, then every other result, each group in the order they came.
    """
    results = list(results)
    failed = {result.check for result in results if result.outcome in ("failed", "xfailed")}
    marked = []
    for result in results:
        causes = [name for name in prerequisites(result.check) if name in failed] if result.outcome == "failed" else []
        if causes:
            cause = causes[0]
            result = dataclasses.replace(result, follows=cause, message=f"follows from {cause!r}: {result.message}")
        marked.append(result)
    return sorted(marked, key=lambda r: 0 if not r.ok and not r.follows else 1 if not r.ok else 2)


def entry_of(entry_or_class: TrackerEntry | type[Tracker]) -> TrackerEntry:
    """The entry itself, or a class's entry with its default parameters (None if they cannot be made)."""
    if isinstance(entry_or_class, TrackerEntry):
        return entry_or_class
    made = Call.of(entry_or_class.make_params, "making the default parameters")
    params = made.result  # None when they cannot be made: the metadata check says why
    return TrackerEntry(str(getattr(entry_or_class, "name", entry_or_class.__name__)), entry_or_class, params)


def check_tracker(
    entry_or_class: TrackerEntry | type[Tracker],
    *,
    modality_data: Sequence | None = None,
    registry: Registry | None = None,
    n_frames: int = DEFAULT_FRAMES,
    random_frames: int = RANDOM_FRAMES,
    time_limit_s: float | None = DEFAULT_TIME_LIMIT_S,
) -> list[CheckResult]:
    """Run every check on one tracker.

    Parameters
    ----------
    entry_or_class : TrackerEntry or Tracker subclass
        A registered tracker, or a tracker class (checked with its default parameters).
    modality_data : Sequence, optional
        Where the frames come from (a sequence of the tracker's modality,
        e.g. one of your own opened with :func:`benchmark.io.open_dataset`);
        by default a registered sequence of the modality, simulated where
        there is one.
    registry : Registry, optional
        The modalities and suites; by default every installed plugin's
        (:func:`benchmark.plugins.load_registry`).
    n_frames : int
        Frames read from the sequence (and from the training sequence of a tracker that learns).
    random_frames : int
        Frames of each random sequence the ``random_sequences`` check draws.
    time_limit_s : float or None
        Time each check may take, s; a check still running then fails as a
        hang (:mod:`benchmark.testing.time_limit`: main thread, POSIX only).
        None sets no limit.

    Returns
    -------
    list of CheckResult
        One per check: failures that follow from nothing first, then those
        that follow from them, then the rest, each in the order of
        :func:`checks` (:func:`with_root_causes`).  NumPy's and Python's
        global random state are left as they were, whatever the tracker does.
    """
    if registry is None:
        from benchmark.plugins import load_registry

        registry = load_registry()
    entry = entry_of(entry_or_class)
    subject = prepare_within(entry, registry, modality_data, n_frames, time_limit_s, random_frames)
    return with_root_causes(run_in_order(entry, lambda check: run_check(check, subject, time_limit_s)))


def run_in_order(entry: TrackerEntry, run: Callable[[Check], CheckResult]) -> list[CheckResult]:
    """The results of every check of tracker ``entry`` in order, each from ``run``, but those after a hang.

    A check that comes after one that ran out of time (:attr:`CheckResult.hung`)
    would step the tracker over the same frames and wait out its limit
    again, up to :data:`~benchmark.testing.time_limit.WAIT_FACTOR` times
    the limit each for a tracker that sleeps; it is not run, and fails
    saying so (an expected failure if the tracker lists it).
    """
    results: dict[str, CheckResult] = {}
    expected_failures = getattr(entry.tracker_class, "expected_failed_checks", {})
    for check in checks(entry):
        hung = [name for name in prerequisites(check.name) if name in results and results[name].hung]
        if hung:
            unrun = CheckResult(entry.name, check.name, "failed", f"not run: {hung[0]!r} ran out of time")
            results[check.name] = expected(unrun, expected_failures)
        else:
            results[check.name] = run(check)
    return list(results.values())


def prepare_within(
    entry: TrackerEntry,
    registry: Registry,
    modality_data: Sequence | None = None,
    n_frames: int = DEFAULT_FRAMES,
    time_limit_s: float | None = DEFAULT_TIME_LIMIT_S,
    random_frames: int = RANDOM_FRAMES,
) -> Subject:
    """:func:`~benchmark.testing.checks.prepare` within the time limit: a fit that hangs is the subject's problem."""
    try:
        with sigint_is_user_interrupt(), time_limit(time_limit_s), global_random_state_kept():
            return prepare(entry, registry, modality_data, n_frames, random_frames)
    except CheckTimeout as exc:
        return Subject(
            entry, dict(registry.modalities), problem=f"preparing its frames and model {exc}", random_frames=random_frames
        )


def run_check(check: Check, subject: Subject, time_limit_s: float | None = DEFAULT_TIME_LIMIT_S) -> CheckResult:
    """Run one check on a prepared subject, within the time limit; what it found.

    NumPy's and Python's global random state are left as they were,
    whatever the tracker does; a tracker's fault, ``SystemExit`` and its own
    ``KeyboardInterrupt`` included, is a failed result, never an exception.
    The user's Ctrl-C still stops the check.  A check the tracker lists in
    ``expected_failed_checks`` is ``xfailed`` if it fails and ``xpassed``
    if it passes.
    """
    name = subject.name
    started = time.perf_counter()

    def checked() -> str:
        with sigint_is_user_interrupt(), time_limit(time_limit_s), global_random_state_kept():
            return check(subject)

    ended = Call.of(checked, check.name, timeouts=(CheckTimeout,))
    outcome, message = verdict(ended, name)
    detail = ended.result if ended.ok else ""
    elapsed = time.perf_counter() - started
    result = CheckResult(name, check.name, outcome, message, detail, elapsed, hung=ended.ending == "timeout")
    return expected(result, getattr(subject.entry.tracker_class, "expected_failed_checks", {}))


def verdict(ended: Call[str], name: str) -> tuple[Outcome, str]:
    """The outcome and message of a check of tracker ``name`` that ended so.

    A check passes by returning, skips by raising :class:`NotApplicable`
    and fails by raising :class:`AssertionError`, with their messages;
    running out of time, or raising anything else, fails it too.
    """
    if ended.ok:
        return "passed", ""
    if ended.ending == "timeout" or ended.fault is None:
        return "failed", f"tracker {name!r}: the check {ended.summary}: does it hang?"
    if ended.fault.is_a(NotApplicable):
        return "skipped", ended.fault.message
    if ended.fault.is_a(AssertionError):
        return "failed", ended.fault.message
    return "failed", f"tracker {name!r}: the check raised {ended.summary}"


def expected(result: CheckResult, expected_failures: Mapping[str, str]) -> CheckResult:
    """``result`` as an expected failure (``xfailed``), or an unexpected pass (``xpassed``), where the tracker lists its check."""
    reason = expected_failures.get(result.check) if isinstance(expected_failures, Mapping) else None
    if reason is None or result.outcome not in ("passed", "failed"):
        return result
    if result.outcome == "failed":
        return dataclasses.replace(result, outcome="xfailed", detail=f"expected to fail: {reason}")
    return dataclasses.replace(
        result,
        outcome="xpassed",
        message=f"tracker {result.tracker!r}: listed in expected_failed_checks ({reason}), but it passed: "
        "take it off the list",
    )



from benchmark.testing.pytest_plugin import assert_conforms, conformance_cases  # noqa: E402
