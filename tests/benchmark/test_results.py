"""Tests of benchmark.results: frame scores, their table, the summary of a cell, and the cell's result."""

import dataclasses
import math
import pickle
import sys

import numpy as np
import pandas as pd
import pytest
from hypothesis import given
from hypothesis import strategies as st

from benchmark.model import Outcome
from benchmark.metrics import CORE
import pydantic

from benchmark.results import LOOP_PREFIX, CellKey, CellResult, FrameScore, LoopValues, Picture, frame_table, summarise

COLUMNS = ("err_d_px", "err_alpha_deg", "err_w_px", "err_beta_deg")

outcomes = st.lists(st.sampled_from([*Outcome, None]), min_size=1, max_size=60)


@given(outcomes)
def test_rates_sum_to_100_over_scored_frames(sequence):
    scores = [FrameScore(i, o, dict(zip(COLUMNS, (1.0,) * 4)), 0.01, 0.02) for i, o in enumerate(sequence)]
    summary = summarise(frame_table(scores), CORE.for_board(None, COLUMNS))
    scored = sum(o is not None for o in sequence)
    assert summary["frames"] == scored
    if scored:
        total = summary["correct_pct"] + summary["false_pct"] + summary["missed_pct"]
        assert total == pytest.approx(100.0)
        assert summary["missed_pct"] == pytest.approx(100.0 * sequence.count(Outcome.MISSED) / scored)
    assert summary["cpu_fps"] == pytest.approx(100.0)
    assert summary["wall_fps"] == pytest.approx(50.0)


def test_rmse_ignores_frames_without_an_error():
    errors = [(3.0, 1.0, 0.0, 0.0), (4.0, -1.0, 0.0, 0.0), (math.nan,) * 4]
    scores = [FrameScore(i, Outcome.CORRECT, dict(zip(COLUMNS, e)), 0.5) for i, e in enumerate(errors)]
    summary = summarise(frame_table(scores), CORE.for_board(None, COLUMNS))
    assert summary["rmse_d_px"] == pytest.approx(np.sqrt((9 + 16) / 2))
    assert summary["rmse_alpha_deg"] == pytest.approx(1.0)
    assert summary["cpu_fps"] == pytest.approx(2.0)


def test_frame_table_has_frame_outcome_errors_step_ms_and_wall_ms():
    table = frame_table([FrameScore(0, Outcome.FALSE, {"err_x_m": 0.5}, 0.002, 0.003), FrameScore(1, None)])
    assert list(table.columns) == ["frame", "outcome", "err_x_m", "step_ms", "wall_ms"]
    assert table["outcome"][0] == "false" and pd.isna(table["outcome"][1])
    assert table["step_ms"].tolist() == pytest.approx([2.0, 0.0])
    assert table["wall_ms"].tolist() == pytest.approx([3.0, 0.0])
    assert math.isnan(table["err_x_m"][1])


def test_frames_of_a_closed_loop_run_add_their_loop_columns_and_others_have_none():
    loop = LoopValues(offset_m=-0.2, heading_error_deg=3.0, along_m=1.5, time_s=0.08, in_view=False)
    first = dataclasses.replace(loop, in_view=True)
    table = frame_table([FrameScore(0, Outcome.CORRECT, {"err_x_m": 0.5}, loop=first), FrameScore(1, None, loop=loop)])
    assert list(table.columns) == [
        "frame", "outcome", "err_x_m", "loop_offset_m", "loop_heading_error_deg", "loop_along_m", "loop_time_s",
        "loop_in_view", "step_ms", "wall_ms",
    ]
    assert table.iloc[1, 3:8].tolist() == [-0.2, 3.0, 1.5, 0.08, 0.0] and table["loop_in_view"][0] == 1.0
    open_loop = frame_table([FrameScore(0, Outcome.CORRECT, {"err_x_m": 0.5})])
    assert not [column for column in open_loop.columns if column.startswith(LOOP_PREFIX)]


@pytest.mark.parametrize("field", ["offset_m", "heading_error_deg", "along_m", "time_s"])
def test_loop_values_refuse_a_value_that_is_not_finite(field):
    values = {"offset_m": 0.0, "heading_error_deg": 0.0, "along_m": 0.0, "time_s": 0.0, "in_view": True}
    with pytest.raises(pydantic.ValidationError, match=field):
        LoopValues(**{**values, field: math.nan})


def test_summary_of_nothing_is_nan_but_names_every_column():
    summary = summarise(pd.DataFrame(), CORE.for_board(None, ("err_x_m", "err_y_deg")))
    assert summary["frames"] == 0.0
    assert set(summary) == {"frames", "correct_pct", "false_pct", "missed_pct", "rmse_x_m", "rmse_y_deg", "cpu_fps", "wall_fps"}
    assert all(math.isnan(summary[key]) for key in summary if key != "frames")


def result(**changes) -> CellResult:
    base = CellResult(
        tracker="t",
        tracker_version="1.0",
        tracker_key="abc",
        params={},
        dataset="suite/seq",
        dataset_key="d41d8cd98f00b204",
        modality="sonar",
        seed=3,
        init="none",
        status="ok",
        message="",
        scores=(FrameScore(0, Outcome.CORRECT, {"err_across_m": 0.3}, 0.01), FrameScore(1, Outcome.MISSED)),
        elapsed_s=0.1,
        error_columns=("err_across_m",),
    )
    return dataclasses.replace(base, **changes)


def test_a_cell_result_is_keyed_by_tracker_key_dataset_identity_seed_and_init():
    assert result().key == CellKey("abc", "d41d8cd98f00b204", 3, "none")
    assert result(dataset="elsewhere/seq").key == result().key
    assert result(tracker="other", status="error").key == result().key
    assert result(seed=4).key != result().key


def test_a_cell_result_summarises_with_its_modality_s_error_columns():
    summary = result().summary()
    assert summary["rmse_across_m"] == pytest.approx(0.3)
    assert summary["correct_pct"] == summary["missed_pct"] == 50.0
    assert "rmse_d_px" not in summary
    assert result().frames["frame"].tolist() == [0, 1]
    assert not any(key.startswith("rmse_") for key in result(error_columns=()).summary())


def test_a_cell_result_has_no_pictures_unless_given_and_pickles_with_them():
    assert result().pictures == ()
    pictured = result(pictures=(Picture(1, "missed", b"\x89PNG\r\n\x1a\n..."),))
    again = pickle.loads(pickle.dumps(pictured))
    assert again == pictured and again.pictures[0].png == b"\x89PNG\r\n\x1a\n..."
    with pytest.raises(dataclasses.FrozenInstanceError):
        again.pictures[0].frame = 2  # type: ignore[misc]


ordinary = st.one_of(st.just(0.0), st.floats(1e-100, 1e100), st.floats(-1e100, -1e-100))


@given(st.lists(ordinary, min_size=1, max_size=50))
def test_rmse_equals_the_plain_formula_where_that_does_not_overflow(errors):
    scores = [FrameScore(i, Outcome.FALSE, {"err_x_m": e}, 0.01) for i, e in enumerate(errors)]
    plain = np.sqrt(np.mean(np.square(errors)))
    np.testing.assert_allclose(summarise(frame_table(scores), CORE.for_board(None, ("err_x_m",)))["rmse_x_m"], plain, rtol=1e-12)


@pytest.mark.parametrize(
    "errors, expected",
    [
        ((1e308, -1e308, 1e308), 1e308),
        ((sys.float_info.max,) * 3, sys.float_info.max),
        ((1e200, 0.0), 1e200 / math.sqrt(2.0)),
        ((1e308, math.inf, math.nan, -math.inf), 1e308),
        ((0.0, -0.0), 0.0),
    ],
)
def test_rmse_of_huge_errors_is_finite_and_ignores_non_finite_values(errors, expected):
    scores = [FrameScore(i, Outcome.FALSE, {"err_x_m": e}, 0.01) for i, e in enumerate(errors)]
    rmse = summarise(frame_table(scores), CORE.for_board(None, ("err_x_m",)))["rmse_x_m"]
    assert math.isfinite(rmse)
    np.testing.assert_allclose(rmse, expected, rtol=1e-12)


@given(st.lists(st.floats(allow_nan=False, allow_infinity=False), min_size=1, max_size=50))
def test_rmse_of_any_finite_errors_is_finite_and_at_most_the_largest(errors):
    scores = [FrameScore(i, Outcome.FALSE, {"err_x_m": e}, 0.01) for i, e in enumerate(errors)]
    rmse = summarise(frame_table(scores), CORE.for_board(None, ("err_x_m",)))["rmse_x_m"]
    assert 0.0 <= rmse <= max(abs(e) for e in errors)
