"""Tests of domain restoration (seeds/004, section IV: "filling up of small holes, removal of isolated points")."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from trackbench_foresti.domains import restore_domain, runs


def domain(text: str) -> np.ndarray:
    """``"1101"`` -> ``[True, True, False, True]``."""
    return np.array([c == "1" for c in text], dtype=bool)


def test_runs_lists_starts_and_stops():
    starts, stops = runs(domain("0110011101"))
    assert starts.tolist() == [1, 5, 9] and stops.tolist() == [3, 8, 10]
    assert runs(domain("000"))[0].size == 0


@pytest.mark.parametrize(
    ("before", "max_gap", "min_run", "after"),
    [
        ("1111100111111", 2, 1, "1111111111111"),  # a hole of 2 is filled
        ("1111100011111", 2, 1, "1111100011111"),  # a hole of 3 is not
        ("0011111000", 5, 1, "0011111000"),  # the ends are not holes
        ("1111110001000111111", 2, 4, "1111110000000111111"),  # an isolated point is removed
        ("11111100010100111111", 1, 3, "11111100011100111111"),  # filling can save a dashed segment...
        ("11111100010100111111", 0, 3, "11111100000000111111"),  # ...that removal alone would clear
        ("011000", 0, 3, "000000"),
        ("", 3, 3, ""),
    ],
)
def test_holes_are_filled_then_short_runs_removed(before, max_gap, min_run, after):
    restored = restore_domain(domain(before), max_gap, min_run)
    assert restored.dtype == bool and "".join("1" if b else "0" for b in restored) == after


def test_the_input_is_not_modified():
    original = domain("1101011")
    copy = original.copy()
    restore_domain(original, 1, 3)
    assert np.array_equal(original, copy)


@settings(max_examples=200, deadline=None)
@given(
    bits=st.lists(st.booleans(), min_size=1, max_size=120),
    max_gap=st.integers(0, 12),
    min_run=st.integers(0, 12),
)
def test_restoration_keeps_long_runs_and_leaves_no_short_ones(bits, max_gap, min_run):
    before = np.array(bits, dtype=bool)
    after = restore_domain(before, max_gap, min_run)
    # Every run at least min_run long survives whole.
    for start, stop in zip(*runs(before), strict=True):
        if stop - start >= min_run:
            assert after[start:stop].all()
    # No run shorter than min_run is left, and nothing appears outside the input's extent.
    starts, stops = runs(after)
    assert np.all(stops - starts >= min_run)
    if after.any():
        ones = np.flatnonzero(before)
        assert ones[0] <= np.flatnonzero(after)[0] and np.flatnonzero(after)[-1] <= ones[-1]
    # Restoring twice changes nothing more.
    assert np.array_equal(restore_domain(after, max_gap, min_run), after)


def reference_restore(domain: np.ndarray, max_gap: int, min_run: int) -> np.ndarray:
    """:func:`restore_domain` by arrays of run starts and stops, painted with a cumulative sum."""
    starts, stops = runs(domain)
    if starts.size == 0:
        return domain.copy()
    keep = np.concatenate(([True], starts[1:] - stops[:-1] > max_gap))
    merged_starts = starts[keep]
    merged_stops = np.concatenate((stops[:-1][keep[1:]], stops[-1:]))
    long_enough = merged_stops - merged_starts >= min_run
    marks = np.zeros(domain.size + 1, dtype=np.int64)
    np.add.at(marks, merged_starts[long_enough], 1)
    np.add.at(marks, merged_stops[long_enough], -1)
    return np.cumsum(marks[:-1]) > 0


@settings(max_examples=300, deadline=None)
@given(bits=st.lists(st.booleans(), max_size=120), max_gap=st.integers(0, 12), min_run=st.integers(0, 12))
def test_restoration_equals_the_reference(bits, max_gap, min_run):
    before = np.array(bits, dtype=bool)
    after = restore_domain(before, max_gap, min_run)
    assert after.dtype == bool and np.array_equal(after, reference_restore(before, max_gap, min_run))


def test_bad_domains_and_parameters_are_refused():
    with pytest.raises(ValueError, match="domain"):
        restore_domain(np.array([1, 0, 1]), 1, 1)
    with pytest.raises(ValueError, match="domain"):
        restore_domain(np.zeros((2, 2), bool), 1, 1)
    with pytest.raises(ValueError, match="max_gap"):
        restore_domain(domain("101"), -1, 1)
