"""The likelihood of eq. (1) over across-track position (seeds/003, section 2, Fig. 2)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays
from trackbench_sonar.cross_section import CrossSection
from trackbench_sonar.likelihood import LikelihoodScan, PipeLikelihood
from trackbench_sonar.profile import resample_swath

from benchmark.modalities.sonar.model import Swath, beam_footprint

BEAM_240 = math.radians(120.0) / 239


def likelihood(
    diameter: float = 0.6, sigma: float = 0.02, weight: float = 1.0, beam_angle: float = BEAM_240, returns: float = 2.0
) -> PipeLikelihood:
    return PipeLikelihood(CrossSection(diameter, diameter), sigma, weight, diameter, 0.8, beam_angle, returns)


def scan_of(swath: Swath, diameter: float = 0.6, **kwargs) -> LikelihoodScan:
    return likelihood(diameter, **kwargs).scan(resample_swath(swath, 0.05, spike_m=0.5 * diameter))


def check_scan(scan: LikelihoodScan) -> None:
    assert scan.positions.shape == scan.values.shape
    assert np.all(np.isfinite(scan.values)) and np.all(scan.values >= 0.0)


ANALYTIC_SWATHS = st.fixed_dictionaries(
    {
        "pipe_at": st.none() | st.floats(-15.0, 15.0),
        "slope": st.floats(-0.2, 0.2),
        "noise": st.floats(0.0, 0.3),
        "missing": st.floats(0.0, 1.0),
        "spikes": st.integers(0, 10),
        "second_at": st.none() | st.floats(-15.0, 15.0),
        "seed": st.integers(0, 2**16),
    }
)


@settings(max_examples=60, deadline=None)
@given(ANALYTIC_SWATHS)
def test_scan_is_finite_and_non_negative_for_any_analytic_swath(swaths, args):
    args = dict(args)
    swath = swaths.make(args.pop("pipe_at"), **args)
    scan = scan_of(swath)
    check_scan(scan)
    probe = np.concatenate([np.linspace(-40.0, 40.0, 33), [math.nan, math.inf]])
    values = scan.at(probe)
    assert np.all(np.isfinite(values)) and np.all(values >= 0.0)


@settings(max_examples=60, deadline=None)
@given(
    arrays(float, st.integers(0, 80), elements=st.floats(-30, 30) | st.just(math.nan)),
    arrays(float, 80, elements=st.floats(0.0, 60.0) | st.just(math.nan)),
)
def test_scan_is_finite_and_non_negative_for_arbitrary_returns(across, depth):
    check_scan(scan_of(Swath(across, depth[: across.size])))


@settings(max_examples=40, deadline=None)
@given(
    x=st.floats(-12.0, 12.0),
    slope=st.floats(-0.1, 0.1),
    diameter=st.floats(0.5, 1.2),
    noise=st.floats(0.0, 0.02),
    altitude=st.floats(8.0, 15.0),
    n_beams=st.sampled_from([111, 240]),
    seed=st.integers(0, 2**16),
)
def test_the_maximum_is_near_the_pipe(swaths, x, slope, diameter, noise, altitude, n_beams, seed):
    # Where the sonar resolves the pipe (three beam intervals or more across it) and sees the
    # seabed beyond it (a pipe at the swath's edge hides the last beams' seabed).
    assume(swaths.spacing_at(x, altitude, n_beams) <= diameter / 3.0)
    assume(abs(x) + diameter <= altitude * math.tan(math.radians(50.0)))
    shape = {"slope": slope, "diameter": diameter, "altitude": altitude, "n_beams": n_beams}
    swath = swaths.make(x, noise=noise, seed=seed, **shape)
    beam_angle = math.radians(120.0) / (n_beams - 1)
    scan = scan_of(swath, diameter, sigma=math.hypot(noise, 0.01), beam_angle=beam_angle)
    assert abs(scan.peak() - x) <= 2.0 * swaths.spacing_at(x, altitude, n_beams)


def test_a_proud_pipe_scores_above_a_buried_one_and_above_bare_seabed(swaths):
    proud = scan_of(swaths.make(2.0, noise=0.01, seed=1))
    half = scan_of(swaths.make(2.0, noise=0.01, seed=1, burial=0.5))
    bare = scan_of(swaths.make(None, noise=0.01, seed=1))
    assert proud.values.max() > half.values.max() > bare.values.max()
    # A circle on the seabed itself has L2 = 0: only the fit term is left.
    assert bare.values.max() <= 1.0 + 1e-12


def test_both_terms_are_in_the_unit_interval_and_the_proud_pipe_reaches_two(swaths):
    model = likelihood(returns=0.0)
    profile = resample_swath(swaths.make(-3.0, seed=2), 0.05)
    found = model.candidates(profile)
    scored = np.isfinite(found.across_m)
    assert np.all((0.0 <= found.fit) & (found.fit <= 1.0))
    assert np.all((0.0 <= found.proud) & (found.proud <= 1.0))
    assert np.allclose(found.value, found.fit + found.proud)
    best = int(np.argmax(found.value))
    assert found.value[best] > 1.9
    assert found.across_m[best] == pytest.approx(-3.0, abs=0.05)
    assert found.depth_m[best] == pytest.approx(10.0 - 0.3, abs=0.05)
    assert scored.sum() < found.value.size  # candidates whose span leaves the profile are not scored


def test_no_candidate_is_scored_where_the_beams_are_too_sparse_for_the_pipe(swaths):
    profile = resample_swath(swaths.make(None, altitude=10.0, seed=1), 0.05)
    found = likelihood(returns=2.0).candidates(profile)
    everywhere = likelihood(returns=0.0).candidates(profile)
    possible = np.isfinite(everywhere.across_m)
    footprint = np.full(possible.shape, np.inf)
    footprint[possible] = beam_footprint(everywhere.across_m[possible], everywhere.depth_m[possible], BEAM_240)
    # Two intervals between beams across the 0.6 m pipe: beams at most 0.3 m apart, some 15 m out.
    assert np.array_equal(np.isfinite(found.across_m), possible & (footprint <= 0.3))
    assert np.any(possible & (footprint > 0.3)) and np.any(footprint <= 0.3)
    assert 14.0 < np.nanmax(np.abs(found.across_m)) < 16.0


def test_the_weight_on_l2_scales_only_the_proud_term(swaths):
    profile = resample_swath(swaths.make(1.0, noise=0.01, seed=3), 0.05)
    plain = likelihood(weight=1.0).candidates(profile)
    heavy = likelihood(weight=3.0).candidates(profile)
    assert np.allclose(heavy.value - plain.value, 2.0 * plain.proud)


def test_the_two_pipes_of_a_swath_both_stand_out(swaths):
    scan = scan_of(swaths.make(-4.0, second_at=3.0, noise=0.01, seed=5))
    top = scan.values.max()
    near = lambda x: scan.values[np.abs(scan.positions - x) <= 0.1].max()  # noqa: E731
    assert near(-4.0) > 0.8 * top and near(3.0) > 0.8 * top
    assert np.median(scan.values) < 0.3 * top


def test_scan_reading_is_linear_inside_and_zero_outside():
    scan = LikelihoodScan(np.array([0.0, 1.0, 2.0]), np.array([0.0, 2.0, 1.0]))
    assert np.allclose(scan.at(np.array([-0.5, 0.5, 1.5, 2.0, 2.5])), [0.0, 1.0, 1.5, 1.0, 0.0])
    assert scan.peak() == 1.0


def test_an_empty_or_zero_scan_has_no_peak():
    assert LikelihoodScan.empty().peak() is None
    assert LikelihoodScan.empty().at(np.array([0.0, 1.0])).tolist() == [0.0, 0.0]
    assert LikelihoodScan(np.array([0.0, 1.0]), np.zeros(2)).peak() is None


def test_too_short_a_profile_gives_no_candidates(swaths):
    model = likelihood(diameter=1.2)
    profile = resample_swath(Swath(np.linspace(0.0, 0.5, 11), np.full(11, 10.0)), 0.05)
    assert not profile.is_empty
    scan = model.scan(profile)
    assert scan.peak() is None and np.all(scan.values == 0.0)


@pytest.mark.parametrize(
    ("field", "value"),
    [
        ("sigma_m", 0.0),
        ("proud_weight", -1.0),
        ("flank_m", 0.0),
        ("sigma_m", math.nan),
        ("fit_span", 0.0),
        ("fit_span", 1.5),
        ("beam_angle", -0.1),
        ("min_pipe_returns", math.inf),
    ],
)
def test_bad_settings_are_rejected(field, value):
    settings_ = {"section": CrossSection(0.6, 0.6), "sigma_m": 0.03, "proud_weight": 1.0, "flank_m": 0.6}
    settings_ |= {"fit_span": 0.8, "beam_angle": 0.01, "min_pipe_returns": 2.0}
    settings_[field] = value
    with pytest.raises(ValueError, match=field):
        PipeLikelihood(**settings_)
