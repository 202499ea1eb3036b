"""The stereo scorer: position, speed and heading errors of the target boat (seeds/002)."""

import math
import sys

import pytest
from hypothesis import given
from hypothesis import strategies as st

from benchmark.modalities.camera.model import CableState
from benchmark.modalities.stereo.modality import STEREO
from benchmark.modalities.stereo.model import StereoTruth, TargetEstimate
from benchmark.modalities.stereo.scoring import StereoScorer
from benchmark.modality import EstimateError
from benchmark.model import Outcome, SequenceInfo
from benchmark.metrics import CORE
from benchmark.results import FrameScore, frame_table, summarise

INFO = SequenceInfo("stereo/case1-slow", "stereo", 1)


def stereo_truth(x=10.0, y=5.0, vx=2.0, vy=0.0):
    return StereoTruth(TargetEstimate((x, y), (vx, vy)), chase_position_m=(0.0, 0.0), chase_heading=0.0)


def test_stereo_scorer_position_speed_and_heading_errors():
    stereo = StereoScorer()
    info = SequenceInfo("stereo/case1-slow", "stereo", 1)
    outcome, errors = stereo.score(TargetEstimate((10.6, 5.8), (0.0, 3.0)), stereo_truth(), info)
    assert outcome is Outcome.CORRECT
    assert errors == pytest.approx((1.0, 1.0, 90.0))
    outcome, errors = stereo.score(TargetEstimate((12.0, 5.0), (-2.0, -1e-9)), stereo_truth(), info)
    assert outcome is Outcome.FALSE and errors[0] == pytest.approx(2.0)
    assert errors[2] == pytest.approx(-180.0, abs=1e-6) or errors[2] == pytest.approx(180.0, abs=1e-6)
    assert stereo.score(None, stereo_truth(), info)[0] is Outcome.MISSED
    with pytest.raises(EstimateError):
        stereo.check(TargetEstimate((math.nan, 0.0), (0.0, 0.0)))
    with pytest.raises(EstimateError):
        STEREO.check_estimate(TargetEstimate((math.nan, 0.0), (0.0, 0.0)))
    with pytest.raises(EstimateError):
        STEREO.check_estimate(CableState(0, 0, 1, 0))


def test_frames_without_truth_are_not_scored():
    info = SequenceInfo("stereo/case1-slow", "stereo", 1)
    outcome, errors = StereoScorer().score(TargetEstimate((10.0, 5.0), (2.0, 0.0)), None, info)
    assert outcome is None and all(math.isnan(e) for e in errors)


def test_the_stereo_modality_scores_with_this_scorer():
    assert isinstance(STEREO.scorer, StereoScorer)
    assert STEREO.error_columns == StereoScorer().error_columns
    assert all(column.startswith("err_") for column in STEREO.error_columns) and len(STEREO.error_columns) == 3


def stereo_summary(scored):
    columns = StereoScorer().error_columns
    frames = [FrameScore(i, outcome, dict(zip(columns, errors)), 0.01) for i, (outcome, errors) in enumerate(scored)]
    return summarise(frame_table(frames), CORE.for_board(None, columns))


def with_component(index, value):
    values = [10.0, 5.0, 2.0, 0.0]  # the components of stereo_truth()
    values[index] = value
    return TargetEstimate(tuple(values[:2]), tuple(values[2:]))


@pytest.mark.parametrize("value", [1e308, 1e200, -1e308])
@pytest.mark.parametrize("component", ["all", "x", "y", "vx", "vy"])
def test_an_absurd_estimate_has_finite_errors_and_rmse_and_is_false_unless_only_its_velocity_is(component, value):
    if component == "all":
        estimate = TargetEstimate((value, value), (value, value))
    else:
        estimate = with_component(["x", "y", "vx", "vy"].index(component), value)
    outcome, errors = StereoScorer().score(estimate, stereo_truth(), INFO)
    assert outcome is (Outcome.CORRECT if component in ("vx", "vy") else Outcome.FALSE)
    assert all(math.isfinite(e) for e in errors)
    summary = stereo_summary([(outcome, errors), (Outcome.CORRECT, (0.5, 0.5, 1.0))])
    assert all(math.isfinite(summary[name]) for name in ("rmse_position_m", "rmse_speed_mps", "rmse_heading_deg"))
    assert summary["rmse_position_m"] == pytest.approx(math.hypot(errors[0], 0.5) / math.sqrt(2.0))


def test_a_speed_or_a_distance_that_overflows_is_false_and_kept_as_the_largest_float():
    largest = sys.float_info.max
    fast = TargetEstimate((10.0, 5.0), (1.7e308, 1.7e308))
    assert StereoScorer().score(fast, stereo_truth(), INFO) == (Outcome.FALSE, (0.0, largest, 45.0))
    far = TargetEstimate((1.7e308, -1.7e308), (2.0, 0.0))
    assert StereoScorer(tolerance_m=math.inf).score(far, stereo_truth(), INFO) == (Outcome.FALSE, (largest, 0.0, 0.0))


@pytest.mark.parametrize("bad", [math.inf, -math.inf, math.nan])
@pytest.mark.parametrize("index", range(4))
def test_non_finite_estimates_are_refused_before_scoring(index, bad):
    with pytest.raises(EstimateError, match="non-finite"):
        STEREO.check_estimate(with_component(index, bad))


finite = st.floats(allow_nan=False, allow_infinity=False)


@given(st.lists(st.tuples(finite, finite, finite, finite), min_size=1, max_size=4))
def test_any_finite_estimate_scores_without_raising_and_summarises_finitely(estimates):
    stereo = StereoScorer()
    scored = []
    for x, y, vx, vy in estimates:
        estimate = TargetEstimate((x, y), (vx, vy))
        STEREO.check_estimate(estimate)
        outcome, errors = stereo.score(estimate, stereo_truth(), INFO)
        assert outcome in (Outcome.CORRECT, Outcome.FALSE)
        assert len(errors) == 3 and all(math.isfinite(e) for e in errors)
        scored.append((outcome, errors))
    assert not any(math.isinf(value) for value in stereo_summary(scored).values())
