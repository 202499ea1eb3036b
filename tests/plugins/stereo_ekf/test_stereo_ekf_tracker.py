"""The stereo EKF on synthetic chases (seeds/002, sections 2-3)."""

from __future__ import annotations

import dataclasses
import typing

import numpy as np
import pydantic
import pytest
from trackbench_stereo_ekf import PAPER, StereoEkfParams, StereoEkfTracker
from trackbench_stereo_ekf.motion import propagate
from trackbench_stereo_ekf.noise import COVARIANCE_FORMS
from trackbench_stereo_raw import StereoRawTracker

from benchmark.errors import DataError, ParameterError
from benchmark.modalities.stereo.geometry import to_north_east
from benchmark.modalities.stereo.modality import STEREO
from benchmark.modalities.stereo.model import ChaseNavigation, StereoMeasurement, StereoTruth, TargetEstimate
from benchmark.model import Frame, SequenceInfo
from benchmark.runner import Cell, run_cell


def _rmse_table(scene, frames, init):
    table = {}
    for name, tracker in (("ekf", StereoEkfTracker()), ("raw", StereoRawTracker())):
        errors = scene.errors(scene.run(tracker, frames, init=init), frames)
        table[name] = {key: scene.rmse(values) for key, values in errors.items()}
    return table


@pytest.mark.parametrize("seed", [0, 1])
def test_ekf_beats_the_raw_baseline_on_a_noisy_straight_chase(scene, seed):
    frames = scene.straight_chase(300, seed=seed, gps_std=0.3)
    table = _rmse_table(scene, frames, init=frames[0].truth)
    assert table["ekf"]["position"] < 0.5 * table["raw"]["position"]
    assert table["ekf"]["speed"] < 0.5 * table["raw"]["speed"]
    assert table["ekf"]["heading"] < table["raw"]["heading"]


def test_ekf_converges_from_its_first_measurement(scene):
    frames = scene.straight_chase(200, seed=2, gps_std=0.3)
    errors = scene.errors(scene.run(StereoEkfTracker(), frames, init=None), frames)
    assert np.isnan(errors["speed"][0])
    assert np.mean(np.abs(errors["speed"][100:])) < 0.3
    assert scene.rmse(errors["position"][100:]) < 1.0
    assert scene.rmse(errors["heading"][100:]) < 5.0


def test_missing_measurements_continue_with_the_prediction(scene):
    frames = scene.straight_chase(160, seed=3, lost=lambda index: 100 <= index < 120)
    tracker = StereoEkfTracker()
    tracker.reset(scene.info(len(frames)), np.random.default_rng(0), init=frames[0].truth)
    estimates, traces = [], []
    for frame in frames:
        estimates.append(tracker.step(frame))
        traces.append(np.trace(tracker.belief.covariance[:2, :2]))
    assert all(estimate is not None for estimate in estimates)
    a, T = tracker.params.control_acceleration_mps2, scene.INTERVAL_S
    for index in range(100, 120):
        previous = np.array([*estimates[index - 1].position_m, *estimates[index - 1].velocity_mps])
        current = np.array([*estimates[index].position_m, *estimates[index].velocity_mps])
        np.testing.assert_allclose(current, propagate(previous, T, a), atol=1e-12)
        assert traces[index] > traces[index - 1]
    errors = scene.errors(estimates, frames)
    assert errors["position"][119] < 2.0
    assert traces[125] < traces[119]


def test_without_init_the_first_measurement_starts_the_filter(scene):
    frames = scene.straight_chase(10, seed=4, lost=lambda index: index < 3 or index == 4)
    tracker = StereoEkfTracker()
    tracker.reset(scene.info(len(frames)), np.random.default_rng(0))
    estimates = []
    for frame in frames:
        estimates.append(tracker.step(frame))
        if frame.index == 3:
            first = tracker.belief.mean
    # nothing before the first measurement, nor until a second one shows a velocity
    assert estimates[:5] == [None] * 5
    navigation = frames[3].navigation
    np.testing.assert_allclose(
        first[:2], to_north_east(*frames[3].observation.relative_m, navigation.position_m, navigation.heading)
    )
    assert np.all(first[2:] == 0.0)
    assert all(estimate is not None for estimate in estimates[5:])


def test_truth_init_reports_the_truth_before_any_measurement(scene):
    frames = scene.straight_chase(5, seed=5, lost=lambda index: index == 0)
    estimate = scene.run(StereoEkfTracker(), frames, init=frames[0].truth)[0]
    assert estimate == frames[0].truth.target


def _one_update(scene, range_m: float, error_m: float, params: StereoEkfParams) -> float:
    """Along-range shift of the estimate of a target at ``range_m`` measured ``error_m`` too far."""
    navigation = ChaseNavigation((0.0, 0.0), 0.0)
    target = TargetEstimate((range_m, 0.0), (0.0, 0.0))
    left, right = scene.project(np.array([range_m + error_m, 0.0]))
    frame = Frame(0, scene.measure(left, right), None, navigation, 0.0)
    tracker = StereoEkfTracker(params)
    tracker.reset(scene.info(1), np.random.default_rng(0), init=StereoTruth(target, (0.0, 0.0), 0.0))
    return tracker.step(frame).position_m[0] - range_m


def test_far_measurements_weigh_less(scene):
    near = _one_update(scene, 8.0, 1.0, StereoEkfParams())
    far = _one_update(scene, 22.0, 1.0, StereoEkfParams())
    assert 0.0 < far < 0.25 * near


def test_beyond_range_inflation_only_touches_far_measurements(scene):
    plain, inflated = StereoEkfParams(), StereoEkfParams(beyond_range_inflation=10.0)
    assert _one_update(scene, 8.0, 1.0, inflated) == pytest.approx(_one_update(scene, 8.0, 1.0, plain))
    assert 0.0 < _one_update(scene, 22.0, 1.0, inflated) < 0.5 * _one_update(scene, 22.0, 1.0, plain)


def test_noise_at_the_measurement_pulls_far_targets_towards_the_camera(scene):
    # both boats at 3 m/s due north, 22 m apart: no GPS noise, only pixel noise
    frames = scene.chase(
        400,
        target=lambda t: (np.array([22.0 + 3.0 * t, 0.0]), np.array([3.0, 0.0])),
        chaser=lambda t: (np.array([3.0 * t, 0.0]), 0.0),
        seed=6,
    )
    bias = {}
    for noise_at in ("measurement", "prediction"):
        estimates = scene.run(StereoEkfTracker(StereoEkfParams(noise_at=noise_at)), frames, init=frames[0].truth)
        along = [e.position_m[0] - f.truth.target.position_m[0] for e, f in zip(estimates, frames, strict=True)]
        bias[noise_at] = float(np.mean(along[100:]))
    # at the prediction what remains is triangulation's own bias, outwards: about x (sigma_d / d)^2 = +0.45 m
    assert bias["measurement"] < -0.8
    assert 0.0 < bias["prediction"] < 1.5


def test_full_covariance_overcorrects_unless_navigation_noise_is_modelled(scene):
    # TG dead ahead, where eq. (18) makes the lateral variance millimetres (seeds/002, Fig. 7(b))
    frames = scene.chase(
        300,
        target=lambda t: (np.array([8.0 + 3.0 * t, 0.0]), np.array([3.0, 0.0])),
        chaser=lambda t: (np.array([3.0 * t - 0.0025 * t * t, 0.0]), 0.0),
        seed=7,
        gps_std=0.3,
        compass_std_deg=0.5,
    )
    variants = {
        "eq18 as printed": StereoEkfParams(**PAPER, covariance="eq18"),
        "eq20 as printed": StereoEkfParams(**PAPER),
        "eq18 with navigation noise": StereoEkfParams(covariance="eq18"),
    }
    rmse = {
        name: scene.rmse(scene.errors(scene.run(StereoEkfTracker(p), frames, init=frames[0].truth), frames)["position"])
        for name, p in variants.items()
    }
    assert rmse["eq18 as printed"] > 5.0 * rmse["eq20 as printed"]
    assert rmse["eq18 with navigation noise"] < 2.0 * rmse["eq20 as printed"]


def test_a_measurement_behind_the_camera_is_treated_as_missing(scene):
    frames = scene.straight_chase(3, seed=8)
    behind = dataclasses.replace(frames[2], observation=StereoMeasurement(150.0, 151.0, (-140.8, 1.0)))
    lost = dataclasses.replace(frames[2], observation=None)
    with_behind = scene.run(StereoEkfTracker(), [*frames[:2], behind], init=frames[0].truth)
    with_lost = scene.run(StereoEkfTracker(), [*frames[:2], lost], init=frames[0].truth)
    assert with_behind == with_lost


def test_runs_are_deterministic(scene):
    frames = scene.straight_chase(50, seed=9, gps_std=0.3)
    assert scene.run(StereoEkfTracker(), frames) == scene.run(StereoEkfTracker(), frames)


@pytest.mark.parametrize(
    "overrides",
    [{"covariance": "eq19"}, {"noise_at": "nowhere"}, {"sigma_a_mps2": 0.0}, {"gps_std_m": -1.0},
     {"beyond_range_inflation": 0.5}, {"control_acceleration_mps2": float("nan")}, {"lateral_k": float("inf")},
     {"frontend_prefilter": "laplace"}, {"frontend_prefilter_cap": 64}],
)
def test_bad_parameters_are_refused(overrides):
    with pytest.raises(ParameterError, match=rf"tracker 'stereo_ekf'.*{next(iter(overrides))}"):
        StereoEkfTracker.make_params(overrides)
    with pytest.raises(pydantic.ValidationError, match=next(iter(overrides))):
        StereoEkfParams(**overrides)


def test_choices_are_the_ones_the_noise_model_knows():
    fields = typing.get_type_hints(StereoEkfParams)
    assert typing.get_args(fields["covariance"]) == COVARIANCE_FORMS
    assert set(typing.get_args(fields["noise_at"])) == {"prediction", "measurement"}


def test_bad_inputs_name_the_sequence_and_frame(scene):
    tracker = StereoEkfTracker()
    with pytest.raises(DataError, match="StereoCalibration"):
        tracker.reset(SequenceInfo("x/y", "stereo", frame_interval_s=0.2), np.random.default_rng(0))
    frames = scene.straight_chase(2, seed=10)
    tracker.reset(scene.info(2), np.random.default_rng(0))
    with pytest.raises(DataError, match="frame 0.*StereoMeasurement"):
        tracker.step(dataclasses.replace(frames[0], observation=np.zeros((4, 4))))
    with pytest.raises(DataError, match="frame 1.*ChaseNavigation"):
        tracker.step(dataclasses.replace(frames[1], navigation=None))


@pytest.mark.parametrize("name", ["stereo_ekf", "stereo_ekf-paper", "stereo_ekf-eq18"])
def test_every_variant_tracks_the_target_in_rendered_image_pairs(name, plugin_registry, stereo_clip):
    result = run_cell(Cell(plugin_registry.trackers[name], stereo_clip, seed=0, init="none", modality=STEREO))
    assert result.status == "ok", result.message
    errors = result.frames["err_position_m"].to_numpy()
    # started from the first measurement, the filter reports once a second one has shown a velocity
    assert np.isnan(errors[0]) and np.all(errors[1:] < 2.0)


def test_an_image_pair_is_read_as_the_front_ends_measurement(stereo_clip, stereo_clip_measured):
    frames = list(stereo_clip.frames())
    runs = []
    for sequence in (frames, stereo_clip_measured):
        tracker = StereoEkfTracker()
        tracker.reset(stereo_clip.info, np.random.default_rng(0), init=frames[0].truth)
        runs.append([tracker.step(frame) for frame in sequence])
    assert runs[0] == runs[1]
    assert all(estimate is not None for estimate in runs[0])


def test_a_gap_in_the_frames_is_predicted_over_its_length_and_frames_may_not_go_back(scene):
    frames = scene.straight_chase(12, seed=7, lost=lambda index: index == 7)
    kept = frames[:5] + frames[7:]  # frames 5 and 6 never arrive; frame 7 has no measurement
    tracker = StereoEkfTracker()
    tracker.reset(scene.info(len(frames)), np.random.default_rng(0), init=frames[0].truth)
    estimates, priors = [], []
    for frame in kept:
        estimates.append(tracker.step(frame))
        priors.append(tracker.prior)
    before, after = estimates[4], estimates[5]
    previous = np.array([*before.position_m, *before.velocity_mps])
    expected = propagate(previous, 3 * scene.INTERVAL_S, tracker.params.control_acceleration_mps2)
    np.testing.assert_allclose([*after.position_m, *after.velocity_mps], expected, atol=1e-12)
    assert priors[5] is None and priors[6] is not None
    assert all(estimate is not None for estimate in estimates)
    with pytest.raises(DataError, match="frame 3 follows frame 11"):
        tracker.step(frames[3])
