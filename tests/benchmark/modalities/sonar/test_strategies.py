"""The sonar strategies: valid calibrations and specs, labelled sequences, swaths with the faults asked for."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest
from hypothesis import Phase, given, settings
from hypothesis import strategies as st

from benchmark.modalities.sonar.modality import SONAR
from benchmark.modalities.sonar.model import SonarCalibration, SonarTruth, Swath
from benchmark.modalities.sonar.scenes.scene import SonarScene
from benchmark.modalities.sonar.scenes.spec import PipeSpec, SonarSceneSpec, SonarSpec
from benchmark.modalities.sonar.scenes.swath import beam_angles
from benchmark.modalities.sonar.strategies import (
    N_BEAMS,
    PIPE_DIAMETER_M,
    RANGE_GATE_M,
    RANGE_SIGMA_M,
    SWATH_DEG,
    calibrations,
    scene_specs,
    sequences,
    swaths,
)


def _examples(strategy: st.SearchStrategy[Any], count: int) -> list[Any]:
    """``count`` examples of ``strategy``, the same ones on every run."""
    found: list[Any] = []

    @settings(max_examples=count, deadline=None, derandomize=True, database=None, phases=[Phase.generate])
    @given(strategy)
    def collect(example: Any) -> None:
        found.append(example)

    collect()
    return found


def _spiked(swath: Swath) -> np.ndarray:
    """Returns no bottom can give: above the transducer or beyond the range gate."""
    return (swath.depth_m <= 0.0) | (swath.depth_m > RANGE_GATE_M)


def _within(value: float, bounds: tuple[float, float]) -> bool:
    return bounds[0] <= value <= bounds[1]


@settings(max_examples=50, deadline=None)
@given(calibrations())
def test_calibrations_are_plausible_sonars_the_scenes_accept(calibration: SonarCalibration) -> None:
    assert _within(calibration.n_beams, N_BEAMS)
    assert _within(math.degrees(calibration.swath_angle), (SWATH_DEG[0] - 1e-9, SWATH_DEG[1] + 1e-9))
    assert _within(calibration.range_sigma_m, RANGE_SIGMA_M)
    assert _within(calibration.pipe_diameter_m, PIPE_DIAMETER_M)
    SonarSpec(
        n_beams=calibration.n_beams,
        swath_deg=math.degrees(calibration.swath_angle),
        range_sigma_m=calibration.range_sigma_m,
    )
    PipeSpec(diameter_m=calibration.pipe_diameter_m)


@settings(max_examples=40, deadline=None)
@given(scene_specs(max_frames=3))
def test_scene_specs_are_valid_tables_of_one_to_max_frames_pings(spec: SonarSceneSpec) -> None:
    assert isinstance(spec, SonarSceneSpec)
    assert 1 <= spec.n_frames <= 3
    assert SonarSceneSpec.from_dict(spec.to_dict()) == spec
    calibration = spec.calibration()
    assert _within(calibration.n_beams, N_BEAMS)
    assert _within(calibration.pipe_diameter_m, PIPE_DIAMETER_M)


def test_max_frames_below_one_is_refused() -> None:
    with pytest.raises(ValueError, match="max_frames must be >= 1"):
        scene_specs(max_frames=0)


@settings(max_examples=40, deadline=None)
@given(sequences(max_frames=3))
def test_sequences_hold_one_to_max_frames_labelled_sonar_pings(sequence: SonarScene) -> None:
    info = sequence.info
    frames = list(sequence.frames())
    assert info.modality == "sonar" and 1 <= len(frames) == info.n_frames <= 3
    for frame in frames:
        SONAR.check_frame(frame, f"{info.name} frame {frame.index}")
        assert isinstance(frame.truth, SonarTruth)
        assert frame.observation.across_m.shape == (info.calibration.n_beams,)


@settings(max_examples=20, deadline=None)
@given(scene_specs(max_frames=3))
def test_the_same_spec_gives_the_same_swaths_bit_for_bit(spec: SonarSceneSpec) -> None:
    for first, second in zip(SonarScene(spec).frames(), SonarScene(spec).frames(), strict=True):
        assert np.array_equal(first.observation.across_m, second.observation.across_m, equal_nan=True)
        assert np.array_equal(first.observation.depth_m, second.observation.depth_m, equal_nan=True)
        assert first.truth == second.truth


def test_missing_beams_are_nan_in_both_arrays_one_by_one_in_runs_or_all() -> None:
    examples = _examples(swaths(), 80)
    for swath in examples:
        assert np.array_equal(np.isnan(swath.across_m), np.isnan(swath.depth_m))
    lost = [~swath.valid for swath in examples]
    assert any(mask.any() for mask in lost)
    assert any(mask.all() for mask in lost)
    assert any((mask[1:] & mask[:-1]).any() and not mask.all() for mask in lost)


@settings(max_examples=40, deadline=None)
@given(swaths(missing=False, spikes=True))
def test_spikes_are_there_when_asked(swath: Swath) -> None:
    assert swath.valid.all()
    assert 1 <= _spiked(swath).sum() <= max(1, swath.depth_m.size // 10)


@settings(max_examples=40, deadline=None)
@given(calibrations(), st.data())
def test_clean_swaths_have_the_calibrations_beams_and_neither_gaps_nor_spikes(
    calibration: SonarCalibration, data: st.DataObject
) -> None:
    swath = data.draw(swaths(calibration, missing=False, spikes=False))
    assert swath.across_m.shape == swath.depth_m.shape == (calibration.n_beams,)
    assert swath.valid.all() and not _spiked(swath).any()
    # a level sonar: each return lies on its beam
    bearings = np.arctan2(swath.across_m, swath.depth_m)
    assert np.allclose(bearings, beam_angles(calibration.n_beams, calibration.swath_angle), atol=1e-9)


@settings(max_examples=30, deadline=None)
@given(calibrations(), st.data())
def test_damaged_swaths_keep_the_calibrations_beams(calibration: SonarCalibration, data: st.DataObject) -> None:
    swath = data.draw(swaths(calibration))
    assert swath.across_m.shape == swath.depth_m.shape == (calibration.n_beams,)
