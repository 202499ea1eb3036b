import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from benchmark.metrics import CameraScorer, EstimateError, FrameScore, frame_table, scorer_for, summarise
from benchmark.model import UNKNOWN_CABLE, CableState, CameraTruth, Outcome, SequenceInfo

INFO = SequenceInfo("test/seq", "camera", 3, frame_size=(320, 240))
TRUTH = CameraTruth(CableState(5.0, 0.1, 30.0, 0.02))
scorer = CameraScorer()


def test_camera_scorer_outcomes_and_errors():
    outcome, errors = scorer.score(CableState(7.0, 0.1, 33.0, 0.02), TRUTH, INFO)
    assert outcome is Outcome.CORRECT
    assert errors == pytest.approx((2.0, 0.0, 3.0, 0.0))
    outcome, errors = scorer.score(CableState(5.0, 0.2, 30.0, 0.02), TRUTH, INFO)
    assert outcome is Outcome.FALSE and errors[1] == pytest.approx(math.degrees(0.1))
    outcome, errors = scorer.score(None, TRUTH, INFO)
    assert outcome is Outcome.MISSED and all(math.isnan(e) for e in errors)


def test_frames_without_truth_are_not_scored():
    assert scorer.score(CableState(0, 0, 1, 0), CameraTruth(UNKNOWN_CABLE), INFO)[0] is None
    assert scorer.score(None, None, INFO)[0] is None


@pytest.mark.parametrize("garbage", ["cable", (1, 2, 3, 4), CableState(math.nan, 0, 1, 0), CableState(0, 0, math.inf, 0)])
def test_garbage_estimates_are_refused(garbage):
    with pytest.raises(EstimateError):
        scorer.check(garbage)
    scorer.check(None)


def test_unknown_modality_is_named():
    with pytest.raises(KeyError, match="lidar"):
        scorer_for("lidar")


outcomes = st.lists(st.sampled_from([*Outcome, None]), min_size=1, max_size=60)


@given(outcomes)
def test_rates_sum_to_100_over_scored_frames(sequence):
    scores = [FrameScore(i, o, dict(zip(scorer.error_columns, (1.0,) * 4)), 0.01) for i, o in enumerate(sequence)]
    summary = summarise(frame_table(scores), scorer.error_columns)
    scored = sum(o is not None for o in sequence)
    assert summary["frames"] == scored
    if scored:
        total = summary["correct_pct"] + summary["false_pct"] + summary["missed_pct"]
        assert total == pytest.approx(100.0)
        assert summary["missed_pct"] == pytest.approx(100.0 * sequence.count(Outcome.MISSED) / scored)
    assert summary["fps"] == pytest.approx(100.0)


def test_rmse_ignores_frames_without_an_error():
    errors = [(3.0, 1.0, 0.0, 0.0), (4.0, -1.0, 0.0, 0.0), (math.nan,) * 4]
    scores = [
        FrameScore(i, Outcome.CORRECT, dict(zip(scorer.error_columns, e)), 0.5) for i, e in enumerate(errors)
    ]
    summary = summarise(frame_table(scores), scorer.error_columns)
    assert summary["rmse_d_px"] == pytest.approx(np.sqrt((9 + 16) / 2))
    assert summary["rmse_alpha_deg"] == pytest.approx(1.0)
    assert summary["fps"] == pytest.approx(2.0)


def stereo_truth(x=10.0, y=5.0, vx=2.0, vy=0.0):
    from benchmark.model import StereoTruth, TargetEstimate

    return StereoTruth(TargetEstimate((x, y), (vx, vy)), chase_position_m=(0.0, 0.0), chase_heading=0.0)


def test_stereo_scorer_position_speed_and_heading_errors():
    from benchmark.model import TargetEstimate

    stereo = scorer_for("stereo")
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
        stereo.check(CableState(0, 0, 1, 0))


SONAR_INFO = SequenceInfo("sonar/as-laid", "sonar", 1)


@given(
    truth_m=st.floats(-40.0, 40.0),
    error_m=st.floats(-5.0, 5.0),
    resolution_m=st.floats(0.01, 1.0),
)
def test_sonar_scorer_counts_a_ping_correct_within_one_beam_spacing(truth_m, error_m, resolution_m):
    from benchmark.model import PipeEstimate, SonarTruth

    sonar = scorer_for("sonar")
    truth = SonarTruth(across_m=truth_m, depth_m=20.0, burial=0.0, resolution_m=resolution_m)
    outcome, (error,) = sonar.score(PipeEstimate(truth_m + error_m), truth, SONAR_INFO)
    assert error == pytest.approx(error_m, abs=1e-9)
    assert (outcome is Outcome.CORRECT) == (abs(error) <= resolution_m)
    assert outcome in (Outcome.CORRECT, Outcome.FALSE)


def test_sonar_scorer_misses_unscored_and_garbage():
    from benchmark.model import PipeEstimate, SonarTruth

    sonar = scorer_for("sonar")
    truth = SonarTruth(across_m=1.0, depth_m=20.0, burial=1.0, resolution_m=0.2)
    outcome, errors = sonar.score(None, truth, SONAR_INFO)
    assert outcome is Outcome.MISSED and math.isnan(errors[0])
    assert sonar.score(PipeEstimate(1.0), None, SONAR_INFO)[0] is None
    for garbage in (1.0, PipeEstimate(math.nan), TRUTH):
        with pytest.raises(EstimateError):
            sonar.check(garbage)
    summary = summarise(frame_table([FrameScore(0, Outcome.CORRECT, {"err_across_m": 0.3}, 0.01)]), sonar.error_columns)
    assert summary["rmse_across_m"] == pytest.approx(0.3)
