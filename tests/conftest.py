"""Fixtures of the whole test suite."""

from __future__ import annotations

import os
from collections.abc import Iterator

import pytest
import threadpoolctl
from hypothesis import settings

from benchmark.frame_cache import CACHE_ENV

# Property-based tests draw the same examples on every run, so that a run of the suite (CI's included)
# is reproducible; `pytest --hypothesis-profile explore` draws new ones on every run.  No example has a time
# limit (Hypothesis' default deadline is 200 ms): on a loaded machine a deadline fails tests that are correct.
settings.register_profile("reproducible", derandomize=True, database=None, deadline=None)
settings.register_profile("explore", derandomize=False)
settings.load_profile("reproducible")

THREAD_VARIABLES = ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS")
"""What OpenMP and BLAS runtimes loaded later in a process (and its children) read for their thread count."""


def pytest_configure(config: pytest.Config) -> None:
    """A pytest-xdist worker gives its OpenMP and BLAS pools its share of the cores, as scikit-learn's suite does.

    Each worker otherwise starts a thread per core: on two cores two workers run four, and OpenMP's threads
    spin while they wait for work, so scikit-learn's fits and predictions in the texture tests took seven
    times the CPU time.  Results do not depend on the thread count; `-n 0` keeps the libraries' defaults.
    Libraries already loaded are limited through threadpoolctl, those loaded later (and child processes)
    through the environment, unless it sets a count already.
    """
    workers = getattr(config, "workerinput", {}).get("workercount")
    if not workers:
        return
    threads = max(1, (os.cpu_count() or 1) // workers)
    for name in THREAD_VARIABLES:
        os.environ.setdefault(name, str(threads))
    threadpoolctl.threadpool_limits(threads, user_api=None)


@pytest.fixture(autouse=True, scope="session")
def _frame_cache_of_the_session(tmp_path_factory: pytest.TempPathFactory) -> Iterator[None]:
    """Runs started by the tests render into a frame cache of their own, never the user's."""
    with pytest.MonkeyPatch.context() as patch:
        patch.setenv(CACHE_ENV, str(tmp_path_factory.mktemp("frame-cache")))
        yield
