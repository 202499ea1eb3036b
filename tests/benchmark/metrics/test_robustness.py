"""Robustness metrics: failures, frames to re-acquire and the longest failure run, against a plain reading."""

from __future__ import annotations

import importlib.metadata
import math

import numpy as np
import pandas as pd
import pytest
from hypothesis import assume, given
from hypothesis import strategies as st

from benchmark.history.regressions import find_changes
from benchmark.metrics import CORE, robustness
from benchmark.metrics.robustness import FAILURES, LONGEST_FAILURE, METRICS, REACQUISITION, failure_runs
from benchmark.model import Outcome
from benchmark.registry import Registry

CELLS = st.lists(st.lists(st.sampled_from([*Outcome, None]), max_size=30), min_size=1, max_size=4)


def table(cells: list[list[Outcome | None]], *, with_cell_ids: bool = True) -> pd.DataFrame:
    """The frame tables of ``cells`` one after another, as the store pools them."""
    rows = [
        {"cell_id": cell_id, "frame": frame, "outcome": None if outcome is None else str(outcome)}
        for cell_id, outcomes in enumerate(cells)
        for frame, outcome in enumerate(outcomes)
    ]
    frames = pd.DataFrame(rows, columns=["cell_id", "frame", "outcome"])
    return frames if with_cell_ids else frames.drop(columns="cell_id")


def plain_runs(cells: list[list[Outcome | None]]) -> tuple[int, list[int], list[bool]]:
    """The definition read literally, one cell and one frame at a time."""
    scored, lengths, reacquired = 0, [], []
    for outcomes in cells:
        held, current = False, None
        for outcome in (o for o in outcomes if o is not None):
            scored += 1
            if outcome is Outcome.CORRECT:
                if current is not None:
                    lengths.append(current)
                    reacquired.append(True)
                held, current = True, None
            elif current is not None:
                current += 1
            elif held:
                current = 1
        if current is not None:
            lengths.append(current)
            reacquired.append(False)
    return scored, lengths, reacquired


@given(CELLS, st.booleans())
def test_failure_runs_follow_the_definition_and_never_span_two_cells(cells: list, with_cell_ids: bool) -> None:
    found = failure_runs(table(cells, with_cell_ids=with_cell_ids))
    scored, lengths, reacquired = plain_runs(cells)
    assert (found.scored, found.lengths.tolist(), found.reacquired.tolist()) == (scored, lengths, reacquired)


@given(CELLS)
def test_values_are_failures_per_100_frames_the_mean_recovery_and_the_longest_run(cells: list) -> None:
    scored, lengths, reacquired = plain_runs(cells)
    frames = table(cells)
    recovered = [n for n, back in zip(lengths, reacquired) if back]
    expected = {
        FAILURES.name: 100.0 * len(lengths) / scored if scored else math.nan,
        REACQUISITION.name: sum(recovered) / len(recovered) if recovered else math.nan,
        LONGEST_FAILURE.name: max(lengths, default=0) if scored else math.nan,
    }
    for metric in METRICS:
        assert metric.of(frames) == pytest.approx(expected[metric.name], nan_ok=True), metric.name


@given(CELLS)
def test_pooling_per_cell_sums_gives_the_value_of_the_pooled_table(cells: list) -> None:
    pooled = table(cells)
    parts = [group for _, group in pooled.groupby("cell_id")]
    assume(parts)
    for metric in METRICS:
        sums = np.array([metric.sums(part, 1.0) for part in parts], dtype=float)
        assert float(metric.value(metric.pooled(sums, axis=0), 1.0)) == pytest.approx(
            metric.of(pooled), nan_ok=True
        ), metric.name


def test_a_tracker_that_never_held_the_cable_has_no_failure_and_one_that_lost_it_for_good_never_recovered() -> None:
    c, f, m = Outcome.CORRECT, Outcome.FALSE, Outcome.MISSED
    never = table([[m, m, f, m]])
    assert FAILURES.of(never) == 0.0 and math.isnan(REACQUISITION.of(never)) and LONGEST_FAILURE.of(never) == 0
    lost = table([[c, c, f, c, c, m, m, m]])
    assert FAILURES.of(lost) == 25.0 and REACQUISITION.of(lost) == 1.0 and LONGEST_FAILURE.of(lost) == 3


def test_they_are_registered_for_every_modality_through_the_hook() -> None:
    registry = Registry()
    robustness.trackbench_register_metrics(registry)
    assert [m.name for m in registry.metrics.for_board("sonar", ())][-3:] == [m.name for m in METRICS]
    assert registry.metrics is not CORE and CORE.for_board("sonar", ())[-1].name == "wall_fps"


def test_trackbench_installs_them_as_a_plugin_like_any_other() -> None:
    plugins = {entry.value for entry in importlib.metadata.entry_points(group="trackbench")}
    assert "benchmark.metrics.robustness" in plugins


def test_more_failures_than_the_minimum_effect_is_a_regression() -> None:
    def run(run_id: int, failures: float) -> pd.DataFrame:
        return pd.DataFrame({
            "run_id": run_id, "tracker": "t", "tracker_version": "1", "tracker_key": "k", "params": [{}],
            "dataset": "s/1", "dataset_key": "d", "seed": 0, "init": "truth", "status": "ok", "machine_key": "m",
            "frames": 100, "cpu_fps": 100.0, FAILURES.name: failures,
        })

    metrics = CORE.adding(FAILURES)
    changes = find_changes(pd.concat([run(1, 1.0), run(2, 2.0)]), 2, metrics=metrics)
    assert changes[["metric", "verdict"]].values.tolist() == [[FAILURES.name, "regression"]]
    assert find_changes(pd.concat([run(1, 1.0), run(2, 1.4)]), 2, metrics=metrics).empty  # below half a failure
