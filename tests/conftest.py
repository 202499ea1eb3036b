"""Fixtures of the whole test suite."""

from __future__ import annotations

from collections.abc import Iterator

import pytest
from hypothesis import settings

from benchmark.frame_cache import CACHE_ENV

# Property-based tests draw the same examples on every run, so that a run of the suite (CI's included)
# is reproducible; `pytest --hypothesis-profile explore` draws new ones on every run.
settings.register_profile("reproducible", derandomize=True, database=None)
settings.register_profile("explore", derandomize=False)
settings.load_profile("reproducible")


@pytest.fixture(autouse=True, scope="session")
def _frame_cache_of_the_session(tmp_path_factory: pytest.TempPathFactory) -> Iterator[None]:
    """Runs started by the tests render into a frame cache of their own, never the user's."""
    with pytest.MonkeyPatch.context() as patch:
        patch.setenv(CACHE_ENV, str(tmp_path_factory.mktemp("frame-cache")))
        yield
