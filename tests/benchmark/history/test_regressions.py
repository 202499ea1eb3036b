from __future__ import annotations

import itertools

import numpy as np
import pandas as pd
import pytest

from benchmark.history.regressions import (
    CHANGE_COLUMNS,
    NOISE_RUNS,
    VERDICTS,
    Thresholds,
    confirm_speed,
    find_changes,
    group_changes,
    judged_speed,
    speed_noise,
    steps,
)


def cells(run_id: int, correct: list[float], rmse: float = 1.0, fps: float | list[float] = 100.0, *,
          machine: str = "m", tracker: str = "t", key: str = "k1", wall_fps: float = 100.0) -> pd.DataFrame:
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
            "wall_fps": wall_fps,
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


def speed_history(values: list[float], **columns: object) -> pd.DataFrame:
    """Runs 1, 2, ... of one series on one machine, their CPU speeds ``values`` (the last is tonight's)."""
    runs = [cells(i, [90.0], fps=fps, **columns) for i, fps in enumerate(values, start=1)]  # type: ignore[arg-type]
    return history(*runs)


def test_a_speed_change_must_exceed_the_series_own_noise_as_well_as_the_minimum_effect() -> None:
    noisy = [100.0, 130.0, 80.0, 115.0, 95.0]  # per-run medians 100 +- 15: a MAD of 15
    assert speed_noise(noisy) == pytest.approx(3 * 1.4826 * 15.0)
    assert find_changes(speed_history([*noisy, 80.0]), 6).empty  # 20 % slower, within 3 MADs of this series
    steady = [100.0, 101.0, 99.0, 100.0, 100.5]
    row = find_changes(speed_history([*steady, 80.0]), 6).iloc[0]
    assert (row["metric"], row["verdict"], row["confirmed"]) == ("cpu_fps", "regression", False)
    assert row["noise"] == pytest.approx(10.0)  # 3 MADs (3 x 1.48 x 0.5) are below the minimum effect, the floor
    assert "not yet repeated" in row["note"]
    wider = find_changes(speed_history([*noisy, 30.0]), 6).iloc[0]  # 70 below, beyond 3 MADs (67)
    assert wider["verdict"] == "regression" and wider["noise"] == pytest.approx(speed_noise(noisy))


def test_without_enough_earlier_runs_on_the_machine_speed_has_no_verdict_and_says_why() -> None:
    row = find_changes(speed_history([100.0, 100.0, 50.0]), 3).iloc[0]
    assert row["verdict"] == "unjudged" and not row["confirmed"] and np.isnan(row["noise"])
    assert f"2 earlier runs on this machine, {NOISE_RUNS} needed" in row["note"]
    assert find_changes(speed_history([100.0, 100.0, 100.0, 50.0]), 4).iloc[0]["verdict"] == "regression"
    assert list(find_changes(speed_history([100.0, 100.0, 95.0]), 3).columns) == CHANGE_COLUMNS


def test_the_wall_clock_speed_is_shown_but_never_judged() -> None:
    runs = [cells(i, [90.0], wall_fps=wall) for i, wall in enumerate([100.0, 100.0, 100.0, 100.0, 30.0], start=1)]
    assert find_changes(history(*runs), 5).empty


RECORDED_CPU_FPS = [1188.0, 1103.0, 1590.0, 1369.0, 1392.0]
RECORDED_WALL_FPS = [411.0, 239.0, 636.0, 595.0, 517.0]
"""condensation-fast on camera/S6, one seed, five nightlies with nothing changed on this project's shared 2-core
machine (load average about 15) while another process spun on both cores: its CPU and wall speeds."""


def test_the_old_fixed_ten_per_cent_rule_flags_nights_with_nothing_changed_and_the_noise_rule_does_not() -> None:
    timed = Thresholds(min_step_s=0.0)  # the nightlies ran with --min-step-time 0.1; these are 1000-frame cells
    old_rule = Thresholds(min_step_s=0.0, noise_multiple=0.0, noise_runs=1)  # the minimum effect alone, as before
    nights = range(2, len(RECORDED_WALL_FPS) + 1)
    as_old_fps = [find_changes(speed_history(RECORDED_WALL_FPS[:night]), night, old_rule) for night in nights]
    assert "regression" in set(pd.concat(as_old_fps)["verdict"])  # the old fps was wall-clock time: red on noise
    on_cpu = [find_changes(speed_history(RECORDED_CPU_FPS[:night]), night, old_rule) for night in nights]
    assert "improvement" in set(pd.concat(on_cpu)["verdict"])  # CPU time alone is not enough on a machine this busy
    judged = pd.concat([find_changes(speed_history(RECORDED_CPU_FPS[:night]), night, timed) for night in nights])
    assert set(judged["verdict"]) == {"unjudged"}  # night 3 (+39 %) had two earlier runs, too few to judge it


def test_a_repeat_holds_a_speed_change_beyond_its_noise_in_the_same_direction_or_drops_it() -> None:
    changes = find_changes(speed_history([100.0, 101.0, 99.0, 100.0, 80.0]), 5)
    def repeat(fps: float) -> pd.DataFrame:
        return pd.DataFrame({"tracker": "t", "dataset": "s/1", "seed": [0, 1], "cpu_fps": [fps, fps]})

    held = confirm_speed(changes, repeat(82.0)).iloc[0]
    assert (held["verdict"], held["confirmed"]) == ("regression", True) and "repeat 82" in held["note"]
    for again in (95.0, 130.0, np.nan):  # back within the noise, the other way, or no value at all
        dropped = confirm_speed(changes, repeat(again)).iloc[0]
        assert (dropped["verdict"], dropped["confirmed"]) == ("unconfirmed", False), again
    accuracy = find_changes(history(cells(1, [90.0]), cells(2, [80.0], key="k2")), 2)
    assert confirm_speed(accuracy, repeat(10.0)).equals(accuracy) and accuracy["confirmed"].all()


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


def with_estimates(table: pd.DataFrame, estimated: float) -> pd.DataFrame:
    return table.assign(estimated_frames=estimated)


def test_an_rmse_change_over_fewer_estimated_frames_is_flagged() -> None:
    before = with_estimates(cells(1, [90.0], rmse=2.0), 300)
    fewer = with_estimates(cells(2, [90.0], rmse=1.0), 212)
    row = find_changes(history(before, fewer), 2).set_index("metric").loc["rmse_d_px"]
    assert row["verdict"] == "improvement"
    assert row["note"] == "frames with an estimate 300 -> 212"
    same = with_estimates(cells(2, [90.0], rmse=1.0), 299)
    assert find_changes(history(before, same), 2).set_index("metric").loc["rmse_d_px", "note"] == ""
    unknown = cells(2, [90.0], rmse=1.0)  # a run recorded before the count was kept
    assert find_changes(history(cells(1, [90.0], rmse=2.0), unknown), 2).set_index("metric").loc["rmse_d_px", "note"] == ""


def test_a_rate_change_is_never_flagged_for_its_estimates() -> None:
    changes = find_changes(history(with_estimates(cells(1, [90.0]), 300), with_estimates(cells(2, [70.0]), 100)), 2)
    assert changes.set_index("metric").loc["correct_pct", "note"] == ""


def test_one_cause_on_many_datasets_and_metrics_is_one_group_led_by_its_largest_change() -> None:
    runs = []
    for run, correct, key in ((1, 90.0, "k1"), (2, 80.0, "k2")):
        for dataset, drop in (("s/1", 0.0), ("s/2", 5.0), ("s/3", 1.0)):
            runs.append(cells(run, [correct - drop * (run - 1)], key=key).assign(dataset=dataset, dataset_key=dataset))
    changes = find_changes(history(*runs), 2)
    groups = group_changes(changes)
    regression = groups[groups["verdict"] == "regression"]
    assert len(regression) == 1 and regression["count"].iloc[0] == len(changes[changes["verdict"] == "regression"])
    group = regression.iloc[0]
    assert group["cause"] == "a 1 -> 2" and group["tracker"] == "t"
    assert set(group["datasets"]) == {"s/1", "s/2", "s/3"} and set(group["metrics"]) == {"correct_pct", "false_pct"}
    assert group["headline"].startswith(("correct_pct -15.0 on s/2", "false_pct +15.0 on s/2"))
    assert group["rows"]["effects"].is_monotonic_decreasing and group["largest"] == pytest.approx(15.0 / 2.0)


def test_groups_put_regressions_first_then_accuracy_before_speed_then_the_largest() -> None:
    rows = pd.DataFrame(
        [
            dict(tracker="a", dataset="d", metric="fps", kind="speed", change=-50.0, verdict="regression",
                 cause="", effects=9.0),
            dict(tracker="b", dataset="d", metric="correct_pct", kind="accuracy", change=3.0, verdict="improvement",
                 cause="", effects=1.5),
            dict(tracker="c", dataset="d", metric="correct_pct", kind="accuracy", change=-3.0, verdict="regression",
                 cause="x", effects=1.5),
            dict(tracker="d", dataset="d", metric="correct_pct", kind="accuracy", change=-9.0, verdict="regression",
                 cause="y", effects=4.5),
        ]
    )
    assert group_changes(rows)["tracker"].tolist() == ["d", "c", "a", "b"]


def test_only_a_speed_change_judged_a_regression_or_an_improvement_is_a_judged_speed_change() -> None:
    kinds = ["speed", "accuracy"]
    table = pd.DataFrame(list(itertools.product(kinds, VERDICTS)), columns=["kind", "verdict"])
    judged = table[judged_speed(table)]
    assert sorted(zip(judged["kind"], judged["verdict"])) == [("speed", "improvement"), ("speed", "regression")]
