"""The sonar scorer: a ping is correct within one beam spacing at the pipe (seeds/003)."""

import math
import sys

import pytest
from hypothesis import given
from hypothesis import strategies as st

from benchmark.modalities.camera.model import CableState, CameraTruth
from benchmark.modalities.sonar.modality import SONAR
from benchmark.modalities.sonar.model import PipeEstimate, SonarTruth
from benchmark.modalities.sonar.scoring import SonarScorer
from benchmark.modality import EstimateError
from benchmark.model import Outcome, SequenceInfo
from benchmark.metrics import CORE
from benchmark.results import FrameScore, frame_table, summarise

SONAR_INFO = SequenceInfo("sonar/as-laid", "sonar", 1)
CAMERA_TRUTH = CameraTruth(CableState(5.0, 0.1, 30.0, 0.02))


@given(
    truth_m=st.floats(-40.0, 40.0),
    error_m=st.floats(-5.0, 5.0),
    resolution_m=st.floats(0.01, 1.0),
)
def test_sonar_scorer_counts_a_ping_correct_within_one_beam_spacing(truth_m, error_m, resolution_m):
    sonar = SonarScorer()
    truth = SonarTruth(across_m=truth_m, depth_m=20.0, burial=0.0, resolution_m=resolution_m)
    outcome, (error,) = sonar.score(PipeEstimate(truth_m + error_m), truth, SONAR_INFO)
    assert error == pytest.approx(error_m, abs=1e-9)
    assert (outcome is Outcome.CORRECT) == (abs(error) <= resolution_m)
    assert outcome in (Outcome.CORRECT, Outcome.FALSE)


def test_sonar_scorer_misses_unscored_and_garbage():
    sonar = SonarScorer()
    truth = SonarTruth(across_m=1.0, depth_m=20.0, burial=1.0, resolution_m=0.2)
    outcome, errors = sonar.score(None, truth, SONAR_INFO)
    assert outcome is Outcome.MISSED and math.isnan(errors[0])
    assert sonar.score(PipeEstimate(1.0), None, SONAR_INFO)[0] is None
    for garbage in (1.0, PipeEstimate(math.nan), CAMERA_TRUTH):
        with pytest.raises(EstimateError):
            SONAR.check_estimate(garbage)
    with pytest.raises(EstimateError):
        sonar.check(PipeEstimate(math.nan))
    sonar.check(PipeEstimate(1.0))
    frames = frame_table([FrameScore(0, Outcome.CORRECT, {"err_across_m": 0.3}, 0.01)])
    summary = summarise(frames, CORE.for_board(None, sonar.error_columns))
    assert summary["rmse_across_m"] == pytest.approx(0.3)


def test_the_sonar_modality_scores_with_this_scorer():
    assert isinstance(SONAR.scorer, SonarScorer)
    assert SONAR.error_columns == SonarScorer().error_columns == ("err_across_m",)


def sonar_summary(scored):
    frames = [FrameScore(i, outcome, {"err_across_m": error}, 0.01) for i, (outcome, (error,)) in enumerate(scored)]
    return summarise(frame_table(frames), CORE.for_board(None, ("err_across_m",)))


@pytest.mark.parametrize("value", [1e308, 1e200, -1e308])
def test_an_absurd_position_is_false_and_its_rmse_finite(value):
    truth = SonarTruth(across_m=1.0, depth_m=20.0, burial=0.0, resolution_m=0.2)
    outcome, (error,) = SonarScorer().score(PipeEstimate(value), truth, SONAR_INFO)
    assert outcome is Outcome.FALSE and error == value - 1.0
    assert sonar_summary([(outcome, (error,)), (Outcome.CORRECT, (0.1,))])["rmse_across_m"] == pytest.approx(
        abs(value) / math.sqrt(2.0)
    )


def test_an_error_that_overflows_is_false_at_any_tolerance_and_kept_as_the_largest_float():
    truth = SonarTruth(across_m=-1e308, depth_m=20.0, burial=0.0, resolution_m=0.2)
    lenient = SonarScorer(tolerance_beams=math.inf)
    assert lenient.score(PipeEstimate(1e308), truth, SONAR_INFO) == (Outcome.FALSE, (sys.float_info.max,))
    assert lenient.score(PipeEstimate(1e300), truth, SONAR_INFO)[0] is Outcome.CORRECT
    mirrored = SonarTruth(across_m=1e308, depth_m=20.0, burial=0.0, resolution_m=0.2)
    assert SonarScorer().score(PipeEstimate(-1e308), mirrored, SONAR_INFO) == (Outcome.FALSE, (-sys.float_info.max,))


@pytest.mark.parametrize("bad", [math.inf, -math.inf, math.nan])
def test_non_finite_positions_are_refused_before_scoring(bad):
    with pytest.raises(EstimateError, match="non-finite"):
        SONAR.check_estimate(PipeEstimate(bad))


@given(
    st.lists(st.floats(allow_nan=False, allow_infinity=False), min_size=1, max_size=4),
    st.floats(-1e308, 1e308),
)
def test_any_finite_estimate_scores_without_raising_and_summarises_finitely(positions, truth_m):
    sonar = SonarScorer()
    truth = SonarTruth(across_m=truth_m, depth_m=20.0, burial=0.0, resolution_m=0.2)
    scored = []
    for position in positions:
        SONAR.check_estimate(PipeEstimate(position))
        outcome, errors = sonar.score(PipeEstimate(position), truth, SONAR_INFO)
        assert outcome in (Outcome.CORRECT, Outcome.FALSE)
        assert len(errors) == 1 and math.isfinite(errors[0])
        scored.append((outcome, errors))
    assert not any(math.isinf(value) for value in sonar_summary(scored).values())
