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
:mod:`benchmark.testing.strategies` has the modalities' hypothesis
strategies for a tracker's own property-based tests, and
:mod:`benchmark.testing.beliefs` the belief protocols a filter may expose.
``trackbench check NAME...`` runs the kit on installed trackers from the
command line.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass

from benchmark.model import Sequence
from benchmark.registry import Registry, TrackerEntry
from benchmark.runner import UserInterrupt, describe_exception, sigint_is_user_interrupt
from benchmark.testing.checks import CHECKS, DEFAULT_FRAMES, Subject, global_random_state_kept, prepare
from benchmark.testing.time_limit import CheckTimeout, time_limit
from benchmark.tracker import Tracker

__all__ = [
    "Check",
    "CheckResult",
    "Subject",
    "assert_conforms",
    "check_tracker",
    "checks",
    "conformance_cases",
    "prepare",
    "run_check",
]

DEFAULT_TIME_LIMIT_S = 60.0
"""Time one check may take by default, s: a first-party tracker needs well under one."""


@dataclass(frozen=True)
class Check:
    """One named check.

    Attributes
    ----------
    name : str
        Its name in reports (``"pickles"``).
    function : callable
        ``function(subject) -> str``: a line of detail, or
        :class:`AssertionError` naming the tracker and what broke.
    """

    name: str
    function: Callable[[Subject], str]

    def __call__(self, subject: Subject) -> str:
        return self.function(subject)


@dataclass(frozen=True)
class CheckResult:
    """What one check found.

    Attributes
    ----------
    tracker : str
        The tracker's name.
    check : str
        The check's name.
    ok : bool
        Whether it passed.
    message : str
        Why it failed; empty when it passed.
    detail : str
        What it measured or saw (``step_time``: milliseconds per frame).
    elapsed_s : float
        Time the check took, in s.
    """

    tracker: str
    check: str
    ok: bool
    message: str = ""
    detail: str = ""
    elapsed_s: float = 0.0


def checks(entry: TrackerEntry | type[Tracker] | None = None) -> list[Check]:
    """The checks that apply to ``entry`` (every tracker gets all of them), in the order they run."""
    return [Check(name, function) for name, function in CHECKS]


def entry_of(entry_or_class: TrackerEntry | type[Tracker]) -> TrackerEntry:
    """The entry itself, or a class's entry with its default parameters (None if they cannot be made)."""
    if isinstance(entry_or_class, TrackerEntry):
        return entry_or_class
    try:
        params = entry_or_class.make_params()
    except UserInterrupt:
        raise
    except BaseException:
        params = None  # reported by the metadata check
    return TrackerEntry(str(getattr(entry_or_class, "name", entry_or_class.__name__)), entry_or_class, params)


def check_tracker(
    entry_or_class: TrackerEntry | type[Tracker],
    *,
    modality_data: Sequence | None = None,
    registry: Registry | None = None,
    n_frames: int = DEFAULT_FRAMES,
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
    time_limit_s : float or None
        Time each check may take, s; a check still running then fails as a
        hang (:mod:`benchmark.testing.time_limit`: main thread, POSIX only).
        None sets no limit.

    Returns
    -------
    list of CheckResult
        One per check, in the order of :func:`checks`.  NumPy's and Python's
        global random state are left as they were, whatever the tracker does.
    """
    if registry is None:
        from benchmark.plugins import load_registry

        registry = load_registry()
    entry = entry_of(entry_or_class)
    subject = prepare_within(entry, registry, modality_data, n_frames, time_limit_s)
    return [run_check(check, subject, time_limit_s) for check in checks(entry)]


def prepare_within(
    entry: TrackerEntry,
    registry: Registry,
    modality_data: Sequence | None = None,
    n_frames: int = DEFAULT_FRAMES,
    time_limit_s: float | None = DEFAULT_TIME_LIMIT_S,
) -> Subject:
    """:func:`~benchmark.testing.checks.prepare` within the time limit: a fit that hangs is the subject's problem."""
    try:
        with sigint_is_user_interrupt(), time_limit(time_limit_s), global_random_state_kept():
            return prepare(entry, registry, modality_data, n_frames)
    except CheckTimeout as exc:
        return Subject(entry, dict(registry.modalities), problem=f"preparing its frames and model {exc}")


def run_check(check: Check, subject: Subject, time_limit_s: float | None = DEFAULT_TIME_LIMIT_S) -> CheckResult:
    """Run one check on a prepared subject, within the time limit; what it found.

    NumPy's and Python's global random state are left as they were,
    whatever the tracker does; a tracker's fault, ``SystemExit`` and its own
    ``KeyboardInterrupt`` included, is a failed result, never an exception.
    The user's Ctrl-C still stops the check.
    """
    name = subject.name
    started = time.perf_counter()
    try:
        with sigint_is_user_interrupt(), time_limit(time_limit_s), global_random_state_kept():
            detail, ok, message = check(subject), True, ""
    except CheckTimeout as exc:
        detail, ok, message = "", False, f"tracker {name!r}: the check {exc}: does it hang?"
    except AssertionError as exc:
        detail, ok, message = "", False, str(exc)
    except UserInterrupt:
        raise
    except BaseException as exc:
        detail, ok, message = "", False, f"tracker {name!r}: the check raised {describe_exception(exc)}"
    return CheckResult(name, check.name, ok, message, detail, time.perf_counter() - started)



from benchmark.testing.pytest_plugin import assert_conforms, conformance_cases  # noqa: E402
