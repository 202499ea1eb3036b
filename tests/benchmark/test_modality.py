"""The modality contract: frames and estimates checked against a modality's declared types."""

from __future__ import annotations

import math
import pickle
import sys
import types
from dataclasses import dataclass

import numpy as np
import pytest

from benchmark.errors import DataError
from benchmark.modalities.camera.modality import CAMERA
from benchmark.modalities.camera.model import CableState, CameraTruth
from benchmark.modalities.sonar.modality import SONAR
from benchmark.modalities.sonar.model import PipeEstimate, SonarTruth, Swath
from benchmark.modalities.stereo.modality import STEREO
from benchmark.modalities.stereo.model import StereoMeasurement, StereoTruth, TargetEstimate
from benchmark.modality import ANY_FILE, EstimateError, Modality, Reader, sequences_in
from benchmark.model import Frame

TRUTH = CameraTruth(CableState(1.0, 0.1, 20.0, 0.02))


def camera_frame(observation: object, truth: object = TRUTH) -> Frame:
    return Frame(3, observation, truth)


def test_a_frame_of_the_declared_types_passes() -> None:
    CAMERA.check_frame(camera_frame(np.zeros((4, 6), np.uint8)), "seq, frame 3")
    CAMERA.check_frame(camera_frame(np.zeros((4, 6), np.uint8), truth=None), "seq, frame 3")


@pytest.mark.parametrize(
    ("frame", "message"),
    [
        (camera_frame("a cable"), r"seq, frame 3: the observation is a str, not what a camera frame holds \(ndarray\)"),
        (camera_frame(np.zeros((4, 6)), TRUTH.cable), r"the truth is a CableState, not a CameraTruth or None"),
    ],
)
def test_a_frame_of_other_types_is_a_data_error_naming_where(frame: Frame, message: str) -> None:
    with pytest.raises(DataError, match=message):
        CAMERA.check_frame(frame, "seq, frame 3")


def test_a_modality_may_take_several_observation_types() -> None:
    pair = (np.zeros((2, 2, 3)), np.zeros((2, 2, 3)))
    for observation in (StereoMeasurement(310.0, 300.0, (12.0, 1.0)), pair, None):
        STEREO.check_frame(Frame(0, observation), "stereo seq, frame 0")
    expected = r"not what a stereo frame holds \(StereoMeasurement or tuple or list or None\)"
    with pytest.raises(DataError, match=expected):
        STEREO.check_frame(Frame(0, 3.0), "stereo seq, frame 0")


def test_estimates_are_checked_for_type_then_by_the_scorer_for_values() -> None:
    SONAR.check_estimate(None)
    SONAR.check_estimate(PipeEstimate(1.5))
    with pytest.raises(EstimateError, match=r"expected a PipeEstimate or None, got float: 1.5"):
        SONAR.check_estimate(1.5)
    with pytest.raises(EstimateError, match="non-finite"):
        SONAR.check_estimate(PipeEstimate(math.nan))
    with pytest.raises(EstimateError, match="non-finite"):
        CAMERA.check_estimate(CableState(math.nan, 0.0, 10.0, 0.0))


def test_error_columns_and_claims_come_from_the_declaration() -> None:
    assert CAMERA.error_columns == CAMERA.scorer.error_columns
    assert CAMERA.error_columns[:4] == ("err_d_px", "err_alpha_deg", "err_w_px", "err_beta_deg")
    assert SONAR.error_columns == ("err_across_m",)
    assert "folders" in CAMERA.claims and "any other file" in CAMERA.claims and "files ending .avi" in CAMERA.claims
    assert SONAR.claims == ("files ending .swaths",)
    assert STEREO.claims == ("folders holding left, right",)


@dataclass(frozen=True)
class Ping:
    value: float


def test_a_minimal_modality_needs_only_its_types_and_scorer() -> None:
    @dataclass(frozen=True)
    class Scorer:
        error_columns: tuple[str, ...] = ("err_value_m",)

        def check(self, estimate: Ping) -> None:
            if estimate.value < 0:
                raise EstimateError("negative")

        def score(self, estimate, truth, info):  # pragma: no cover - not scored here
            raise AssertionError

    minimal = Modality("ping", Ping, Ping, Ping, Scorer())
    assert minimal.readers == () and minimal.exporter is None and dict(minimal.scene_kinds) == {}
    assert minimal.draw is None
    minimal.check_frame(Frame(0, Ping(1.0), Ping(1.0)), "here")
    with pytest.raises(EstimateError, match="negative"):
        minimal.check_estimate(Ping(-1.0))
    reader = Reader(lambda path: None, "anything", suffixes=(ANY_FILE,))  # type: ignore[arg-type, return-value]
    assert Modality("ping", Ping, Ping, Ping, Scorer(), readers=(reader,)).claims == ("any other file",)


def test_the_built_in_modalities_draw_their_frames_as_bgr_pictures() -> None:
    frames = {
        CAMERA: (Frame(0, np.zeros((4, 6), np.uint8), TRUTH), CableState(0.0, 0.0, 2.0, 0.0)),
        SONAR: (Frame(0, Swath(np.array([-1.0, 1.0]), np.array([5.0, 5.0])), SonarTruth(0.0, 4.5, 0.0, 0.1)),
                PipeEstimate(0.5)),
        STEREO: (Frame(0, None, StereoTruth(TargetEstimate((5.0, 0.0), (1.0, 0.0)), (0.0, 0.0), 0.0)), None),
    }
    for modality, (frame, estimate) in frames.items():
        assert modality.draw is not None, modality.name
        picture = modality.draw(frame, estimate)
        assert picture.dtype == np.uint8 and picture.ndim == 3 and picture.shape[2] == 3, modality.name


def test_sequences_in_imports_its_module_only_when_called(monkeypatch: pytest.MonkeyPatch) -> None:
    lazy = sequences_in("no_such_strategies_module")
    with pytest.raises(ModuleNotFoundError, match="no_such_strategies_module"):
        lazy(3)
    module = types.ModuleType("fake_strategies")
    module.sequences = lambda max_frames: ("strategy of", max_frames)  # type: ignore[attr-defined]
    monkeypatch.setitem(sys.modules, "fake_strategies", module)
    assert pickle.loads(pickle.dumps(sequences_in("fake_strategies")))(4) == ("strategy of", 4)
