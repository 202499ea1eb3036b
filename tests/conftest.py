"""Fixtures of the whole test suite."""

from __future__ import annotations

from collections.abc import Iterator

import pytest

from benchmark.frame_cache import CACHE_ENV


@pytest.fixture(autouse=True, scope="session")
def _frame_cache_of_the_session(tmp_path_factory: pytest.TempPathFactory) -> Iterator[None]:
    """Runs started by the tests render into a frame cache of their own, never the user's."""
    with pytest.MonkeyPatch.context() as patch:
        patch.setenv(CACHE_ENV, str(tmp_path_factory.mktemp("frame-cache")))
        yield
