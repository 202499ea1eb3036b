"""Tests of the condensation tracker on drawn cable sequences."""

from __future__ import annotations

import math
import typing

import numpy as np
import pydantic
import pytest
import trackbench_condensation.tracker as tracker_module
from trackbench_condensation import CondensationParams, CondensationTracker
from trackbench_condensation.observation import INTERPOLATIONS
from trackbench_condensation.prior import InitLimits

from benchmark.errors import DataError, ParameterError
from benchmark.filters import RESAMPLERS
from benchmark.modalities.camera.geometry import cable_borders, score_line_pair
from benchmark.modalities.camera.model import CableState, CameraTruth
from benchmark.model import Frame, Outcome, SequenceInfo

SIZE = (320, 240)
INFO = SequenceInfo("drawn", "camera", frame_size=SIZE)


def moving_cable(frames: int) -> list[CableState]:
    """A cable drifting right and turning, about 1.5 px and 0.3 deg per frame."""
    return [
        CableState(-25.0 + 1.5 * k, math.radians(-4.0 + 0.3 * k), 30.0 + 0.1 * k, math.radians(1.0))
        for k in range(frames)
    ]


def make(**overrides) -> CondensationTracker:
    return CondensationTracker(CondensationTracker.make_params(overrides))


def run(tracker, images, seed=0, init=None):
    tracker.reset(INFO, np.random.default_rng(seed), init=init)
    return [tracker.step(Frame(k, image)) for k, image in enumerate(images)]


def outcomes(estimates, states):
    return [
        score_line_pair(None if e is None else cable_borders(e), cable_borders(s), SIZE)
        for e, s in zip(estimates, states, strict=True)
    ]


@pytest.fixture(scope="module")
def sequence(scene):
    states = moving_cable(30)
    return states, [scene.draw_cable(state, contrast=-55.0, seed=k) for k, state in enumerate(states)]


def test_follows_a_moving_cable_from_its_first_state(sequence):
    states, images = sequence
    estimates = run(make(), images, init=CameraTruth(states[0]))
    assert outcomes(estimates, states).count(Outcome.CORRECT) == len(states)


def test_estimate_is_the_weighted_mean_of_the_particles(sequence):
    states, images = sequence
    tracker = make(report_mode=False, outline_fraction=0.0)
    estimate = run(tracker, images[:3], init=CameraTruth(states[0]))[-1]
    np.testing.assert_allclose(estimate.as_array(), tracker.weights @ tracker.particles[:, :4])


def test_the_peak_beside_a_lagging_mean_is_reported(sequence):
    states, images = sequence
    # Started 4 px, 2.5 deg and 6 px of width off, the particles' mean is still off on the first frame.
    first = states[0]
    start = CameraTruth(CableState(first.d + 4.0, first.alpha + math.radians(2.5), first.w + 6.0, first.beta))
    mean_only, with_mode = (
        run(make(report_mode=mode, redetect_fraction=0.0, max_spread_px=0.0, outline_fraction=0.0), images[:1], init=start)[0]
        for mode in (False, True)
    )
    assert outcomes([mean_only, with_mode], states[:1] * 2) == [Outcome.FALSE, Outcome.CORRECT]


def test_particles_that_disagree_on_the_distance_report_no_cable(sequence):
    states, images = sequence
    tracker = make(max_spread_px=0.2, spread_share=0.0)
    estimates = run(tracker, images[:3], init=CameraTruth(states[0]))
    assert estimates == [None] * 3
    assert not tracker._lost  # reported as no detection, but the filter still tracks


def test_the_width_prior_starts_at_the_true_width_and_follows_the_reports(sequence):
    states, images = sequence
    tracker = make(outline_fraction=0.0)
    estimates = run(tracker, images[:2], init=CameraTruth(states[0]))
    rate = tracker.params.width_prior_rate
    expected = (1 - rate) * ((1 - rate) * states[0].w + rate * estimates[0].w) + rate * estimates[1].w
    assert tracker.width_prior.mean_width == pytest.approx(expected)
    tracker.reset(INFO, np.random.default_rng(0))
    assert tracker.width_prior.mean_width is None


def test_the_outline_moves_only_what_is_reported(sequence):
    states, images = sequence
    plain, outlined = make(outline_fraction=0.0), make()
    reports = [run(tracker, images[:4], init=CameraTruth(states[0])) for tracker in (plain, outlined)]
    np.testing.assert_array_equal(plain.particles, outlined.particles)
    np.testing.assert_array_equal(plain.weights, outlined.weights)
    assert plain.width_prior.mean_width == outlined.width_prior.mean_width
    # On the drawn band's sharp borders the outline stays within a pixel of the tracked edges.
    for before, after in zip(*reports, strict=True):
        assert abs(after.alpha - before.alpha) < 1e-12 and abs(after.beta - before.beta) < 1e-12
        for side in (-1.0, 1.0):
            assert abs((after.d + side * after.w / 2) - (before.d + side * before.w / 2)) <= 1.5


def test_the_thesis_variant_reports_the_mean_without_a_width_prior():
    from trackbench_condensation import VARIANTS

    tracker = make(**VARIANTS["condensation-thesis"])
    assert tracker.width_prior is None and tracker.report.mode_gain is None and tracker.report.max_spread_px == 0
    # Nor is its outline moved, and Table 5.2's limits stay in pixels as printed on any frame.
    assert tracker.silhouette is None
    tracker.reset(SequenceInfo("drawn", "camera", frame_size=(640, 480)), np.random.default_rng(0))
    assert tracker.limits == InitLimits()


def test_same_seed_replays_and_another_seed_differs(sequence):
    states, images = sequence
    first = run(make(), images[:12], seed=3, init=CameraTruth(states[0]))
    again = run(make(), images[:12], seed=3, init=CameraTruth(states[0]))
    other = run(make(), images[:12], seed=4, init=CameraTruth(states[0]))
    assert [e.as_array().tolist() for e in first] == [e.as_array().tolist() for e in again]
    assert [e.as_array().tolist() for e in first] != [e.as_array().tolist() for e in other]


def test_uniform_initialisation_within_table_5_2(sequence):
    _, images = sequence
    tracker = make(n_particles=2000, init_w_px=(5.0, 100.0))
    tracker.reset(INFO, np.random.default_rng(0), init=None)
    states = tracker.particles
    assert states.shape == (2000, 6)
    low = np.array([-150, -math.radians(45), 5, 0, -1, -math.radians(0.1)])
    high = np.array([150, math.radians(45), 100, math.radians(10), 1, math.radians(0.1)])
    assert np.all(states >= low) and np.all(states <= high)
    assert np.all(states.max(axis=0) - states.min(axis=0) > 0.9 * (high - low))
    # An unknown first state counts as no initialisation.
    tracker.reset(INFO, np.random.default_rng(0), init=CameraTruth(CableState(*(4 * [math.nan]))))
    assert np.ptp(tracker.particles[:, 0]) > 200


def test_without_initialisation_the_cable_is_found(sequence):
    states, images = sequence
    estimates = run(make(), images, seed=1, init=None)
    assert outcomes(estimates, states)[-10:].count(Outcome.CORRECT) >= 8


@pytest.mark.parametrize(("reference", "found"), [(320.0, True), (0.0, False)])
def test_a_wide_cable_on_a_large_frame_is_found_within_the_scaled_limits(scene, reference, found):
    # 250 px wide on 640 x 480: beyond the 190 px allowed at 320 px, within the 380 px at twice that width.
    size = (640, 480)
    cable = CableState(30.0, math.radians(5.0), 250.0, math.radians(1.0))
    images = [scene.draw_cable(cable, contrast=-50.0, seed=k, size=size) for k in range(6)]
    tracker = make(reference_width_px=reference)
    tracker.reset(SequenceInfo("drawn", "camera", frame_size=size), np.random.default_rng(3), init=None)
    assert tracker.limits.w_px == ((10.0, 380.0) if reference else (5.0, 190.0))
    estimates = [tracker.step(Frame(k, image)) for k, image in enumerate(images)]
    correct = [
        score_line_pair(None if e is None else cable_borders(e), cable_borders(cable), size) == Outcome.CORRECT
        for e in estimates
    ]
    assert all(correct[-3:]) if found else not any(correct)


def test_the_limits_follow_the_frame_when_its_size_is_not_told_in_advance(sequence):
    _, images = sequence
    tracker = make()
    tracker.reset(SequenceInfo("drawn", "camera"), np.random.default_rng(0), init=None)
    assert tracker.limits.d_px == (-150.0, 150.0)
    tracker.step(Frame(0, np.repeat(np.repeat(images[0], 2, axis=0), 2, axis=1)))
    assert tracker.limits.d_px == (-300.0, 300.0) and tracker.scan.width_range_px == (10.0, 380.0)


def test_truth_initialisation_puts_every_particle_at_the_truth(sequence):
    states, _ = sequence
    tracker = make(width_skew_velocities=True)
    tracker.reset(INFO, np.random.default_rng(0), init=CameraTruth(states[0]))
    expected = np.r_[states[0].as_array(), np.zeros(4)]
    np.testing.assert_array_equal(tracker.particles, np.tile(expected, (500, 1)))


def test_reinitialisation_every_k_frames(sequence, monkeypatch):
    states, images = sequence
    calls = []
    original = tracker_module.uniform_particles

    def counting(n, dims, limits, rng):
        calls.append(n)
        return original(n, dims, limits, rng)

    monkeypatch.setattr(tracker_module, "uniform_particles", counting)
    run(make(reinit_every=5, n_particles=100), images[:12], init=CameraTruth(states[0]))
    assert calls == [100, 100]  # before frames 5 and 10
    calls.clear()
    run(make(n_particles=100), images[:12], init=CameraTruth(states[0]))
    assert calls == []


def test_reinitialised_particles_spread_over_the_limits(sequence):
    states, images = sequence
    tracker = make(reinit_every=4, redetect_fraction=0.0)
    run(tracker, images[:4], init=CameraTruth(states[0]))
    assert np.ptp(tracker.particles[:, 0]) < 50
    tracker.step(Frame(4, images[4]))
    assert np.ptp(tracker.particles[:, 0]) > 200


def test_reports_no_cable_on_a_blank_image_after_tracking(sequence):
    states, images = sequence
    tracker = make()
    estimates = run(tracker, images[:8], init=CameraTruth(states[0]))
    assert all(e is not None for e in estimates)
    blank = np.full((SIZE[1], SIZE[0]), 128, np.uint8)
    assert tracker.step(Frame(8, blank)) is None
    assert tracker.step(Frame(9, blank)) is None


def test_finds_the_cable_again_after_it_was_hidden(sequence, scene):
    states, images = sequence
    tracker = make()
    run(tracker, images[:5], init=CameraTruth(states[0]))
    for k in range(5, 12):
        tracker.step(Frame(k, scene.to_uint8(scene.background(seed=k))))
    # The cable comes back 40 px to the right of where it was left.
    moved = CableState(states[4].d + 40.0, states[4].alpha, states[4].w, states[4].beta)
    found = [tracker.step(Frame(12 + k, scene.draw_cable(moved, contrast=-55.0, seed=50 + k))) for k in range(8)]
    assert outcomes(found[-3:], [moved] * 3) == [Outcome.CORRECT] * 3


@pytest.mark.parametrize(
    "variant", [{"width_skew_velocities": True}, {"centre_weight": 1.0}, {"n_particles": 300, "filter_size_px": 5}]
)
def test_variants_follow_the_cable(sequence, variant):
    states, images = sequence
    estimates = run(make(**variant), images[:15], init=CameraTruth(states[0]))
    assert outcomes(estimates, states[:15]).count(Outcome.CORRECT) >= 14


def test_unknown_and_bad_parameters_are_parameter_errors():
    with pytest.raises(ParameterError, match="no parameter 'particles'"):
        CondensationTracker.make_params({"particles": 10})
    for bad in (
        {"filter_size_px": 4},
        {"n_particles": 0},
        {"resampler": "lottery"},
        {"interpolation": "cubic"},
        {"var_w_px2": -1.0},
        {"init_w_px": (10.0, 1.0)},
        {"init_d_px": (-1.0, float("nan"))},
        {"lost_threshold": 2.0},
        {"lost_decay": 0.0},
        {"redetect_fraction": 1.5},
        {"reinit_every": -1},
        {"redetect_candidates": 0},
        {"weight_exponent": 0.0},
        {"n_particles": 2.5},
        {"mode_gain": 0.5},
        {"max_spread_px": -1.0},
        {"width_prior_spread": -0.5},
        {"width_prior_rate": 0.0},
    ):
        (name,) = bad
        with pytest.raises(ParameterError, match=rf"tracker 'condensation'.*{name}"):
            make(**bad)
        with pytest.raises(pydantic.ValidationError, match=name):
            CondensationParams(**bad)


def test_choices_are_the_ones_the_components_know():
    fields = typing.get_type_hints(CondensationParams)
    assert set(typing.get_args(fields["resampler"])) == set(RESAMPLERS)
    assert typing.get_args(fields["interpolation"]) == INTERPOLATIONS


def test_parameters_from_the_command_line_are_converted():
    params = CondensationTracker.make_params({"n_particles": "300", "init_d_px": "[-100, 100]", "carry_weights": "yes"})
    assert params.n_particles == 300 and params.init_d_px == (-100.0, 100.0) and params.carry_weights is True
    assert all(type(value) is float for value in params.init_d_px)
    assert make(n_particles="300").params.n_particles == 300


def test_bad_frames_are_data_errors_naming_the_frame():
    tracker = make()
    tracker.reset(INFO, np.random.default_rng(0))
    with pytest.raises(DataError, match="frame 7"):
        tracker.step(Frame(7, np.zeros((4, 4, 3), np.uint8)))


def test_step_before_reset_fails_clearly():
    with pytest.raises(RuntimeError, match="reset"):
        make().step(Frame(0, np.zeros((240, 320), np.uint8)))
