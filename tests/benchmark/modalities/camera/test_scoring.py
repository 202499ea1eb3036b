"""The camera scorer: Foresti's line-pair rule and the cable-state errors (seeds/004, Table V)."""

import dataclasses
import math
import sys

import pytest
from hypothesis import given
from hypothesis import strategies as st

from benchmark.modalities.camera.geometry import cable_borders, score_line_pair
from benchmark.modalities.camera.modality import CAMERA
from benchmark.modalities.camera.model import UNKNOWN_CABLE, CableState, CameraPose, CameraTruth, PosedCableState
from benchmark.modalities.camera.scoring import CameraScorer
from benchmark.modality import EstimateError
from benchmark.model import Outcome, SequenceInfo
from benchmark.metrics import CORE
from benchmark.results import FrameScore, frame_table, summarise

INFO = SequenceInfo("test/seq", "camera", 3, frame_size=(320, 240))
TRUTH = CameraTruth(CableState(5.0, 0.1, 30.0, 0.02))
scorer = CameraScorer()


def test_camera_scorer_outcomes_and_errors():
    outcome, errors = scorer.score(CableState(7.0, 0.1, 33.0, 0.02), TRUTH, INFO)
    assert outcome is Outcome.CORRECT
    assert errors[:4] == pytest.approx((2.0, 0.0, 3.0, 0.0)) and all(math.isnan(e) for e in errors[4:])
    outcome, errors = scorer.score(CableState(5.0, 0.2, 30.0, 0.02), TRUTH, INFO)
    assert outcome is Outcome.FALSE and errors[1] == pytest.approx(math.degrees(0.1))
    outcome, errors = scorer.score(None, TRUTH, INFO)
    assert outcome is Outcome.MISSED and all(math.isnan(e) for e in errors)


def test_a_reported_pose_is_scored_against_the_true_pose():
    truth_pose = CameraPose(0.1, 1.5, 4.0, math.radians(2.0), math.radians(50.0), 0.0)
    truth = CameraTruth(TRUTH.cable, pose=truth_pose)
    pose = CameraPose(0.3, 1.4, 0.0, math.radians(1.0), math.radians(53.0), 0.0)
    estimate = PosedCableState(7.0, 0.1, 33.0, 0.02, pose=pose, pose_variance=(0.1, 0.1, 0.01, 0.01))
    outcome, errors = scorer.score(estimate, truth, INFO)
    assert outcome is Outcome.CORRECT
    assert errors == pytest.approx((2.0, 0.0, 3.0, 0.0, 0.2, -0.1, -1.0, 3.0))
    plain = scorer.score(CableState(7.0, 0.1, 33.0, 0.02), truth, INFO)[1]
    without_true_pose = scorer.score(estimate, TRUTH, INFO)[1]
    assert all(math.isnan(e) for e in plain[4:] + without_true_pose[4:])
    with pytest.raises(EstimateError, match="pose"):
        scorer.check(PosedCableState(7.0, 0.1, 33.0, 0.02, pose=CameraPose(math.nan, 1.0, 0.0, 0.0, 0.0, 0.0)))


def test_frames_without_truth_are_not_scored():
    assert scorer.score(CableState(0, 0, 1, 0), CameraTruth(UNKNOWN_CABLE), INFO)[0] is None
    assert scorer.score(None, None, INFO)[0] is None


@pytest.mark.parametrize(
    "garbage", ["cable", (1, 2, 3, 4), CableState(math.nan, 0, 1, 0), CableState(0, 0, math.inf, 0)]
)
def test_garbage_estimates_are_refused(garbage):
    with pytest.raises(EstimateError):
        CAMERA.check_estimate(garbage)
    if isinstance(garbage, CableState):  # of the right type: the scorer itself refuses its values
        with pytest.raises(EstimateError):
            scorer.check(garbage)
    CAMERA.check_estimate(None)
    scorer.check(CableState(0, 0, 1, 0))


def test_a_frame_without_a_size_cannot_be_scored_by_line_pairs():
    with pytest.raises(ValueError, match="test/seq.*frame size"):
        scorer.score(CableState(5.0, 0.1, 30.0, 0.02), TRUTH, SequenceInfo("test/seq", "camera", 3))


def test_the_camera_modality_scores_with_this_scorer():
    assert isinstance(CAMERA.scorer, CameraScorer)
    assert CAMERA.error_columns == scorer.error_columns == (
        "err_d_px", "err_alpha_deg", "err_w_px", "err_beta_deg", "err_cx_m", "err_cy_m", "err_theta_deg", "err_phi_deg"
    )


def summary_of(scored: list[tuple[Outcome, tuple[float, ...]]]) -> dict[str, float]:
    frames = [
        FrameScore(i, outcome, dict(zip(scorer.error_columns, errors)), 0.01)
        for i, (outcome, errors) in enumerate(scored)
    ]
    return summarise(frame_table(frames), CORE.for_board(None, scorer.error_columns))


@pytest.mark.parametrize("value", [1e308, 1e200, -1e308])
@pytest.mark.parametrize("component", ["d", "alpha", "w", "beta", None])
def test_an_absurd_estimate_is_false_with_finite_errors_and_rmse(component, value):
    if component is None:
        estimate = CableState(value, value, value, value)
    else:
        estimate = dataclasses.replace(TRUTH.cable, **{component: value})
    outcome, errors = scorer.score(estimate, TRUTH, INFO)
    assert outcome is Outcome.FALSE
    assert all(math.isfinite(e) for e in errors[:4]) and all(math.isnan(e) for e in errors[4:])
    summary = summary_of([(outcome, errors)])
    assert all(math.isfinite(summary["rmse_" + c.removeprefix("err_")]) for c in scorer.error_columns[:4])


def test_a_skew_whose_degrees_overflow_is_false_and_reported_as_the_largest_float():
    # The line-pair rule alone calls this estimate correct: 1.0002000100000003e308 rad is 0.02 rad modulo pi.
    estimate = dataclasses.replace(TRUTH.cable, beta=1.0002000100000003e308)
    assert score_line_pair(cable_borders(estimate), cable_borders(TRUTH.cable), INFO.frame_size) is Outcome.CORRECT
    outcome, errors = scorer.score(estimate, TRUTH, INFO)
    assert (outcome, errors[:4]) == (Outcome.FALSE, (0.0, 0.0, 0.0, sys.float_info.max))
    negative = dataclasses.replace(TRUTH.cable, beta=-1e308)
    assert scorer.score(negative, TRUTH, INFO)[1][3] == -sys.float_info.max


@pytest.mark.parametrize("component, value", [("alpha", 1.000000000000002e20), ("beta", 1.0000000000000028e20)])
def test_an_angle_too_large_to_name_a_direction_is_false(component, value):
    # Neighbouring floats of these angles are farther apart than 3 deg, yet the line-pair rule calls them correct.
    estimate = dataclasses.replace(TRUTH.cable, **{component: value})
    assert math.ulp(value) > math.radians(scorer.rule.max_angle_deg)
    assert score_line_pair(cable_borders(estimate), cable_borders(TRUTH.cable), INFO.frame_size) is Outcome.CORRECT
    outcome, errors = scorer.score(estimate, TRUTH, INFO)
    assert outcome is Outcome.FALSE
    if component == "alpha":
        assert errors[1] == 90.0
    else:
        assert errors[3] == pytest.approx(math.degrees(value))


def test_an_angle_of_a_few_turns_is_still_scored_by_the_line_pair_rule():
    outcome, errors = scorer.score(dataclasses.replace(TRUTH.cable, alpha=0.1 + 4 * math.pi), TRUTH, INFO)
    assert outcome is Outcome.CORRECT and errors[1] == pytest.approx(0.0, abs=1e-9)


def test_borders_beyond_the_float_range_are_false_not_a_crash():
    outcome, errors = scorer.score(CableState(1.7e308, 0.0, 1.7e308, 0.0), TRUTH, INFO)
    assert outcome is Outcome.FALSE
    assert errors[:4] == (1.7e308 - 5.0, math.degrees(-0.1), 1.7e308 - 30.0, math.degrees(-0.02))


@pytest.mark.parametrize("bad", [math.inf, -math.inf, math.nan])
@pytest.mark.parametrize("component", ["d", "alpha", "w", "beta"])
def test_non_finite_estimates_are_refused_before_scoring(component, bad):
    with pytest.raises(EstimateError, match="non-finite"):
        CAMERA.check_estimate(dataclasses.replace(TRUTH.cable, **{component: bad}))


finite = st.floats(allow_nan=False, allow_infinity=False)


@given(st.lists(st.tuples(finite, finite, finite, finite), min_size=1, max_size=4))
def test_any_finite_estimate_scores_without_raising_and_summarises_finitely(states):
    scored = []
    for state in states:
        estimate = CableState(*state)
        CAMERA.check_estimate(estimate)
        outcome, errors = scorer.score(estimate, TRUTH, INFO)
        assert outcome in (Outcome.CORRECT, Outcome.FALSE)
        assert len(errors) == len(scorer.error_columns) and all(math.isfinite(e) for e in errors[:4])
        scored.append((outcome, errors))
    assert not any(math.isinf(value) for value in summary_of(scored).values())
