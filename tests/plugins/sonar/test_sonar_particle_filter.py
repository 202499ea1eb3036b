"""The ``sonar_pf`` tracker (seeds/003, section 3, eqs. 3-5 and section 3.4)."""

from __future__ import annotations

import dataclasses
import math
import typing

import numpy as np
import pydantic
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays
from trackbench_sonar import SonarDetector, SonarParticleFilter
from trackbench_sonar.likelihood import LikelihoodScan
from trackbench_sonar.params import ParticleFilterParams, ResamplerName
from trackbench_sonar.particle_filter import AcrossTrackRate, ScanWeights, injection_rate, nothing_lost, walk_sigma

from benchmark.errors import DataError, ParameterError
from benchmark.filters import RESAMPLERS
from benchmark.modalities.sonar.model import PipeEstimate, SonarTruth, Swath
from benchmark.model import Frame, SequenceInfo


def run(tracker, info, frames, seed=0, init="truth"):
    tracker.reset(info, np.random.default_rng(seed), frames[0].truth if init == "truth" else init)
    return [tracker.step(frame) for frame in frames]


def start_at(across_m: float) -> SonarTruth:
    """A first ping's truth with the pipe at ``across_m``."""
    return SonarTruth(across_m, 9.7, 0.0, 0.09)


def meander(n: int = 60) -> np.ndarray:
    return 2.0 + 3.0 * np.sin(np.arange(n) / 15.0)


def test_follows_a_meandering_pipe_from_the_truth(swaths):
    positions = meander()
    frames = swaths.track(positions, noise=0.01, missing=0.03, spikes=2)
    estimates = run(SonarParticleFilter(), swaths.info(), frames)
    errors = np.array([e.across_m for e in estimates]) - positions
    tolerance = np.array([f.truth.resolution_m for f in frames])
    assert np.all(np.abs(errors) <= 2.0 * tolerance)


def test_finds_the_pipe_without_a_start(swaths):
    positions = meander()
    frames = swaths.track(positions, noise=0.01)
    estimates = run(SonarParticleFilter(), swaths.info(), frames, init=None)
    errors = np.abs(np.array([e.across_m for e in estimates]) - positions)
    assert np.all(errors[20:] <= 0.2)


def test_stays_on_its_pipe_when_a_second_one_shows_up(swaths):
    positions = meander(40)
    frames = swaths.track(positions, noise=0.01)
    rival = [
        dataclasses.replace(frame, observation=swaths.make(x, second_at=x + 2.5, noise=0.01, burial=0.0, seed=k))
        for k, (frame, x) in enumerate(zip(frames, positions))
    ]
    estimates = run(SonarParticleFilter(), swaths.info(), rival)
    assert np.all(np.abs(np.array([e.across_m for e in estimates]) - positions) <= 0.2)


def test_the_same_seed_replays_bit_for_bit_and_another_does_not(swaths):
    frames = swaths.track(meander(20), noise=0.02, missing=0.05)
    info = swaths.info()
    first = [e.across_m for e in run(SonarParticleFilter(), info, frames, seed=5)]
    again = [e.across_m for e in run(SonarParticleFilter(), info, frames, seed=5)]
    other = [e.across_m for e in run(SonarParticleFilter(), info, frames, seed=6)]
    assert first == again
    assert first != other


@settings(max_examples=20, deadline=None)
@given(
    pipe_at=st.none() | st.floats(-10.0, 10.0),
    noise=st.floats(0.0, 0.2),
    missing=st.floats(0.0, 1.0),
    n_particles=st.integers(1, 200),
    exponent=st.floats(0.5, 8.0),
    floor=st.floats(0.0, 0.5),
    seed=st.integers(0, 2**16),
)
def test_weights_stay_normalised_under_eq_4(swaths, pipe_at, noise, missing, n_particles, exponent, floor, seed):
    params = dataclasses.replace(
        ParticleFilterParams(), n_particles=n_particles, weight_exponent=exponent, weight_floor=floor
    )
    tracker = SonarParticleFilter(params)
    tracker.reset(swaths.info(), np.random.default_rng(seed), start_at(0.0))
    for k in range(3):
        estimate = tracker.step(Frame(k, swaths.make(pipe_at, noise=noise, missing=missing, seed=seed + k)))
        weights = tracker.weights
        assert weights.shape == (n_particles,)
        assert np.all(np.isfinite(weights)) and np.all(weights >= 0.0)
        assert weights.sum() == pytest.approx(1.0)
        assert estimate is not None and math.isfinite(estimate.across_m)


def _frozen(**changes) -> ParticleFilterParams:
    """Parameters without a walk or drift (nor, unless changed, a spread at the start), injecting at the fixed
    rate J, with the sharp scan of the ellipse."""
    still = {"walk_sigma_m": 0.0, "walk_speed_mps": 0.0, "init_sigma_m": 0.0, "weight_exponent": 50.0}
    still |= {"drift_gain": 0.0, "lost_ratio": 0.0, "likelihood": "ellipse"}
    return dataclasses.replace(ParticleFilterParams(), **(still | changes))


@settings(max_examples=20, deadline=None)
@given(fraction=st.floats(0.001, 0.5), n_particles=st.integers(2, 300), seed=st.integers(0, 2**16))
def test_with_injection_the_particles_never_collapse_onto_one_value(swaths, fraction, n_particles, seed):
    # No walk and a sharp scan: without injection resampling would leave copies of one particle.
    tracker = SonarParticleFilter(_frozen(n_particles=n_particles, inject_fraction=fraction, weight_floor=0.0))
    tracker.reset(swaths.info(), np.random.default_rng(seed), start_at(1.0))
    for k in range(6):
        tracker.step(Frame(k, swaths.make(1.0, noise=0.01, seed=k)))
        assert np.unique(tracker.particles).size >= 2


def test_without_injection_or_walk_the_particles_do_collapse(swaths):
    params = _frozen(inject_fraction=0.0, init_sigma_m=0.3, n_particles=20, weight_floor=0.0)
    tracker = SonarParticleFilter(params)
    tracker.reset(swaths.info(), np.random.default_rng(0), start_at(1.0))
    assert np.unique(tracker.particles).size > 1
    for k in range(3):
        tracker.step(Frame(k, swaths.make(1.0, seed=k)))
    assert np.unique(tracker.particles).size == 1


def test_coasts_through_pings_without_returns(swaths):
    frames = swaths.track([1.0] * 5, noise=0.01)
    tracker = SonarParticleFilter()
    run(tracker, swaths.info(), frames)
    before = tracker.weights.copy()
    nothing = Swath(np.full(240, np.nan), np.full(240, np.nan))
    coasting = [tracker.step(Frame(5 + k, nothing)) for k in range(3)]
    assert all(isinstance(e, PipeEstimate) and abs(e.across_m - 1.0) < 0.1 for e in coasting)
    assert np.array_equal(tracker.weights, before)
    assert tracker.last_scan.peak() is None


def test_without_a_start_it_reports_nothing_until_a_swath_has_returns(swaths):
    tracker = SonarParticleFilter()
    tracker.reset(swaths.info(), np.random.default_rng(0), None)
    nothing = Swath(np.full(240, np.nan), np.full(240, np.nan))
    assert tracker.step(Frame(0, nothing)) is None
    assert tracker.particles is None
    assert isinstance(tracker.step(Frame(1, swaths.make(3.0))), PipeEstimate)
    states = tracker.particles
    assert states.min() > -20.0 and states.max() < 20.0 and np.ptp(states) > 10.0


def test_an_observation_that_is_not_a_swath_is_a_data_error_naming_the_frame(swaths):
    tracker = SonarParticleFilter()
    tracker.reset(swaths.info(), np.random.default_rng(0), None)
    with pytest.raises(DataError, match="sonar_pf: frame 7: observation is a ndarray, expected a Swath"):
        tracker.step(Frame(7, np.zeros((240, 2))))


def test_the_walk_scales_with_the_ping_interval_unless_given_per_ping(swaths):
    params = ParticleFilterParams()
    assert walk_sigma(params, swaths.info(), "t") == pytest.approx(params.walk_speed_mps * 0.3)
    fixed = dataclasses.replace(params, walk_sigma_m=0.25)
    no_interval = SequenceInfo("sonar/x", "sonar", None, None, None, swaths.calibration())
    assert walk_sigma(fixed, no_interval, "t") == 0.25
    with pytest.raises(DataError, match="sonar_pf: sequence 'sonar/x' has no ping interval.*walk_sigma_m"):
        SonarParticleFilter().reset(no_interval, np.random.default_rng(0))


def test_scan_weights_are_the_sharpened_scan_with_a_relative_floor():
    scan = LikelihoodScan(np.array([0.0, 1.0, 2.0]), np.array([0.0, 2.0, 1.0]))
    states = np.array([[0.0], [1.0], [2.0], [9.0]])
    weights = ScanWeights(0.1, 2.0).likelihood(states, scan)
    assert np.allclose(weights, [0.4, 4.0, 1.0, 0.4])
    assert np.all(ScanWeights(0.1, 2.0).likelihood(states, LikelihoodScan.empty()) == 0.0)


@pytest.mark.parametrize(
    ("name", "value"),
    [
        ("n_particles", 0),
        ("inject_fraction", 1.5),
        ("walk_speed_mps", -1.0),
        ("weight_exponent", 0.0),
        ("weight_floor", math.inf),
        ("resampler", "bogus"),
        ("grid_m", 0.0),
    ],
)
def test_bad_parameters_name_the_tracker_and_the_parameter(name, value):
    with pytest.raises(ParameterError, match=rf"tracker 'sonar_pf'.*'{name}'"):
        SonarParticleFilter.make_params({name: value})
    with pytest.raises(pydantic.ValidationError, match=name):
        dataclasses.replace(ParticleFilterParams(), **{name: value})


def test_resampler_choices_are_the_filters_resamplers():
    assert set(typing.get_args(ResamplerName)) == set(RESAMPLERS)


def test_the_filter_ignores_decoys_that_fool_the_detector(swaths):
    # One ping in five loses the pipe's returns and shows a pipe-like object 6 m away instead.
    positions = 1.0 + 0.5 * np.sin(np.arange(50) / 10.0)
    frames = swaths.track(positions, noise=0.02, missing=0.05)
    frames = [
        dataclasses.replace(frame, observation=swaths.make(x + 6.0, noise=0.02, seed=k)) if k % 5 == 4 else frame
        for k, (frame, x) in enumerate(zip(frames, positions))
    ]
    info = swaths.info()

    def errors(estimates):
        return np.abs(np.array([np.nan if e is None else e.across_m for e in estimates]) - positions)

    detector, tracker = errors(run(SonarDetector(), info, frames)), errors(run(SonarParticleFilter(), info, frames))
    assert np.all(detector[4::5] > 5.0)
    assert np.all(tracker <= 0.2)
    assert np.sqrt(np.mean(tracker**2)) < np.sqrt(np.mean(detector**2))


def drift_track(speed_mps: float, interval_s: float = 0.3, n: int = 50, amplitude_m: float = 5.0) -> np.ndarray:
    """Across-track positions of a pipe swinging 5 m either side of nadir, at ``speed_mps`` at its fastest."""
    return amplitude_m * np.sin(speed_mps * interval_s * np.arange(n) / amplitude_m)


def test_keeps_up_with_a_pipe_drifting_three_times_faster_than_its_walk(swaths):
    positions = drift_track(1.2)
    frames = swaths.track(positions, noise=0.01, missing=0.02)
    estimates = np.array([e.across_m for e in run(SonarParticleFilter(), swaths.info(), frames)])
    tolerance = np.array([f.truth.resolution_m for f in frames])
    assert np.mean(np.abs(estimates - positions) <= tolerance) >= 0.9
    # The walk alone, tuned for 0.4 m/s, falls behind.
    lagging = SonarParticleFilter(SonarParticleFilter.make_params({"drift_gain": 0.0}))
    behind = np.array([e.across_m for e in run(lagging, swaths.info(), frames)])
    assert np.mean(np.abs(behind - positions) <= tolerance) < 0.5


def test_the_rate_is_smoothed_from_the_estimates_and_forgets_jumps():
    rate = AcrossTrackRate(0.5, limit_m=0.3, last_m=0.0)
    rate.update(0.2)
    assert rate.rate_m == pytest.approx(0.1)
    rate.update(0.4)
    assert rate.rate_m == pytest.approx(0.15)
    rate.update(10.0)  # faster than any drift: a jump to another peak
    assert rate.rate_m == 0.0 and rate.last_m == 10.0
    rate.update(10.2)
    assert rate.rate_m == pytest.approx(0.1)
    rate.update(10.4, trusted=False)  # the filter is lost
    assert rate.rate_m == 0.0
    still = AcrossTrackRate(0.0, last_m=0.0)
    still.update(0.1)
    assert still.rate_m == 0.0 and still.last_m == 0.1


@settings(max_examples=60, deadline=None)
@given(
    values=arrays(float, st.integers(2, 40), elements=st.floats(0.0, 1e4)),
    positions=arrays(float, st.integers(1, 30), elements=st.floats(-5.0, 50.0)),
    fraction=st.floats(0.0, 1.0),
    lost_ratio=st.just(0.0) | st.floats(1e-3, 1.0),
)
def test_the_injection_rate_lies_between_none_and_j(values, positions, fraction, lost_ratio):
    scan = LikelihoodScan(np.arange(values.size, dtype=float), values)
    if scan.is_empty:
        return

    def rate_at(where: np.ndarray) -> float:
        return injection_rate(fraction, lost_ratio, scan, float(scan.at(where).max(initial=0.0)))

    rate = rate_at(positions)
    assert 0.0 <= rate <= fraction
    if lost_ratio == 0.0:
        assert rate == fraction
    best = float(scan.positions[int(np.argmax(scan.values))])
    assert rate_at(np.append(positions, best)) == (fraction if lost_ratio == 0.0 else 0.0)
    assert rate_at(np.array([1e6])) == fraction


@settings(max_examples=200, deadline=None)
@given(
    values=arrays(float, st.integers(1, 20), elements=st.floats(0.0, 1e6) | st.floats(1e-300, 1e-280)),
    lost_ratio=st.floats(0.0, 2.0) | st.floats(1e-300, 1e-10) | st.just(math.inf),
    shift=st.integers(-8, 8).map(lambda ulps: ulps * 2.0**-52) | st.floats(-1e-6, 1e-6),
    fraction=st.floats(0.0, 1.0),
)
def test_the_rate_decided_without_the_best_is_the_formula_s(values, lost_ratio, shift, fraction):
    """Where :func:`nothing_lost` answers without the scan's best, the rate is the formula's, to the last bit."""
    scan = LikelihoodScan(np.arange(values.size, dtype=float), values)
    best = scan.maximum()
    threshold = lost_ratio * best
    # The particles' best about the boundary ``lost_ratio * best``: a few ulps or a relative 1e-6 either side.
    here = min(threshold * (1.0 + shift), best) if math.isfinite(threshold) else best
    if not here > 0.0:
        return
    formula = fraction * max(0.0, 1.0 - here / threshold) if threshold > 0.0 else fraction
    assert injection_rate(fraction, lost_ratio, scan, here) == formula
    assert not nothing_lost(lost_ratio, here, scan) or formula == 0.0


def test_step_before_reset_is_an_error(swaths):
    with pytest.raises(RuntimeError, match="reset"):
        SonarParticleFilter().step(Frame(0, swaths.make(0.0)))
