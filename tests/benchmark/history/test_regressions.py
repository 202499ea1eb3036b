from __future__ import annotations

import itertools

import numpy as np
import pandas as pd
import pytest

from benchmark.history.regressions import Thresholds, find_changes, steps


def cells(run_id: int, correct: list[float], rmse: float = 1.0, fps: float = 100.0, *, machine: str = "m",
          tracker: str = "t", key: str = "k1") -> pd.DataFrame:
    """One run's cells of one tracker on one dataset, a seed per value of ``correct``."""
    return pd.DataFrame(
        {
            "run_id": run_id,
            "tracker": tracker,
            "tracker_version": "1",
            "tracker_key": key,
            "params": [{"a": 1 if key == "k1" else 2}] * len(correct),
            "dataset": "s/1",
            "dataset_key": "d1",
            "seed": range(len(correct)),
            "init": "truth",
            "status": "ok",
            "machine_key": machine,
            "correct_pct": correct,
            "false_pct": [100.0 - c for c in correct],
            "missed_pct": 0.0,
            "rmse_d_px": rmse,
            "cpu_fps": fps,
            "frames": 1000,
        }
    )


def history(*runs: pd.DataFrame) -> pd.DataFrame:
    return pd.concat(runs, ignore_index=True)


def test_a_deterministic_drop_beyond_the_minimum_effect_is_a_regression_naming_its_cause() -> None:
    changes = find_changes(history(cells(1, [90.0]), cells(2, [80.0], key="k2")), 2)
    regression = changes[changes["metric"] == "correct_pct"].iloc[0]
    assert regression["verdict"] == "regression"
    assert (regression["before"], regression["after"], regression["change"]) == (90.0, 80.0, -10.0)
    assert regression["cause"] == "a 1 -> 2"
    false_rate = changes[changes["metric"] == "false_pct"].iloc[0]
    assert false_rate["verdict"] == "regression"


def test_a_change_below_the_minimum_effect_is_none() -> None:
    changes = find_changes(history(cells(1, [90.0]), cells(2, [88.5])), 2)
    assert changes.empty
    lower = Thresholds(overrides={"correct_pct": 1.0})
    assert not find_changes(history(cells(1, [90.0]), cells(2, [88.5])), 2, lower).empty


def test_seed_noise_larger_than_the_change_is_not_significant() -> None:
    before = cells(1, [70.0, 95.0, 80.0, 90.0])
    after = cells(2, [92.0, 68.0, 85.0, 79.0])
    assert "correct_pct" not in set(find_changes(history(before, after), 2)["metric"])


def test_a_clear_shift_over_seeds_is_found_and_an_improvement_is_not_a_regression() -> None:
    changes = find_changes(history(cells(1, [70.0, 71.0, 72.0]), cells(2, [80.0, 81.0, 79.0])), 2)
    row = changes[changes["metric"] == "correct_pct"].iloc[0]
    assert row["verdict"] == "improvement" and row["low"] > 0


def test_rmse_uses_a_relative_minimum_effect_and_lower_is_better() -> None:
    assert find_changes(history(cells(1, [90.0], rmse=1.0), cells(2, [90.0], rmse=1.05)), 2).empty
    row = find_changes(history(cells(1, [90.0], rmse=1.0), cells(2, [90.0], rmse=1.3)), 2).iloc[0]
    assert (row["metric"], row["verdict"]) == ("rmse_d_px", "regression")


def test_speed_is_compared_on_the_same_machine_only_against_the_median_of_the_window() -> None:
    runs = [cells(i, [90.0], fps=fps) for i, fps in enumerate([100.0, 300.0, 100.0, 102.0], start=1)]
    slow = cells(5, [90.0], fps=80.0)
    row = find_changes(history(*runs, slow), 5).iloc[0]
    assert (row["kind"], row["verdict"], row["before"]) == ("speed", "regression", 101.0)
    elsewhere = cells(5, [90.0], fps=80.0, machine="other")
    assert find_changes(history(*runs, elsewhere), 5).empty
    assert find_changes(history(*runs, slow), 5, Thresholds(min_step_s=20.0)).empty


def test_compare_takes_the_runs_it_is_given() -> None:
    table = history(cells(1, [90.0]), cells(2, [50.0]), cells(3, [90.0]))
    assert set(find_changes(table, 3, Thresholds(window=1))["verdict"]) == {"improvement"}
    assert find_changes(table, 3, Thresholds(window=1), against=[1]).empty


def test_a_new_series_has_nothing_to_compare() -> None:
    assert find_changes(history(cells(1, [90.0]), cells(2, [10.0], tracker="new")), 2).empty


def test_steps_finds_a_level_change_and_ignores_single_outliers() -> None:
    levels = pd.Series([90.0, 90.5, 89.5, 90.0, 80.0, 80.5, 79.5, 80.0], index=range(10, 18))
    found = steps(levels, minimum_effect=2.0)
    assert [(s.run_id, s.before, s.after) for s in found] == [(14, 90.0, 80.0)]
    assert steps(pd.Series([90.0, 90.0, 60.0, 90.0, 90.0]), minimum_effect=2.0) == []
    assert steps(pd.Series([90.0, 91.0, 90.0, 91.0]), minimum_effect=2.0) == []


def test_the_latest_run_is_a_step_when_it_leaves_its_level() -> None:
    assert [(s.run_id, s.before, s.after) for s in steps(pd.Series([90.0, 80.0]), minimum_effect=2.0)] == [
        (1, 90.0, 80.0)
    ]
    found = steps(pd.Series([90.0, 90.0, 90.0, 80.0, 80.0, 95.0]), minimum_effect=2.0)
    assert [(s.run_id, s.before, s.after) for s in found] == [(3, 90.0, 80.0), (5, 80.0, 95.0)]


@pytest.mark.parametrize("size", [2, 3, 6])
def test_steps_of_a_noiseless_staircase(size: int) -> None:
    values = list(itertools.chain.from_iterable([[level] * size for level in (10.0, 20.0, 5.0)]))
    found = steps(pd.Series(values), minimum_effect=1.0)
    assert [s.run_id for s in found] == [size, 2 * size]
    assert np.allclose([(s.before, s.after) for s in found], [(10.0, 20.0), (20.0, 5.0)])
