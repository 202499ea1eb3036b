"""The stereo scorer: position, speed and heading errors of the target boat (seeds/002)."""

import math

import pytest

from benchmark.modalities.camera.model import CableState
from benchmark.modalities.stereo.modality import STEREO
from benchmark.modalities.stereo.model import StereoTruth, TargetEstimate
from benchmark.modalities.stereo.scoring import StereoScorer
from benchmark.modality import EstimateError
from benchmark.model import Outcome, SequenceInfo


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
