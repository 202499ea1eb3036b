from __future__ import annotations

import math

import pandas as pd
from hypothesis import given, settings
from hypothesis import strategies as st

from benchmark.intervals import seed_intervals
from benchmark.metrics import CORE
from benchmark.results import summarise

ERRORS = ("err_d_px",)
METRICS = CORE.for_board(None, ERRORS)


def table(outcomes: list[str], errors: list[float]) -> pd.DataFrame:
    return pd.DataFrame(
        {"frame": range(len(outcomes)), "outcome": outcomes, "err_d_px": errors, "step_ms": 1.0}
    )


def test_a_single_seed_has_no_interval_and_no_verdict() -> None:
    intervals, deterministic = seed_intervals([table(["correct", "false"], [1.0, 2.0])], METRICS)
    assert deterministic is None
    assert all(math.isnan(low) and math.isnan(high) for low, high in intervals.values())


def test_identical_seeds_are_deterministic_with_a_point_interval() -> None:
    seed = table(["correct", "missed", "false"], [1.0, math.nan, 3.0])
    intervals, deterministic = seed_intervals([seed, seed.copy(), seed.copy()], METRICS)
    summary = summarise(seed, METRICS)
    assert deterministic is True
    for name, (low, high) in intervals.items():
        assert low == high
        assert math.isclose(low, summary[name], rel_tol=1e-12)


def test_seeds_that_differ_give_an_interval_around_the_pooled_value() -> None:
    seeds = [table(["correct"] * k + ["false"] * (10 - k), [float(k)] * 10) for k in (5, 6, 8, 9)]
    intervals, deterministic = seed_intervals(seeds, METRICS)
    pooled = summarise(pd.concat(seeds), METRICS)
    assert deterministic is False
    low, high = intervals["correct_pct"]
    assert 50.0 <= low < pooled["correct_pct"] < high <= 90.0
    low, high = intervals["rmse_d_px"]
    assert 5.0 <= low < pooled["rmse_d_px"] < high <= 9.0
    assert seed_intervals(seeds, METRICS) == (intervals, deterministic)


outcome_lists = st.lists(st.sampled_from(["correct", "false", "missed"]), min_size=4, max_size=4)


@settings(max_examples=30, deadline=None)
@given(st.lists(outcome_lists, min_size=2, max_size=6))
def test_rate_intervals_lie_within_the_seeds_rates(per_seed: list[list[str]]) -> None:
    seeds = [table(outcomes, [1.0] * len(outcomes)) for outcomes in per_seed]
    intervals, deterministic = seed_intervals(seeds, METRICS)
    assert deterministic == all(outcomes == per_seed[0] for outcomes in per_seed)
    for name in ("correct_pct", "false_pct", "missed_pct"):
        rates = [summarise(seed, METRICS)[name] for seed in seeds]
        low, high = intervals[name]
        assert min(rates) - 1e-9 <= low <= high <= max(rates) + 1e-9
