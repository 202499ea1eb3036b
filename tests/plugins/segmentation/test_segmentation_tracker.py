"""Tests of the segmentation tracker on drawn cable sequences: tracking, loss, bad frames, determinism."""

from __future__ import annotations

import math

import numpy as np
import pytest
from trackbench_segmentation.tracker import SegmentationTracker

from benchmark.errors import DataError, ParameterError
from benchmark.modalities.camera.geometry import cable_borders, score_line_pair
from benchmark.modalities.camera.model import UNKNOWN_CABLE, CableState, CameraTruth
from benchmark.model import Frame, Outcome, SequenceInfo

SIZE = (320, 240)
INFO = SequenceInfo("drawn", "camera", frame_size=SIZE)


def fresh(init: CameraTruth | None = None, **overrides) -> SegmentationTracker:
    tracker = SegmentationTracker(SegmentationTracker.make_params(overrides))
    tracker.reset(INFO, np.random.default_rng(0), init=init)
    return tracker


def outcome(estimate: CableState | None, truth: CableState) -> Outcome:
    return score_line_pair(None if estimate is None else cable_borders(estimate), cable_borders(truth), SIZE)


def moving_cable(k: int) -> CableState:
    return CableState(-30.0 + 3.0 * k, math.radians(-5.0 + 1.0 * k), 30.0 + 0.5 * k, math.radians(1.5))


def test_tracks_a_moving_cable_with_a_kalman_predicted_roi(scene):
    tracker = fresh()
    for k in range(8):
        truth = moving_cable(k)
        estimate = tracker.step(Frame(k, scene.cable(truth, seed=k)))
        assert outcome(estimate, truth) is Outcome.CORRECT, f"frame {k}"
        assert tracker.belief is not None
        covariance = tracker.belief.covariance
        assert np.array_equal(covariance, covariance.T)
        assert np.linalg.eigvalsh(covariance).min() > 0
    # From the second frame on the search is limited to the predicted region of interest.
    assert tracker.prediction is not None
    assert 0.1 < tracker.prediction.roi.mean() < 0.8


def test_the_roi_keeps_a_far_distractor_out_until_the_cable_is_lost(scene):
    cable = CableState(-80.0, 0.0, 30.0, 0.0)
    distractor = CableState(80.0, math.radians(-8.0), 36.0, 0.0)
    tracker = fresh(max_misses=3)
    assert outcome(tracker.step(Frame(0, scene.cable(cable))), cable) is Outcome.CORRECT
    for k in range(1, 4):
        assert tracker.step(Frame(k, scene.cable(distractor, seed=k))) is None
    assert tracker.belief is None
    assert outcome(tracker.step(Frame(4, scene.cable(distractor, seed=4))), distractor) is Outcome.CORRECT


def test_the_roi_widens_while_frames_go_without_a_pair(scene):
    tracker = fresh(max_misses=10)
    tracker.step(Frame(0, scene.cable(CableState(0.0, 0.0, 30.0, 0.0))))
    blank = np.full(SIZE[::-1], 120, np.uint8)
    shares = []
    for k in range(1, 4):
        assert tracker.step(Frame(k, blank)) is None
        shares.append(tracker.prediction.roi.mean())
    assert shares[0] < shares[1] < shares[2]


def test_init_starts_the_filter_and_unknown_init_is_ignored(scene):
    cable = CableState(-80.0, 0.0, 30.0, 0.0)
    distractor = CableState(80.0, 0.0, 30.0, 0.0)
    started = fresh(init=CameraTruth(cable))
    assert started.belief is not None
    assert started.step(Frame(0, scene.cable(distractor))) is None
    for init in (CameraTruth(UNKNOWN_CABLE), CameraTruth(cable)):
        ignoring = fresh(init=init, use_init=init.cable is UNKNOWN_CABLE)
        assert ignoring.belief is None
        assert outcome(ignoring.step(Frame(0, scene.cable(distractor))), distractor) is Outcome.CORRECT


def test_the_filter_states_its_variances_in_pixels_of_the_frame_size(scene):
    cable = CableState(-80.0, 0.0, 30.0, 0.0)
    d_var, alpha_var, w_var = SegmentationTracker.Params().measurement_var
    for size, factor in ((SIZE, 1.0), ((640, 480), 2.0)):
        tracker = SegmentationTracker()
        tracker.reset(SequenceInfo("drawn", "camera", frame_size=size), np.random.default_rng(0), init=CameraTruth(cable))
        expected = np.diag([d_var * factor**2, alpha_var, w_var * factor**2])
        assert np.allclose(tracker.belief.covariance, expected)


def test_without_a_known_frame_size_the_start_waits_for_the_first_frame(scene):
    truth = moving_cable(0)
    tracker = SegmentationTracker()
    tracker.reset(SequenceInfo("drawn", "camera"), np.random.default_rng(0), init=CameraTruth(truth))
    assert tracker.belief is None
    estimate = tracker.step(Frame(0, scene.cable(truth)))
    assert tracker.prediction is not None, "the first frame is searched in the region of interest of init"
    assert outcome(estimate, truth) is Outcome.CORRECT


def test_reset_forgets_the_previous_sequence(scene):
    tracker = fresh()
    tracker.step(Frame(0, scene.cable(CableState(0.0, 0.0, 30.0, 0.0))))
    assert tracker.belief is not None
    tracker.reset(INFO, np.random.default_rng(0))
    assert tracker.belief is None and tracker.prediction is None


def test_is_deterministic_and_ignores_the_generator(scene):
    images = [scene.cable(moving_cable(k), seed=k) for k in range(5)]
    runs = []
    for seed in (1, 2):
        tracker = SegmentationTracker()
        tracker.reset(INFO, np.random.default_rng(seed))
        runs.append([tracker.step(Frame(k, image)) for k, image in enumerate(images)])
    assert runs[0] == runs[1]
    assert all(estimate is not None for estimate in runs[0])


@pytest.mark.parametrize(
    "observation, message",
    [
        (np.full((240, 320), np.nan), "NaN"),
        (np.zeros((240, 320), np.float64), "float64"),
        (np.zeros((240, 320), np.int32), "int32"),
        (np.zeros((240, 320, 2), np.uint8), r"shape \(240, 320, 2\)"),
        (np.zeros(320, np.uint8), r"shape \(320,\)"),
        (np.zeros((0, 320), np.uint8), r"shape \(0, 320\) is smaller than 3 px"),
        ([[1, 2, 3]], "list"),
    ],
    ids=["nan", "float", "int32", "two-channel", "1-d", "empty", "not-an-array"],
)
def test_bad_frames_are_data_errors_naming_the_frame(observation, message):
    with pytest.raises(DataError, match=rf"segmentation: frame 7: .*{message}"):
        fresh().step(Frame(7, observation))


def test_colour_frames_are_read_as_grey(scene):
    truth = CableState(10.0, 0.05, 30.0, 0.0)
    grey = scene.cable(truth)
    colour = np.repeat(grey[:, :, None], 3, axis=2)
    assert fresh().step(Frame(0, colour)) == fresh().step(Frame(0, grey))


def test_unknown_parameter_is_a_parameter_error():
    with pytest.raises(ParameterError, match="pyramid_levelz"):
        SegmentationTracker.make_params({"pyramid_levelz": 2})


@pytest.mark.parametrize(
    "bad",
    [
        {"pyramid_levels": 0},
        {"smooth_share": 0.0},
        {"valley_ratio": 1.5},
        {"max_skew_deg": 45.0},
        {"min_width_px": 200.0},
        {"process_var": (1.0, -1.0, 1.0)},
        {"max_misses": 0},
    ],
)
def test_values_outside_the_declared_domains_are_parameter_errors(bad):
    (name,) = bad
    with pytest.raises(ParameterError, match=rf"tracker 'segmentation'.*{name}"):
        SegmentationTracker.make_params(bad)


@pytest.mark.parametrize("gate_sigmas, reported", [(4.0, "cable"), (0.0, "distractor")])
def test_the_gate_passes_over_better_scored_pairs_the_filter_cannot_have_produced(
    scene, monkeypatch, gate_sigmas, reported
):
    import trackbench_segmentation.detector as detector_module
    from trackbench_segmentation.pairing import BorderPair

    cable = CableState(0.0, 0.0, 30.0, 0.0)
    states = {"distractor": CableState(4.0, math.radians(25.0), 30.0, 0.0), "cable": CableState(2.0, 0.01, 31.0, 0.0)}
    pairs = [BorderPair(0, 1, cable_borders(state), state, score) for state, score in zip(states.values(), (900.0, 500.0))]
    monkeypatch.setattr(detector_module, "detect_pairs", lambda image, params, prediction: pairs)
    tracker = fresh(init=CameraTruth(cable), gate_sigmas=gate_sigmas)
    assert tracker.step(Frame(0, scene.cable(cable))) == states[reported]
