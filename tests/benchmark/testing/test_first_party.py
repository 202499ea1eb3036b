"""Every registered first-party tracker passes the conformance kit, on short sequences."""

from __future__ import annotations

import functools

import pytest

from benchmark.plugins import load_registry
from benchmark.registry import Registry
from benchmark.testing import check_tracker

FRAMES = 12
"""Frames per run: each tracker takes well under a second."""


@functools.cache
def installed() -> Registry:
    """The registry of every installed plugin, loaded once for collection and tests."""
    return load_registry()


def first_party() -> list[str]:
    """The trackers our own distribution registers, by name."""
    entries = installed().trackers.values()
    return [entry.name for entry in entries if entry.origin.distribution.split()[0] == "subsea-trackbench"]


def test_first_party_trackers_are_registered() -> None:
    assert installed().problems == []
    assert len(first_party()) >= 8


@pytest.mark.parametrize("name", first_party())
def test_first_party_tracker_passes_the_kit(name: str) -> None:
    registry = installed()
    results = check_tracker(registry.trackers[name], registry=registry, n_frames=FRAMES)
    failed = [result.message for result in results if not result.ok]
    assert not failed, "\n".join(failed)
    assert {result.check for result in results} >= {"runs", "pickles", "reset_leaves_no_state"}
