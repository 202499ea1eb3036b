"""The pytest side of the conformance kit: a plugin's test in one line.

Installed as the pytest plugin ``trackbench`` (entry-point group ``pytest11``),
so any test suite in an environment with subsea-trackbench can write::

    from benchmark.testing import assert_conforms

    def test_conforms():
        assert_conforms(MyTracker)          # a class, a TrackerEntry or an installed tracker's name

or use the fixture: ``def test_conforms(tracker_check): tracker_check(MyTracker)``.
To see each check as its own test, parametrise over :func:`conformance_cases`::

    @pytest.mark.parametrize("case", conformance_cases(MyTracker))
    def test_conforms(case):
        case()
"""

from __future__ import annotations

import functools
from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

try:
    import pytest
except ImportError:  # benchmark.testing re-exports assert_conforms, and pytest is only a test dependency
    pytest = None

if TYPE_CHECKING:
    from benchmark.registry import TrackerEntry
    from benchmark.testing import Check, CheckResult, Subject
    from benchmark.tracker import Tracker


def assert_conforms(tracker: type[Tracker] | TrackerEntry | str, **options: Any) -> None:
    """Run :func:`benchmark.testing.check_tracker` and raise one AssertionError listing every failed check.

    Parameters
    ----------
    tracker : Tracker subclass, TrackerEntry or str
        What to check; a name is looked up among the installed plugins' trackers.
    **options
        Passed to :func:`~benchmark.testing.check_tracker`: ``modality_data``,
        ``registry``, ``n_frames``, ``time_limit_s``.
    """
    from benchmark.testing import check_tracker

    if isinstance(tracker, str):
        tracker = _installed(tracker, options)
    failed = [result for result in check_tracker(tracker, **options) if not result.ok]
    if failed:
        lines = [f"{result.tracker}: {result.check}: {result.message}" for result in failed]
        raise AssertionError(f"{len(failed)} conformance check(s) failed:\n" + "\n".join(lines))


def _installed(name: str, options: dict[str, Any]) -> TrackerEntry:
    """The installed tracker ``name``, with ``options["registry"]`` set to the registry it was found in."""
    from benchmark.plugins import load_registry
    from benchmark.selection import select_trackers

    registry = options.get("registry") or options.setdefault("registry", load_registry())
    (entry,) = select_trackers(registry, [name])
    return entry


@dataclass(frozen=True)
class ConformanceCase:
    """One check of the conformance kit on one tracker, as a pytest parameter: calling it runs the check.

    Attributes
    ----------
    check : Check
        The check.
    subject : callable
        Returns the prepared subject, the same one for every case of the tracker.
    time_limit_s : float or None
        Time the check may take.
    """

    check: Check
    subject: Callable[[], Subject]
    time_limit_s: float | None
    run: Callable[[Check], CheckResult] | None = None

    def __call__(self) -> None:
        """Run the check: skip, xfail, or raise AssertionError with its message, as its outcome says.

        A failure that follows from an earlier check's says so
        (:func:`benchmark.testing.with_root_causes`), those checks being run
        for it (each once per tracker).
        """
        from benchmark.testing import checks, run_check, with_root_causes
        from benchmark.testing.checks import prerequisites

        run = self.run or (lambda check: run_check(check, self.subject(), self.time_limit_s))
        result = run(self.check)
        if result.outcome == "failed":
            earlier = [run(check) for check in checks() if check.name in prerequisites(self.check.name)]
            (result,) = [r for r in with_root_causes([*earlier, result]) if r.check == self.check.name]
        if result.outcome == "skipped":
            pytest.skip(result.message)
        if result.outcome == "xfailed":
            pytest.xfail(result.detail)
        if not result.ok:
            raise AssertionError(result.message)


def conformance_cases(tracker: type[Tracker] | TrackerEntry | str, **options: Any) -> list[Any]:
    """One pytest parameter per check of the conformance kit, with the check's name as its id.

    The tracker's frames (and model, if it learns) are prepared once, when
    the first case runs, not when tests are collected.

    Parameters
    ----------
    tracker : Tracker subclass, TrackerEntry or str
        What to check, as for :func:`assert_conforms`.
    **options
        As for :func:`~benchmark.testing.check_tracker`: ``modality_data``,
        ``registry``, ``n_frames``, ``time_limit_s``.

    Returns
    -------
    list of pytest.param
        Each holds a :class:`ConformanceCase`; call it in the test.
    """
    from benchmark.testing import DEFAULT_TIME_LIMIT_S, checks, entry_of, prepare_within

    if pytest is None:
        raise RuntimeError("conformance_cases makes pytest parameters, and pytest is not installed")
    time_limit_s = options.get("time_limit_s", DEFAULT_TIME_LIMIT_S)

    @functools.cache
    def subject() -> Subject:
        entry = _installed(tracker, options) if isinstance(tracker, str) else entry_of(tracker)
        registry = options.get("registry")
        if registry is None:
            from benchmark.plugins import load_registry

            registry = options.setdefault("registry", load_registry())
        extra = {key: options[key] for key in ("modality_data", "n_frames", "random_frames") if key in options}
        return prepare_within(entry, registry, time_limit_s=time_limit_s, **extra)

    @functools.cache
    def run(check: Check) -> CheckResult:
        from benchmark.testing import run_check

        return run_check(check, subject(), time_limit_s)

    return [pytest.param(ConformanceCase(check, subject, time_limit_s, run), id=check.name) for check in checks()]



if pytest is not None:

    @pytest.fixture
    def tracker_check() -> Callable[..., None]:
        """:func:`assert_conforms`, as a fixture."""
        return assert_conforms
