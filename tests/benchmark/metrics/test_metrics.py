"""The metrics room: a metric's declaration, the catalogue's board order and its refusals."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd
import pydantic
import pytest
from hypothesis import given
from hypothesis import strategies as st

from benchmark.metrics import (
    CORE,
    KINDS,
    RATES,
    SPEED,
    WALL_SPEED,
    Effect,
    Metric,
    derived_column,
    error_metric,
    percentage,
)
from benchmark.model import Outcome
from benchmark.results import FrameScore, frame_table, summarise


def counted(name: str = "estimated_pct", **changes: object) -> Metric:
    """A plain metric: per cent of scored frames that are correct, under another name."""
    fields = dict(
        name=name, better="higher", kind="detection", columns=("outcome",),
        sums=lambda frames, scale: (float(frames["outcome"].notna().sum()), float((frames["outcome"] == "correct").sum())),
        value=percentage, digits=1, minimum_effect=Effect(2.0),
    )
    return Metric(**{**fields, **changes})


def test_core_board_order_is_by_kind_rates_then_errors_in_scorer_order_then_speed() -> None:
    names = [metric.name for metric in CORE.for_board("camera", ("err_d_px", "err_alpha_deg"))]
    assert names == ["correct_pct", "false_pct", "missed_pct", "rmse_d_px", "rmse_alpha_deg", "cpu_fps", "wall_fps"]
    ranking = [metric.name for metric in CORE.for_board("camera", ("err_d_px", "err_alpha_deg")) if metric.ranks]
    assert ranking == ["correct_pct", "rmse_d_px"]


def test_an_added_metric_joins_its_kind_on_every_board_or_on_its_modality_s_only() -> None:
    everywhere = CORE.adding(counted())
    assert [m.name for m in everywhere.for_board("sonar", ())][:4] == ["correct_pct", "false_pct", "missed_pct", "estimated_pct"]
    camera_only = CORE.adding(counted(kind="robustness"), "camera")
    assert camera_only.for_board("camera", ())[-1].name == "estimated_pct"
    assert "estimated_pct" not in [m.name for m in camera_only.for_board("sonar", ())]
    assert CORE.for_board("camera", ()) == tuple(m for m in CORE.for_board("camera", ()))  # the core is untouched


@pytest.mark.parametrize(
    ("name", "says"),
    [("correct_pct", "correct_pct"), ("correct_lo_pct", "correct_lo_pct"), ("rmse_z_m", "rmse_z_m"),
     ("frames", "frames"), ("status", "status")],
)
def test_a_name_or_derived_column_already_taken_is_refused(name: str, says: str) -> None:
    with pytest.raises(ValueError, match=says):
        CORE.adding(counted(name))
    with pytest.raises(ValueError, match="estimated_pct"):
        CORE.adding(counted()).adding(counted())


@pytest.mark.parametrize(
    "changes",
    [dict(name="Bad Name"), dict(better="up"), dict(kind="beauty"), dict(digits=-1), dict(pool="mean"),
     dict(value="not callable")],
)
def test_a_malformed_declaration_names_the_field(changes: dict[str, object]) -> None:
    with pytest.raises(pydantic.ValidationError, match=next(iter(changes))):
        counted(**changes)


def test_derived_columns_keep_the_unit_last() -> None:
    assert derived_column("correct_pct", "lo") == "correct_lo_pct"
    assert derived_column("fps", "sd") == "fps_sd"
    assert error_metric("err_alpha_deg").interval_columns == ("rmse_alpha_lo_deg", "rmse_alpha_hi_deg")
    assert CORE.of_column("rmse_alpha_hi_deg").name == "rmse_alpha_deg"
    assert CORE.of_column("correct_sd_pct") is RATES[0] and CORE.of_column("tracker") is None


def test_effects_are_absolute_or_a_share_of_the_earlier_value() -> None:
    assert Effect(2.0).of(90.0) == 2.0 and Effect(0.1, relative=True).of(-30.0) == pytest.approx(3.0)
    assert Effect(0.1, relative=True).of(30.0, amount=0.5) == 15.0


outcomes = st.lists(st.sampled_from([*Outcome, None]), max_size=40)


@given(outcomes, outcomes)
def test_a_pooled_value_is_the_value_of_the_pooled_sums(first: list, second: list) -> None:
    tables = [frame_table(FrameScore(i, o, {"err_x_m": float(i)}, 0.001) for i, o in enumerate(seq))
              for seq in (first, second)]
    pooled = pd.concat(tables, ignore_index=True)
    for metric in CORE.for_board(None, ("err_x_m",)):
        scale = metric.scale(tables)
        sums = np.array([metric.sums(table, scale) for table in tables], dtype=float)
        by_sums = float(metric.value(metric.pooled(sums, axis=0), scale))
        assert by_sums == pytest.approx(metric.of(pooled), rel=1e-12, nan_ok=True), metric.name


def test_the_core_summary_of_a_cell_has_rates_errors_and_speed() -> None:
    scores = [FrameScore(0, Outcome.CORRECT, {"err_x_m": 3.0}, 0.5, 1.0), FrameScore(1, Outcome.MISSED, {}, 0.5, 1.0),
              FrameScore(2, None, {}, 0.5, 1.0)]
    summary = summarise(frame_table(scores), CORE.for_board(None, ("err_x_m",)))
    assert summary == {"frames": 2.0, "correct_pct": 50.0, "false_pct": 0.0, "missed_pct": 50.0,
                       "rmse_x_m": 3.0, "cpu_fps": 2.0, "wall_fps": 1.0}
    assert math.isnan(summarise(frame_table([]), (SPEED,))["cpu_fps"])


def test_frames_without_a_cpu_time_count_in_neither_sum_of_the_cpu_speed() -> None:
    frames = pd.DataFrame({"step_ms": [10.0, np.nan, 30.0], "wall_ms": [20.0, 40.0, 60.0]})
    assert SPEED.of(frames) == pytest.approx(2 / 0.04)
    assert WALL_SPEED.of(frames) == pytest.approx(3 / 0.12)
    assert math.isnan(SPEED.of(frames.assign(step_ms=np.nan)))
    assert SPEED.judged and not WALL_SPEED.judged
    assert KINDS.index("detection") < KINDS.index("robustness")
