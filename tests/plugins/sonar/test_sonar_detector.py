"""The ``sonar_detector`` baseline and the detection set-up it shares with ``sonar_pf`` (seeds/003, section 2)."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pydantic
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from trackbench_sonar import SonarDetector
from trackbench_sonar.detection import SwathDetector
from trackbench_sonar.evidence import FootprintLikelihood, WidestEvidence
from trackbench_sonar.likelihood import PipeLikelihood
from trackbench_sonar.params import DetectorParams

from benchmark.errors import DataError, ParameterError
from benchmark.modalities.sonar.model import PipeEstimate, Swath
from benchmark.model import Frame, SequenceInfo


def detector(swaths, **overrides) -> SonarDetector:
    tracker = SonarDetector(SonarDetector.make_params(overrides))
    tracker.reset(swaths.info(), np.random.default_rng(0))
    return tracker


@pytest.mark.parametrize("x", [-9.0, -2.5, 0.0, 4.0, 11.0])
def test_reports_the_pipe_of_each_ping(swaths, x):
    tracker = detector(swaths)
    estimate = tracker.step(Frame(0, swaths.make(x, noise=0.01, slope=0.05, missing=0.02, spikes=2, seed=7)))
    assert isinstance(estimate, PipeEstimate)
    assert abs(estimate.across_m - x) <= swaths.spacing_at(x, 10.0)
    assert estimate.across_m == tracker.last_scan.peak(refine=True)
    assert abs(estimate.across_m - tracker.last_scan.peak()) <= 0.5 * tracker.detector.grid_m


def test_as_printed_it_reports_the_grid_point_of_the_maximum(swaths):
    tracker = detector(swaths, likelihood="ellipse", refine_peak=False)
    estimate = tracker.step(Frame(0, swaths.make(1.3, noise=0.01, seed=7)))
    assert estimate.across_m == tracker.last_scan.peak()
    assert abs(estimate.across_m - 1.3) <= swaths.spacing_at(1.3, 10.0)


def test_each_ping_on_its_own(swaths):
    tracker = detector(swaths)
    first = tracker.step(Frame(0, swaths.make(-6.0, seed=1)))
    second = tracker.step(Frame(1, swaths.make(5.0, seed=2)))
    assert first.across_m == pytest.approx(-6.0, abs=0.15)
    assert second.across_m == pytest.approx(5.0, abs=0.15)


def test_a_ping_without_returns_is_a_missed_detection(swaths):
    tracker = detector(swaths)
    nothing = Swath(np.full(240, np.nan), np.full(240, np.nan))
    assert tracker.step(Frame(3, nothing)) is None
    few = Swath(np.array([0.0, 0.1, np.nan]), np.array([10.0, 10.0, np.nan]))
    assert tracker.step(Frame(4, few)) is None


@pytest.mark.parametrize(
    "observation",
    [np.zeros((240, 2)), None, (np.zeros(240), np.zeros(240)), "swath"],
    ids=["array", "none", "tuple", "str"],
)
def test_an_observation_that_is_not_a_swath_is_a_data_error_naming_the_frame(swaths, observation):
    tracker = detector(swaths)
    with pytest.raises(DataError, match=r"sonar_detector: frame 12: observation is a \w+, expected a Swath"):
        tracker.step(Frame(12, observation))


def test_a_swath_spanning_kilometres_is_a_data_error_naming_the_frame(swaths):
    tracker = detector(swaths)
    with pytest.raises(DataError, match="sonar_detector: frame 5: .*across track"):
        tracker.step(Frame(5, Swath(np.linspace(-5e4, 5e4, 240), np.full(240, 10.0))))


@settings(max_examples=40, deadline=None)
@given(
    st.lists(st.one_of(st.floats(allow_nan=True, allow_infinity=True), st.just(math.nan)), min_size=0, max_size=40),
    st.lists(st.one_of(st.floats(allow_nan=True, allow_infinity=True), st.just(math.nan)), min_size=40, max_size=40),
)
def test_any_swath_gives_an_estimate_none_or_a_data_error(swaths, across, depth):
    tracker = detector(swaths)
    try:
        estimate = tracker.step(Frame(0, Swath(np.array(across, dtype=float), np.array(depth[: len(across)]))))
    except DataError as exc:
        assert "frame 0" in str(exc)
        return
    assert estimate is None or math.isfinite(estimate.across_m)


def test_the_calibration_supplies_the_pipe_and_the_parameters_may_override_it(swaths):
    info = swaths.info(diameter=0.9, noise=0.05)
    default = SwathDetector.for_sequence(DetectorParams(), info, "t")
    assert isinstance(default.likelihood, WidestEvidence)
    assert default.likelihood.section.major_m == 0.9 and default.likelihood.section.minor_m == 0.9
    # No beam width in the calibration: each ping tries beams 1, 2 and 4 spacings wide.
    spacing = info.calibration.beam_spacing
    assert [model.beam_width for model in default.likelihood.models] == pytest.approx([spacing, 2 * spacing, 4 * spacing])
    assert [model.sigma_m for model in default.likelihood.models] == pytest.approx([math.hypot(0.05, 0.01)] * 3)
    assert default.spike_m == pytest.approx(0.9)
    assert default.grid_m == pytest.approx(0.05)
    oblique = SwathDetector.for_sequence(DetectorParams(major_axis_m=1.3, likelihood="ellipse"), info, "t")
    assert isinstance(oblique.likelihood, PipeLikelihood)
    assert oblique.likelihood.section.major_m == 1.3 and oblique.likelihood.section.minor_m == 0.9
    assert oblique.likelihood.flank_m == pytest.approx(1.3)
    assert oblique.likelihood.beam_angle == pytest.approx(info.calibration.beam_spacing)


def test_the_beam_width_comes_from_the_parameter_else_the_calibration_else_the_spacing(swaths):
    wide = dataclasses.replace(swaths.calibration(), beam_width=math.radians(2.0))
    info = SequenceInfo("sonar/wide", "sonar", None, None, 0.3, wide)
    assert SwathDetector.for_sequence(DetectorParams(), info, "t").likelihood.beam_width == pytest.approx(
        math.radians(2.0)
    )
    given = SwathDetector.for_sequence(DetectorParams(beam_width_deg=0.7), info, "t")
    assert given.likelihood.beam_width == pytest.approx(math.radians(0.7))
    unknown = SwathDetector.for_sequence(DetectorParams(unknown_width_spacings=(3.0,)), swaths.info(), "t")
    assert unknown.likelihood.beam_width == pytest.approx(3.0 * swaths.info().calibration.beam_spacing)


def test_the_grid_is_at_most_a_tenth_of_the_pipe(swaths):
    small = SwathDetector.for_sequence(DetectorParams(), swaths.info(diameter=0.3), "t")
    assert small.grid_m == pytest.approx(0.03)


def test_a_sequence_without_a_pipe_diameter_is_a_data_error_unless_the_axes_are_given():
    info = SequenceInfo("sonar/bare", "sonar", 10, None, 0.3, None)
    with pytest.raises(DataError, match="sonar_detector: sequence 'sonar/bare'.*major_axis_m"):
        SonarDetector().reset(info, np.random.default_rng(0))
    tracker = SonarDetector(SonarDetector.make_params({"major_axis_m": "0.6", "minor_axis_m": "0.6"}))
    tracker.reset(info, np.random.default_rng(0))
    assert tracker.detector.likelihood.beam_width == 0.0
    paper = SonarDetector(SonarDetector.make_params({"major_axis_m": 0.6, "minor_axis_m": 0.6, "likelihood": "ellipse"}))
    paper.reset(info, np.random.default_rng(0))
    assert paper.detector.likelihood.min_pipe_returns == 2.0 and paper.detector.likelihood.beam_angle == 0.0


@pytest.mark.parametrize(
    ("name", "value"),
    [
        ("grid_m", 0.0),
        ("grid_m", -1.0),
        ("fit_span", 1.5),
        ("proud_weight", -1.0),
        ("min_beams", -1),
        ("spike_window", 2.5),
        ("flank_widths", math.inf),
        ("likelihood", "circle"),
        ("beam_width_deg", -1.0),
        ("seabed_widths", 0.0),
        ("relief_widths", math.nan),
        ("robust_sigmas", -2.0),
        ("unknown_width_spacings", ()),
    ],
)
def test_bad_parameters_name_the_tracker_and_the_parameter(name, value):
    with pytest.raises(ParameterError, match=rf"tracker 'sonar_detector'.*'{name}'"):
        SonarDetector.make_params({name: value})
    with pytest.raises(pydantic.ValidationError, match=name):
        dataclasses.replace(DetectorParams(), **{name: value})


def test_a_negative_width_to_try_is_refused_naming_it():
    with pytest.raises(ParameterError, match=r"'unknown_width_spacings.1': Input should be greater than 0"):
        SonarDetector.make_params({"unknown_width_spacings": (1.0, -2.0)})


def test_step_before_reset_is_an_error(swaths):
    with pytest.raises(RuntimeError, match="reset"):
        SonarDetector().step(Frame(0, swaths.make(0.0)))
