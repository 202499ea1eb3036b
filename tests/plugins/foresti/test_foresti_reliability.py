"""Tests of the line reliability parameters, seeds/004 eqs. (5a)-(6d) and Tables I-II."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from trackbench_foresti.reliability import (
    DEFAULT_WEIGHTS,
    extent,
    is_reliable,
    length_and_robustness,
    reliability,
    strength,
)

# (PL, PR, PF, Lambda) of Table I (lines 1-19) and Table II (lines 1-6), Lambda with weights 0.5, 0.35, 0.15.
TABLES = [
    (0.96, 0.70, 0.51, 0.80), (0.49, 1.00, 0.50, 0.67), (0.99, 0.74, 0.93, 0.89), (0.48, 1.00, 0.69, 0.70),
    (0.80, 0.81, 0.56, 0.76), (0.75, 0.87, 0.65, 0.78), (0.55, 0.82, 0.49, 0.64), (0.68, 0.85, 0.61, 0.73),
    (0.78, 0.79, 1.00, 0.82), (0.61, 0.68, 0.91, 0.68), (0.62, 0.72, 0.89, 0.70), (0.62, 0.73, 0.87, 0.70),
    (0.52, 0.77, 0.83, 0.65), (0.66, 0.80, 1.00, 0.76), (0.47, 0.67, 0.73, 0.58), (0.49, 0.69, 0.61, 0.58),
    (0.54, 0.66, 0.58, 0.59), (0.49, 0.76, 0.64, 0.61), (0.51, 0.79, 0.62, 0.62),
    (0.85, 0.87, 0.82, 0.85), (0.60, 0.71, 0.64, 0.65), (0.54, 0.66, 0.61, 0.59), (0.41, 0.69, 0.63, 0.54),
    (0.52, 0.85, 0.75, 0.67), (0.78, 0.78, 1.00, 0.81),
]  # fmt: skip


def test_table_one_first_line():
    assert DEFAULT_WEIGHTS == (0.5, 0.35, 0.15)
    assert round(reliability(0.96, 0.70, 0.51), 2) == 0.80
    assert math.isclose(reliability(0.96, 0.70, 0.51), 0.8015, abs_tol=1e-12)


@pytest.mark.parametrize(("pl", "pr", "pf", "printed"), TABLES)
def test_tables_one_and_two_are_reproduced(pl, pr, pf, printed):
    # Inputs and outputs are printed to two decimals: the sum can be off by one in the last digit.
    assert abs(reliability(pl, pr, pf) - printed) <= 0.0101


def test_extent_length_and_robustness_of_a_hand_made_domain():
    dom = np.zeros(240, bool)
    dom[20:220] = True  # d1 = 20, d2 = 219
    dom[100:150] = False  # n = 150
    assert extent(dom) == (20, 219, 150)
    pl, pr = length_and_robustness(dom)
    assert math.isclose(pl, 199 / 240) and math.isclose(pr, 150 / 199)


def test_robustness_is_clipped_to_one_and_degenerate_domains_score_zero():
    full = np.ones(100, bool)
    assert length_and_robustness(full) == (0.99, 1.0)  # n / (d2 - d1) = 100 / 99
    one = np.zeros(100, bool)
    one[40] = True
    assert length_and_robustness(one) == (0.0, 0.0)  # d2 == d1
    assert length_and_robustness(np.zeros(100, bool)) == (0.0, 0.0)
    assert extent(np.zeros(5, bool)) is None


def test_strength_is_relative_to_the_strongest_line():
    assert np.allclose(strength([2.0, 4.0, 1.0]), [0.5, 1.0, 0.25])
    assert np.array_equal(strength([0.0, 0.0]), [0.0, 0.0])
    assert strength([]).size == 0
    with pytest.raises(ValueError, match="moduli"):
        strength([1.0, math.nan])


def test_filtering_uses_strict_thresholds_of_fig_8():
    assert is_reliable(0.51, 0.66)
    assert not is_reliable(0.5, 0.9) and not is_reliable(0.9, 0.65)
    assert is_reliable(0.3, 0.3, min_pl=0.2, min_pr=0.2)


@settings(max_examples=200, deadline=None)
@given(
    pl=st.floats(0.0, 1.0),
    pr=st.floats(0.0, 1.0),
    pf=st.floats(0.0, 1.0),
    raw=st.tuples(st.floats(0.0, 1.0), st.floats(0.0, 1.0), st.floats(0.01, 1.0)),
)
def test_lambda_lies_in_the_unit_interval_and_between_its_terms(pl, pr, pf, raw):
    total = sum(raw)
    weights = (raw[0] / total, raw[1] / total, 1.0 - raw[0] / total - raw[1] / total)
    assume(weights[2] >= 0.0)
    value = reliability(pl, pr, pf, weights)
    assert 0.0 <= value <= 1.0
    assert min(pl, pr, pf) - 1e-12 <= value <= max(pl, pr, pf) + 1e-12


@settings(max_examples=100, deadline=None)
@given(bits=st.lists(st.booleans(), min_size=1, max_size=300))
def test_length_and_robustness_lie_in_the_unit_interval(bits):
    pl, pr = length_and_robustness(np.array(bits, dtype=bool))
    assert 0.0 <= pl < 1.0 and 0.0 <= pr <= 1.0


def test_bad_inputs_are_refused():
    with pytest.raises(ValueError, match="weights"):
        reliability(0.5, 0.5, 0.5, (0.5, 0.5, 0.5))
    with pytest.raises(ValueError, match="weights"):
        reliability(0.5, 0.5, 0.5, (1.2, -0.2, 0.0))
    with pytest.raises(ValueError, match="pr"):
        reliability(0.5, 1.2, 0.5)
    with pytest.raises(ValueError, match="pl"):
        reliability(math.nan, 0.5, 0.5)
    with pytest.raises(ValueError, match="domain"):
        length_and_robustness(np.array([0, 1, 1]))
