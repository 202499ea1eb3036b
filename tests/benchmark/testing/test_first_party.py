"""Every registered first-party tracker passes the conformance kit, on short sequences."""

from __future__ import annotations

import functools

import pytest

from benchmark.plugins import load_registry
from benchmark.registry import Registry
from benchmark.testing import check_tracker, checks, prepare

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


FILTERS = [
    "condensation",
    "condensation-thesis",
    "condensation-fast",
    "condensation-8d",
    "condensation-centre",
    "sonar_pf",
    "stereo_ekf",
    "stereo_ekf-paper",
    "stereo_ekf-eq18",
    "foresti_ekf",
    "segmentation",
]
"""The first-party trackers that filter, and so expose their belief to the kit."""


@pytest.mark.parametrize("name", FILTERS)
def test_first_party_filters_expose_their_belief(name: str) -> None:
    registry = installed()
    subject = prepare(registry.trackers[name], registry, n_frames=FRAMES)
    (belief,) = [check for check in checks() if check.name == "belief_invariants"]
    detail = belief(subject)
    assert detail != "exposes no belief"
    assert " belief held at " in detail and not detail.startswith("no ")
