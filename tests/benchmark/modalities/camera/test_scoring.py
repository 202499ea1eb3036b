"""The camera scorer: Foresti's line-pair rule and the cable-state errors (seeds/004, Table V)."""

import math

import pytest

from benchmark.modalities.camera.modality import CAMERA
from benchmark.modalities.camera.model import UNKNOWN_CABLE, CableState, CameraTruth
from benchmark.modalities.camera.scoring import CameraScorer
from benchmark.modality import EstimateError
from benchmark.model import Outcome, SequenceInfo

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
    assert CAMERA.error_columns == scorer.error_columns == ("err_d_px", "err_alpha_deg", "err_w_px", "err_beta_deg")
