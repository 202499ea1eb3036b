"""Tests of the lost-cable test."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from trackbench_condensation.lost import LostCable


def decisions(scores, threshold=0.3, decay=0.99):
    test = LostCable(threshold, decay)
    return [test.update(s) for s in scores]


def test_a_steady_cable_is_never_lost():
    assert not any(decisions([1000.0, 900.0, 1100.0, 950.0] * 20))


def test_a_collapse_of_the_evidence_is_reported_until_it_returns():
    scores = [1000.0] * 10 + [100.0] * 20 + [1000.0] * 5
    lost = decisions(scores)
    assert not any(lost[:10]) and all(lost[10:30]) and not any(lost[30:])


def test_a_lasting_change_is_accepted_after_the_reference_decays():
    lost = decisions([1000.0] * 5 + [200.0] * 100, threshold=0.3, decay=0.98)
    # 0.3 * 1000 * 0.98^k < 200 from k = 21 on.
    first_found = 5 + next(k for k, flag in enumerate(lost[5:]) if not flag)
    assert lost[5] and 20 <= first_found - 5 <= 22 and not any(lost[first_found:])


@given(
    st.lists(st.just(0.0) | st.floats(1e-3, 1e4), min_size=1, max_size=40),
    st.integers(-12, 12).map(lambda k: 2.0**k),
)
def test_the_test_is_free_of_the_grey_level_scale(scores, factor):
    # Powers of two scale floating-point numbers exactly.
    assert decisions(scores) == decisions([s * factor for s in scores])


def test_threshold_zero_never_reports_lost():
    assert not any(decisions([1000.0, 0.0, 0.0], threshold=0.0))


@pytest.mark.parametrize("args", [(-0.1, 0.9), (1.5, 0.9), (0.3, 0.0), (0.3, 1.2)])
def test_bad_settings_are_rejected(args):
    with pytest.raises(ValueError):
        LostCable(*args)


def test_bad_scores_are_rejected():
    with pytest.raises(ValueError):
        LostCable(0.3, 0.99).update(float("nan"))
    with pytest.raises(ValueError):
        LostCable(0.3, 0.99).update(-1.0)


def test_reset_forgets_the_reference():
    test = LostCable(0.3, 0.99)
    test.update(1000.0)
    test.reset()
    assert test.reference is None and not test.update(10.0)
    assert np.isclose(test.reference, 10.0)
