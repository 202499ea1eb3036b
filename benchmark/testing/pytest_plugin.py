"""The pytest side of the conformance kit: a plugin's test in one line.

Installed as the pytest plugin ``trackbench`` (entry-point group ``pytest11``),
so any test suite in an environment with subsea-trackbench can write::

    from benchmark.testing import assert_conforms

    def test_conforms():
        assert_conforms(MyTracker)          # a class, a TrackerEntry or an installed tracker's name

or use the fixture: ``def test_conforms(tracker_check): tracker_check(MyTracker)``.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any

try:
    import pytest
except ImportError:  # benchmark.testing re-exports assert_conforms, and pytest is only a test dependency
    pytest = None

if TYPE_CHECKING:
    from benchmark.registry import TrackerEntry
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
        from benchmark.plugins import load_registry
        from benchmark.selection import select_trackers

        registry = options.setdefault("registry", load_registry())
        (tracker,) = select_trackers(registry, [tracker])
    failed = [result for result in check_tracker(tracker, **options) if not result.ok]
    if failed:
        lines = [f"{result.tracker}: {result.check}: {result.message}" for result in failed]
        raise AssertionError(f"{len(failed)} conformance check(s) failed:\n" + "\n".join(lines))


if pytest is not None:

    @pytest.fixture
    def tracker_check() -> Callable[..., None]:
        """:func:`assert_conforms`, as a fixture."""
        return assert_conforms
