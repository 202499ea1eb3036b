"""Every registered first-party tracker passes the conformance kit, on short sequences."""

from __future__ import annotations

import functools
import re

import pytest

from benchmark.plugins import load_registry
from benchmark.registry import Registry
from benchmark.testing import checks, conformance_cases, prepare
from benchmark.testing.pytest_plugin import ConformanceCase

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


ONCE_PER_CLASS = {"hash_seed"}
"""Checks run on one tracker of each class only: each starts a fresh interpreter (0.4-2 s, mostly imports)."""


def first_party_cases() -> list[object]:
    """Every check on every first-party tracker, one pytest parameter each (``hough:runs``).

    The checks of :data:`ONCE_PER_CLASS` run on the first tracker of each
    class (the variants differ in parameters only), to keep the suite fast.
    """
    seen: set[type] = set()
    cases = []
    for name in first_party():
        tracker_class = installed().trackers[name].tracker_class
        first_of_class = tracker_class not in seen
        seen.add(tracker_class)
        cases += [
            pytest.param(*case.values, id=f"{name}:{case.id}")
            for case in conformance_cases(name, registry=installed(), n_frames=FRAMES)
            if first_of_class or case.id not in ONCE_PER_CLASS
        ]
    return cases


@pytest.mark.parametrize("case", first_party_cases())
def test_first_party_tracker_passes_the_kit(case: ConformanceCase) -> None:
    case()


FILTERS = [
    "condensation",
    "condensation-thesis",
    "condensation-fast",
    "condensation-8d",
    "condensation-centre",
    "sonar_pf",
    "sonar_pf-paper",
    "stereo_ekf",
    "stereo_ekf-paper",
    "stereo_ekf-eq18",
    "foresti_ekf",
    "segmentation",
]
"""The first-party trackers that filter, and so expose their belief to the kit."""


MEASURING = {"foresti_ekf": "camera/S2"}
"""Where the kit's own frames give a filter no measurement to update with, frames that do.

foresti_ekf finds no pair of borders in the first frames of camera/S1 (the clutter of its start): it only predicts.
"""


@pytest.mark.parametrize("name", FILTERS)
def test_first_party_filters_expose_their_belief_and_the_prior_of_their_updates(name: str) -> None:
    registry = installed()
    sequences = {sequence.identity.name: sequence for suite in registry.suites.values() for sequence in suite.sequences}
    subject = prepare(registry.trackers[name], registry, sequences.get(MEASURING.get(name, "")), n_frames=FRAMES)
    (belief,) = [check for check in checks() if check.name == "belief_invariants"]
    detail = belief(subject)
    assert detail != "exposes no belief"
    assert " belief held at " in detail and not detail.startswith("no ")
    compared = re.search(r"prior and posterior compared at (\d+) ", detail)
    assert compared is not None and int(compared.group(1)) > 0, detail
